// Newton–Raphson position solve on the configuration manifold with an LU of Φ_q
// (ω' version): dense partial-pivoting LU up to 20 bodies (faster for small
// systems), else sparse LU with the symbolic analysis done once per row set.
//
// Modified Newton: Solve() first iterates with the factorization it already holds
// (normally Φ_q at the previous step's solution, which the derivative solves
// needed anyway) and refactorizes only when that stops contracting fast (the
// residual must drop by 10× per iteration). With the Taylor predictor one
// back-solve usually suffices.
#pragma once

#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <memory>

#include "kinematics/factorization.hpp"
#include "math/small_lu.hpp"
#include "kinematics/position.hpp"

namespace mechkin {

class NewtonSolver : public Factorization {
 public:
  /// `rows`: the independent equations (redundant ones set aside); must be 6n of them.
  NewtonSolver(const ConstraintSystem& sys, std::vector<int> rows);

  /// Solves Φ(q, t) = 0 on the rows from the state's current pose (the predictor).
  /// Uses the held factorization first when `reuse` (modified Newton).
  /// Driver values must already be evaluated at t. On return the factorization is
  /// that of Φ_q at the final pose (also on failure, for diagnostics).
  SolveSummary Solve(const SolveOptions& options, SystemState* s, bool reuse = false);

  /// Factorizes Φ_q at the current pose (ω' version). Returns false if singular.
  bool Factorize(const SystemState& s) override;
  /// Solves Φ_q x = b with the current factorization (b, x over the active rows / 6n columns).
  void BackSolve(const Eigen::VectorXd& b, Eigen::VectorXd* x);
  bool SolveLinear(const Eigen::VectorXd& b, Eigen::VectorXd* x) override { BackSolve(b, x); return factorized_; }
  /// Φ_qᵀ x = b with the same factors (dense: SmallLU; sparse: SparseLU's transpose view).
  bool SolveLinearTranspose(const Eigen::VectorXd& b, Eigen::VectorXd* x) override;
  double Sign() override { return JacobianSign(); }

  /// Sign of det Φ_q of the current factorization (ω' columns). It flips exactly
  /// when the path crosses a singular position, which is how runs detect them.
  double JacobianSign();
  const std::vector<int>& rows() const { return rows_; }
  const Eigen::VectorXd& scales() const { return scales_; }
  const Eigen::SparseMatrix<double>& jacobian() const { return jac_.matrix(); }
  /// Cheap estimate of the condition number of the dimensionless Φ_q (Frobenius
  /// norm times an inverse-iteration estimate of the inverse's norm), from the
  /// current factorization: independent of the mechanism's size and units.
  double ConditionEstimate() override;
  double SharperConditionEstimate(int steps) override;

 private:
  void RefineToTarget(const SolveOptions& options, SystemState* s, SolveSummary* sum);
  void RefineExtended(SystemState* s, SolveSummary* sum);
  Real ExtendedResidual();

  const ConstraintSystem& sys_;
  std::vector<int> rows_;
  Eigen::VectorXd scales_;
  SparseJacobian jac_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  bool dense_ = false;
  Eigen::MatrixXd dense_J_;
  std::vector<int> dense_offset_;  // per nonzero of jac_ (storage order): its place in dense_J_
  SmallLU dense_lu_;
  bool factorized_ = false;
  Eigen::VectorXd phi_, rhs_, dq_, cond_x_, cond_y_, cond_b_, sharp_x_, sharp_y_, sharp_b_;
  double cond_norm_ = 0, cond_last_ = 0;  // ‖J_s‖_F and the estimate of the last ConditionEstimate
  Eigen::VectorXd col_scales_;  // L for translation columns, 1 for rotation (dimensionless κ)
  // Extended-precision accuracy phase: poses, driver values and Φ, sized once.
  std::vector<ExtendedPose> ext_poses_;
  std::vector<Real> ext_drivers_;
  Eigen::Matrix<Real, Eigen::Dynamic, 1> ext_phi_;

};

}  // namespace mechkin
