#include "kinematics/workspace.hpp"

#include <algorithm>

#include "kinematics/ceres_position.hpp"

namespace mechkin {

KinematicsWorkspace::KinematicsWorkspace(const ConstraintSystem& sys, std::vector<int> active,
                                         const WorkspaceOptions& options)
    : sys_(sys), active_(std::move(active)), options_(options), newton_(sys, active_) {
  const int n = sys.num_bodies();
  BlockStructure structure;
  if (FindBlockStructure(newton_.jacobian(), &structure)) {
    blocks_ = blocks_solved_ = structure.size();
    SetUpBlockPath(structure);
  }
  if (options.formulation == Formulation::P && options.order > 0) {
    jac_p_ = std::make_unique<SparseJacobian>(sys, Formulation::P, active_);
    lu_p_.analyzePattern(jac_p_->matrix());
  }
  rhs_.resize(active_.size() + (jac_p_ ? n : 0));
  pd_.resize(n);
}

// Block by block only when the selection skips blocks: for a full run one LU of
// the whole Φ_q is faster (slider-crank: 3.5 µs per step against 5.8 µs in two
// blocks) and is what the singular-position location uses.
void KinematicsWorkspace::SetUpBlockPath(const BlockStructure& structure) {
  if (options_.needed_bodies.empty() || options_.formulation != Formulation::Omega ||
      options_.solver != PositionSolver::Newton)
    return;
  std::vector<int> cols;
  for (int b : options_.needed_bodies)
    for (int q = 0; q < 6 && b >= 0; ++q) cols.push_back(6 * b + q);
  const std::vector<char> needed = NeededBlocks(structure, cols);
  const int count = static_cast<int>(std::count(needed.begin(), needed.end(), 1));
  if (count == structure.size()) return;
  block_solver_ = std::make_unique<BlockSolver>(sys_, active_, structure, needed);
  blocks_solved_ = count;
  skipped_body_.assign(sys_.num_bodies(), 0);
  for (int b = 0; b < structure.size(); ++b)
    if (!needed[b])
      for (int c : structure.cols[b]) skipped_body_[c / 6] = 1;
}

std::vector<int> RowsOnSolvedBodies(const KinematicsWorkspace& ws, const std::vector<int>& rows) {
  const ConstraintSystem& sys = ws.system();
  std::vector<int> kept;
  for (int row : rows) {
    const Constraint& c = *sys.entries()[sys.Locate(row).first].constraint;
    bool solved = true;
    for (int side = 0; side < c.num_sides(); ++side) solved = solved && (c.body(side) == kGround || ws.SolvesBody(c.body(side)));
    if (solved) kept.push_back(row);
  }
  return kept;
}

SolveSummary SolvePosition(KinematicsWorkspace& ws, const SolveOptions& options, SystemState* s, bool reuse) {
  SolveSummary sum;
  if (ws.block_solver_) {
    sum = ws.block_solver_->Solve(options, s);
  } else if (ws.options_.solver == PositionSolver::Ceres) {
    sum = SolvePositionCeres(ws.sys_, ws.active_, options, s,
                             ws.options_.ceres_normalization_residual ? CeresUnitQuaternion::NormalizationResidual
                                                                      : CeresUnitQuaternion::Manifold);
  } else {
    sum = ws.newton_.Solve(options, s, reuse);
  }
  if (sum.success && !ws.factorization().Factorize(*s)) {
    sum.success = false;
    sum.message = "the constraint Jacobian is singular at the solution";
  }
  return sum;
}

// ω' version: RHS_k over the active rows, x = Φ_q⁻¹ RHS_k = (r^(k), ω'^(k−1)) per body.
void KinematicsWorkspace::SolveOrderOmega(int k, SystemState* s) {
  for (size_t r = 0; r < active_.size(); ++r) rhs_[r] = rhs_full_[active_[r]];
  newton_.BackSolve(rhs_, &x_);
  for (int b = 0; b < sys_.num_bodies(); ++b) {
    s->bodies[b].r[k] = x_.segment<3>(6 * b);
    s->bodies[b].w[k - 1] = x_.segment<3>(6 * b + 3);
  }
}

// p version: unknowns (r^(k), p^(k)) with the EUL rows; ω'^(k−1) from p^(k) (§1.3):
// ω' = 2Gṗ, ω̇' = 2Gp̈, ω̈' = 2Gp⃛ + 2G(ṗ)p̈, ω⃛' = 2Gp⁗ + 4G(ṗ)p⃛.
void KinematicsWorkspace::SolveOrderP(int k, SystemState* s) {
  const int n = sys_.num_bodies();
  for (size_t r = 0; r < active_.size(); ++r) rhs_[r] = rhs_full_[active_[r]];
  for (int b = 0; b < n; ++b) rhs_[active_.size() + b] = rhs_full_[sys_.num_rows() + b];
  x_ = lu_p_.solve(rhs_);
  for (int b = 0; b < n; ++b) {
    BodyKinematics& bk = s->bodies[b];
    auto& pd = pd_[b];
    bk.r[k] = x_.segment<3>(7 * b);
    pd[k] = x_.segment<4>(7 * b + 3);
    Vec3 w = 2 * CalcG(pd[0]) * pd[k];
    if (k == 3) w += 2 * CalcG(pd[1]) * pd[2];
    if (k == 4) w += 4 * CalcG(pd[1]) * pd[3];
    bk.w[k - 1] = w;
  }
}

void SolveDerivatives(KinematicsWorkspace& ws, int order, SystemState* s) {
  if (ws.block_solver_) {
    ws.block_solver_->Derivatives(order, s);
    return;
  }
  for (auto& b : s->bodies) {
    for (int k = 1; k <= kMaxOrder; ++k) b.r[k].setZero();
    for (int k = 0; k < kMaxOrder; ++k) b.w[k].setZero();
  }
  const bool p_version = ws.jac_p_ != nullptr;
  if (p_version && order > 0) {
    ws.jac_p_->Fill(ws.sys_, *s);
    ws.lu_p_.factorize(ws.jac_p_->matrix());
    for (int b = 0; b < ws.sys_.num_bodies(); ++b) ws.pd_[b][0] = s->bodies[b].p;
  }
  for (int k = 1; k <= order; ++k) {
    for (auto& b : s->bodies) b.PrepareOrder(k);
    CalcRhs(ws.sys_, *s, k, ws.options_.formulation, &ws.rhs_full_);
    if (p_version) ws.SolveOrderP(k, s);
    else ws.SolveOrderOmega(k, s);
  }
  for (auto& b : s->bodies) b.CompleteOrder(order);
}

bool SolveTranspose(KinematicsWorkspace& ws, const Eigen::VectorXd& b, Eigen::VectorXd* x) {
  return ws.factorization().SolveLinearTranspose(b, x);
}

void PredictPose(double dt, int order, SystemState* s) {
  static constexpr double kFact[] = {1, 1, 2, 6, 24};
  for (auto& b : s->bodies) {
    Vec4 pd[kMaxOrder + 1];
    b.CalcEulerDerivatives(order, pd);
    Vec3 r = b.r[0];
    Vec4 p = pd[0];
    double hk = 1;
    for (int k = 1; k <= order; ++k) {
      hk *= dt;
      r += hk / kFact[k] * b.r[k];
      p += hk / kFact[k] * pd[k];
    }
    b.r[0] = r;
    b.p = p.normalized();
    b.A = CalcA(b.p);
    b.AD[0] = b.AB[0] = b.A;
  }
}

}  // namespace mechkin
