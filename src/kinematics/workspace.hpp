// The step engine (Pinocchio's Model/Data split): a KinematicsWorkspace is built
// once per model and row selection and holds everything a step reuses — the
// factorizations, the p-version Jacobian, right-hand-side buffers — so that the
// step loop allocates nothing. Free functions do the work on it: the position
// solve, the derivative orders (constraints.md §1.6: Φ_q q^(k) = RHS_k with one
// factorization) and the transpose solve Φ_qᵀ x = b.
#pragma once

#include <Eigen/SparseLU>
#include <array>
#include <memory>
#include <vector>

#include "kinematics/block_solver.hpp"
#include "kinematics/newton.hpp"

namespace mechkin {

enum class PositionSolver { Newton, Ceres };

struct WorkspaceOptions {
  Formulation formulation = Formulation::Omega;
  PositionSolver solver = PositionSolver::Newton;
  bool ceres_normalization_residual = false;  // Ceres: pᵀp − 1 residuals instead of the manifold
  int order = 3;                               // highest derivative order solved
  /// Bodies the caller reads; empty = all. A strict subset switches to the
  /// block-by-block path when it skips blocks (own Newton, ω' formulation only).
  std::vector<int> needed_bodies;
};

class KinematicsWorkspace {
 public:
  /// `active`: the 6n independent rows (redundant equations set aside).
  KinematicsWorkspace(const ConstraintSystem& sys, std::vector<int> active, const WorkspaceOptions& options);

  const ConstraintSystem& system() const { return sys_; }
  const std::vector<int>& active() const { return active_; }
  const WorkspaceOptions& options() const { return options_; }
  NewtonSolver& newton() { return newton_; }
  /// The factorization the step uses: the block solver on the block path, else Newton's LU.
  Factorization& factorization() { return block_solver_ ? static_cast<Factorization&>(*block_solver_) : newton_; }
  BlockSolver* block_solver() { return block_solver_.get(); }
  int blocks() const { return blocks_; }
  int blocks_solved() const { return blocks_solved_; }
  /// Whether the solves move body `b` (false only for bodies of blocks the block
  /// path skips: their poses stay at the design and their equations go unchecked).
  bool SolvesBody(int b) const { return skipped_body_.empty() || !skipped_body_[b]; }

 private:
  friend void SolveDerivatives(KinematicsWorkspace& ws, int order, SystemState* s);
  friend SolveSummary SolvePosition(KinematicsWorkspace& ws, const SolveOptions& options, SystemState* s, bool reuse);
  void SetUpBlockPath(const BlockStructure& structure);
  void SolveOrderOmega(int k, SystemState* s);
  void SolveOrderP(int k, SystemState* s);

  const ConstraintSystem& sys_;
  std::vector<int> active_;
  WorkspaceOptions options_;
  NewtonSolver newton_;
  std::unique_ptr<BlockSolver> block_solver_;
  int blocks_ = 0, blocks_solved_ = 0;
  std::vector<char> skipped_body_;  // per body, on the block path only
  std::unique_ptr<SparseJacobian> jac_p_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_p_;
  Eigen::VectorXd rhs_full_, rhs_, x_;
  std::vector<std::array<Vec4, kMaxOrder + 1>> pd_;  // p version: Euler parameter derivatives per body
};

/// Those of `rows` whose bodies the workspace's solves move (KinematicsWorkspace::SolvesBody).
std::vector<int> RowsOnSolvedBodies(const KinematicsWorkspace& ws, const std::vector<int>& rows);

/// Φ(q, t) = 0 from the state's current pose (driver values evaluated at t), then
/// factorizes Φ_q at the solution. `reuse`: modified Newton with the held factors.
SolveSummary SolvePosition(KinematicsWorkspace& ws, const SolveOptions& options, SystemState* s, bool reuse);
/// Up to two more Newton iterations from a solved pose toward the scaled residual
/// `target` (stopping at round-off), then a fresh factorization at the final pose:
/// for when the residual met its tolerance but the derivatives' error bound
/// (κ²·r, analysis/error_bounds.hpp) does not. Full-system Newton path only; elsewhere a no-op
/// (returns success = false).
SolveSummary PolishPosition(KinematicsWorkspace& ws, double target, SystemState* s);
/// Velocity … up to `order` at the current (factorized) pose, one back-solve per order.
void SolveDerivatives(KinematicsWorkspace& ws, int order, SystemState* s);
/// Φ_qᵀ x = b over the active rows with the step's factorization.
bool SolveTranspose(KinematicsWorkspace& ws, const Eigen::VectorXd& b, Eigen::VectorXd* x);
/// Taylor predictor: moves every body by dt along its r and p series up to `order`.
void PredictPose(double dt, int order, SystemState* s);

}  // namespace mechkin
