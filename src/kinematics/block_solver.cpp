#include "kinematics/block_solver.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace mechkin {

BlockSolver::BlockSolver(const ConstraintSystem& sys, const std::vector<int>& active, const BlockStructure& bs,
                         std::vector<char> needed)
    : sys_(sys), col_pos_(6 * sys.num_bodies(), -1), xk_(Eigen::VectorXd::Zero(6 * sys.num_bodies())) {
  const Eigen::VectorXd scales = RowScales(sys, active);
  for (int k = 0; k < bs.size(); ++k) {
    if (!needed[k]) continue;
    Block b;
    std::set<int> entries, bodies, coupling;
    for (int pos : bs.rows[k]) {
      b.rows.push_back(active[pos]);
      b.scales.push_back(scales[pos]);
      b.entries.push_back(sys.Locate(active[pos]));
      entries.insert(b.entries.back().first);
    }
    b.cols = bs.cols[k];
    for (size_t i = 0; i < b.cols.size(); ++i) {
      col_pos_[b.cols[i]] = static_cast<int>(i);
      bodies.insert(b.cols[i] / 6);
    }
    for (int e : entries) {
      const Constraint& c = *sys.entries()[e].constraint;
      for (int side = 0; side < c.num_sides(); ++side)
        if (c.body(side) != kGround)
          for (int q = 0; q < 6; ++q) coupling.insert(6 * c.body(side) + q);
    }
    b.entry_list.assign(entries.begin(), entries.end());
    b.bodies.assign(bodies.begin(), bodies.end());
    b.coupling_cols.assign(coupling.begin(), coupling.end());
    const int nb = static_cast<int>(b.rows.size());
    b.J.setZero(nb, nb);
    b.coupling.setZero(nb, b.coupling_cols.size());
    b.rhs.resize(nb);
    b.x.resize(nb);
    b.cond_x = Eigen::VectorXd::Ones(nb).normalized();
    b.cond_y.resize(nb);
    b.cond_b.resize(nb);
    b.row_scale = Eigen::Map<const Eigen::VectorXd>(b.scales.data(), nb);
    b.col_scale.resize(nb);
    for (int i = 0; i < nb; ++i) b.col_scale[i] = b.cols[i] % 6 < 3 ? sys.model().characteristic_length : 1.0;
    blocks_.push_back(std::move(b));
  }
  solved_ = static_cast<int>(blocks_.size());
}

void BlockSolver::FillBlock(Block& b, const SystemState& s, bool with_coupling) {
  b.J.setZero();
  if (with_coupling) b.coupling.setZero();
  for (int e : b.entry_list) {
    const Constraint& c = *sys_.entries()[e].constraint;
    JacobianBlocks jb;
    c.CalcJacobian(MakeInput(sys_, s, e), &jb);
    for (size_t r = 0; r < b.rows.size(); ++r) {
      if (b.entries[r].first != e) continue;
      const int lr = b.entries[r].second;
      for (int side = 0; side < c.num_sides(); ++side) {
        const BodyIndex body = c.body(side);
        if (body == kGround) continue;
        for (int q = 0; q < 6; ++q) {
          const double v = q < 3 ? jb.R(side)(lr, q) : jb.Pi(side)(lr, q - 3);
          const int col = 6 * body + q;
          const int pos = col_pos_[col];
          if (pos >= 0 && std::binary_search(b.cols.begin(), b.cols.end(), col)) b.J(r, pos) = v;
          if (with_coupling) {
            const auto it = std::lower_bound(b.coupling_cols.begin(), b.coupling_cols.end(), col);
            b.coupling(r, it - b.coupling_cols.begin()) = v;
          }
        }
      }
    }
  }
}

double BlockSolver::BlockResidual(Block& b, const SystemState& s) {
  double worst = 0, phi[kMaxRows];
  for (int e : b.entry_list) {
    sys_.entries()[e].constraint->CalcPhi(MakeInput(sys_, s, e), phi);
    for (size_t r = 0; r < b.rows.size(); ++r)
      if (b.entries[r].first == e) {
        b.rhs[r] = -phi[b.entries[r].second];
        worst = std::max(worst, std::abs(phi[b.entries[r].second]) * b.scales[r]);
      }
  }
  return worst;
}

SolveSummary BlockSolver::Solve(const SolveOptions& options, SystemState* s) {
  SolveSummary sum;
  sum.success = true;
  sum.residual = 0;
  for (Block& b : blocks_) {
    double res = BlockResidual(b, *s);
    int it = 0;
    while (!(res <= options.tolerance)) {
      if (it >= options.max_iterations) {
        sum.success = false;
        sum.message = "Newton did not converge on a block in " + std::to_string(options.max_iterations) + " iterations";
        break;
      }
      FillBlock(b, *s, false);
      b.lu = b.J;
      if (!b.solver.Compute(&b.lu)) {
        sum.success = false;
        sum.message = "a diagonal block of the constraint Jacobian is singular";
        break;
      }
      b.solver.Solve(b.rhs, &b.x);
      // Apply the block's update to the bodies it owns.
      for (int body : b.bodies) {
        Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
        for (size_t i = 0; i < b.cols.size(); ++i)
          if (b.cols[i] / 6 == body) d[b.cols[i] % 6] = b.x[i];
        BodyKinematics& k = s->bodies[body];
        k.r[0] += d.head<3>();
        k.p = QuatRetractBody(k.p, d.tail<3>());
        k.A = CalcA(k.p);
        k.AD[0] = k.AB[0] = k.A;
      }
      ++it;
      res = BlockResidual(b, *s);
    }
    sum.iterations = std::max(sum.iterations, it);
    sum.residual = std::max(sum.residual, res);
    if (!sum.success) return sum;
  }
  sum.message = "converged";
  return sum;
}

bool BlockSolver::Factorize(const SystemState& s) {
  for (Block& b : blocks_) {
    FillBlock(b, s, true);
    b.lu = b.J;
    if (!b.solver.Compute(&b.lu)) return false;
  }
  return true;
}

void BlockSolver::Derivatives(int order, SystemState* s) {
  for (int body_index = 0; body_index < static_cast<int>(s->bodies.size()); ++body_index) {
    BodyKinematics& k = s->bodies[body_index];
    for (int o = 1; o <= kMaxOrder; ++o) k.r[o].setZero();
    for (int o = 0; o < kMaxOrder; ++o) k.w[o].setZero();
  }
  double rhs_entry[kMaxRows];
  for (int order_k = 1; order_k <= order; ++order_k) {
    for (auto& k : s->bodies) k.PrepareOrder(order_k);
    xk_.setZero();
    for (Block& b : blocks_) {
      for (int e : b.entry_list) {
        sys_.entries()[e].constraint->CalcRhs(MakeInput(sys_, *s, e), order_k, rhs_entry);
        for (size_t r = 0; r < b.rows.size(); ++r)
          if (b.entries[r].first == e) b.rhs[r] = rhs_entry[b.entries[r].second];
      }
      // Forward substitution: the columns of earlier blocks are known.
      for (size_t q = 0; q < b.coupling_cols.size(); ++q) {
        const int col = b.coupling_cols[q];
        if (std::binary_search(b.cols.begin(), b.cols.end(), col)) continue;
        b.rhs -= b.coupling.col(q) * xk_[col];
      }
      b.solver.Solve(b.rhs, &b.x);
      for (size_t i = 0; i < b.cols.size(); ++i) xk_[b.cols[i]] = b.x[i];
    }
    for (const Block& b : blocks_)
      for (int body : b.bodies) {
        s->bodies[body].r[order_k] = xk_.segment<3>(6 * body);
        s->bodies[body].w[order_k - 1] = xk_.segment<3>(6 * body + 3);
      }
  }
  for (auto& k : s->bodies) k.CompleteOrder(order);
}

double BlockSolver::Sign() {
  double sign = 1;
  for (const Block& b : blocks_) {
    sign *= b.solver.sign();
    for (int k = 0; k < b.lu.rows(); ++k) if (b.lu(k, k) < 0) sign = -sign;
  }
  return sign;
}

// As NewtonSolver::ConditionEstimate: κ of each dimensionless block W J_bb D.
double BlockSolver::ConditionEstimate() {
  double worst = 0;
  for (Block& b : blocks_) {
    b.cond_b = b.cond_x.cwiseQuotient(b.row_scale);
    b.solver.Solve(b.cond_b, &b.cond_y);
    b.cond_y.array() /= b.col_scale.array();
    const double inv = b.cond_y.norm();
    if (!(inv > 0) || !std::isfinite(inv)) return std::numeric_limits<double>::infinity();
    b.cond_x = b.cond_y / inv;
    const double norm = (b.row_scale.asDiagonal() * b.J * b.col_scale.asDiagonal()).norm();
    worst = std::max(worst, norm * inv);
  }
  last_condition_ = worst;
  return worst;
}

}  // namespace mechkin
