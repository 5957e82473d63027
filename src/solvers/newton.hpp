// Newton–Raphson position solve on the configuration manifold with a sparse LU
// of Φ_q (ω' version). The symbolic analysis is done once per row set; each
// iteration refactorizes numerically. After Solve(), the factorization held is
// Φ_q at the solution, ready for the velocity … snap back-solves of the step.
#pragma once

#include <Eigen/SparseLU>
#include <memory>

#include "solvers/position.hpp"

namespace mechkin {

class NewtonSolver {
 public:
  /// `rows`: the independent equations (redundant ones set aside); must be 6n of them.
  NewtonSolver(const ConstraintSystem& sys, std::vector<int> rows);

  /// Solves Φ(q, t) = 0 on the rows from the state's current pose (the predictor).
  /// Driver values must already be evaluated at t. On return the factorization is
  /// that of Φ_q at the final pose (also on failure, for diagnostics).
  SolveSummary Solve(const SolveOptions& options, SystemState* s);

  /// Factorizes Φ_q at the current pose (ω' version). Returns false if singular.
  bool Factorize(const SystemState& s);
  /// Solves Φ_q x = b with the current factorization (b, x over the active rows / 6n columns).
  void BackSolve(const Eigen::VectorXd& b, Eigen::VectorXd* x);

  /// Sign of det Φ_q of the current factorization (ω' columns). It flips exactly
  /// when the path crosses a singular position, which is how runs detect them.
  double JacobianSign() { return lu_.signDeterminant(); }
  const std::vector<int>& rows() const { return rows_; }
  const Eigen::VectorXd& scales() const { return scales_; }
  const Eigen::SparseMatrix<double>& jacobian() const { return jac_.matrix(); }
  /// Cheap estimate of the condition number of Φ_q (Frobenius norm times an
  /// inverse-iteration estimate of ‖Φ_q⁻¹‖), from the current factorization.
  double ConditionEstimate();

 private:
  const ConstraintSystem& sys_;
  std::vector<int> rows_;
  Eigen::VectorXd scales_;
  SparseJacobian jac_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  bool factorized_ = false;
  Eigen::VectorXd phi_, rhs_, dq_;
};

}  // namespace mechkin
