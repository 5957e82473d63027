#include "kinematics/position.hpp"

#include <cmath>

namespace mechkin {

std::vector<int> AllRows(const ConstraintSystem& sys) {
  std::vector<int> r(sys.num_rows());
  for (int k = 0; k < sys.num_rows(); ++k) r[k] = k;
  return r;
}

Eigen::VectorXd RowScales(const ConstraintSystem& sys, const std::vector<int>& rows) {
  const double L = sys.model().characteristic_length;
  Eigen::VectorXd w(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    const int pw = sys.entries()[sys.Locate(rows[k]).first].constraint->LengthPower();
    w[k] = std::pow(L, -pw);
  }
  return w;
}

double ScaledResidual(const Eigen::VectorXd& phi, const std::vector<int>& rows, const Eigen::VectorXd& scales) {
  double m = 0;
  for (size_t k = 0; k < rows.size(); ++k) {
    const double v = std::abs(phi[rows[k]]) * scales[k];
    if (!(v <= m)) m = v;  // NaN propagates as "not converged"
  }
  return m;
}

void ApplyStep(const Eigen::VectorXd& dq, SystemState* s) {
  for (size_t b = 0; b < s->bodies.size(); ++b) {
    BodyKinematics& k = s->bodies[b];
    k.r[0] += dq.segment<3>(6 * b);
    k.p = QuatRetractBody(k.p, dq.segment<3>(6 * b + 3));
    k.A = CalcA(k.p);
    k.AD[0] = k.A;
    k.AB[0] = k.A;
  }
}

Eigen::VectorXd DimensionlessColumnScales(const ConstraintSystem& sys) {
  Eigen::VectorXd c = Eigen::VectorXd::Ones(6 * sys.num_bodies());
  for (int b = 0; b < sys.num_bodies(); ++b) c.segment<3>(6 * b).setConstant(sys.model().characteristic_length);
  return c;
}

double DimensionlessNorm(const Eigen::SparseMatrix<double>& J, const Eigen::VectorXd& row_scales,
                         const Eigen::VectorXd& col_scales) {
  double sum = 0;
  for (int c = 0; c < J.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, c); it; ++it) {
      const double v = it.value() * row_scales[it.row()] * col_scales[c];
      sum += v * v;
    }
  return std::sqrt(sum);
}

Eigen::MatrixXd ScaledJacobian(const ConstraintSystem& sys, const SystemState& s) {
  Eigen::MatrixXd J;
  CalcJacobianDense(sys, s, Formulation::Omega, &J);
  const Eigen::VectorXd w = RowScales(sys, AllRows(sys));
  const double L = sys.model().characteristic_length;
  J = w.asDiagonal() * J;
  for (int b = 0; b < sys.num_bodies(); ++b) J.middleCols(6 * b, 3) *= L;
  return J;
}

SolveSummary DampedGaussNewton(const ConstraintSystem& sys, const std::vector<int>& rows, const SolveOptions& options,
                               const ScaledStep& step, SystemState* s) {
  SolveSummary sum;
  const double L = sys.model().characteristic_length;
  const Eigen::VectorXd w = RowScales(sys, rows);
  Eigen::VectorXd phi;
  CalcPhi(sys, *s, &phi);
  sum.residual = ScaledResidual(phi, rows, w);
  for (sum.iterations = 0; sum.iterations < options.max_iterations; ++sum.iterations) {
    if (sum.residual <= options.tolerance) break;
    Eigen::VectorXd rs(rows.size());
    for (size_t k = 0; k < rows.size(); ++k) rs[k] = phi[rows[k]] * w[k];
    Eigen::VectorXd dq = -step(*s, rs);
    for (int b = 0; b < sys.num_bodies(); ++b) dq.segment<3>(6 * b) *= L;
    // Backtracking on the scaled residual keeps rough starts on the nearby branch.
    const SystemState saved = *s;
    double alpha = 1.0, trial = 0;
    for (int ls = 0; ls < 12; ++ls, alpha *= 0.5) {
      *s = saved;
      ApplyStep(alpha * dq, s);
      CalcPhi(sys, *s, &phi);
      trial = ScaledResidual(phi, rows, w);
      if (trial < sum.residual) break;
    }
    if (!(trial < sum.residual)) {
      *s = saved;
      CalcPhi(sys, *s, &phi);
      sum.message = "no further decrease of the residual (stalled)";
      break;
    }
    sum.residual = trial;
  }
  // Keep the derived matrices consistent with the final pose.
  for (auto& b : s->bodies) b.UpdateDerived(0);
  sum.success = sum.residual <= options.tolerance;
  if (sum.success) sum.message = "assembled";
  else if (sum.message.empty()) sum.message = "did not converge in " + std::to_string(options.max_iterations) + " iterations";
  return sum;
}

SolveSummary AssembleMinNorm(const ConstraintSystem& sys, const std::vector<int>& rows, const SolveOptions& options,
                             SystemState* s) {
  const Eigen::VectorXd w = RowScales(sys, rows);
  const double L = sys.model().characteristic_length;
  auto dense_min_norm_step = [&](const SystemState& state, const Eigen::VectorXd& rs) {
    Eigen::MatrixXd J;
    CalcJacobianDense(sys, state, Formulation::Omega, &J);
    Eigen::MatrixXd Js(rows.size(), J.cols());
    for (size_t k = 0; k < rows.size(); ++k) Js.row(k) = J.row(rows[k]) * w[k];
    for (int b = 0; b < sys.num_bodies(); ++b) Js.middleCols(6 * b, 3) *= L;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(Js);
    cod.setThreshold(1e-10);
    return Eigen::VectorXd(cod.solve(rs));
  };
  return DampedGaussNewton(sys, rows, options, dense_min_norm_step, s);
}

std::vector<int> IndependentRows(const Eigen::MatrixXd& J, double rel_tol, std::vector<int>* dependent) {
  std::vector<int> kept;
  std::vector<Eigen::VectorXd> basis;
  for (int r = 0; r < J.rows(); ++r) {
    Eigen::VectorXd v = J.row(r).transpose();
    const double norm0 = v.norm();
    for (int pass = 0; pass < 2; ++pass)
      for (const auto& q : basis) v -= q.dot(v) * q;
    if (norm0 > 0 && v.norm() > rel_tol * norm0) {
      basis.push_back(v.normalized());
      kept.push_back(r);
    } else if (dependent) {
      dependent->push_back(r);
    }
  }
  return kept;
}

}  // namespace mechkin
