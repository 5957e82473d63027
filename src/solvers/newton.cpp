#include "solvers/newton.hpp"

#include <cmath>

namespace mechkin {

NewtonSolver::NewtonSolver(const ConstraintSystem& sys, std::vector<int> rows)
    : sys_(sys), rows_(std::move(rows)), scales_(RowScales(sys, rows_)), jac_(sys, Formulation::Omega, rows_) {
  lu_.analyzePattern(jac_.matrix());
  rhs_.resize(rows_.size());
  dq_.resize(6 * sys.num_bodies());
}

bool NewtonSolver::Factorize(const SystemState& s) {
  jac_.Fill(sys_, s);
  lu_.factorize(jac_.matrix());
  factorized_ = lu_.info() == Eigen::Success;
  return factorized_;
}

void NewtonSolver::BackSolve(const Eigen::VectorXd& b, Eigen::VectorXd* x) { *x = lu_.solve(b); }

double NewtonSolver::ConditionEstimate() {
  if (!factorized_) return std::numeric_limits<double>::infinity();
  // ‖J‖_F · ‖J⁻¹‖ with ‖J⁻¹‖ from three steps of inverse iteration: cheap (three
  // back-solves with the factors we already have), an underestimate at worst.
  Eigen::VectorXd x = Eigen::VectorXd::Ones(jac_.matrix().cols()).normalized();
  double inv_norm = 0;
  for (int it = 0; it < 3; ++it) {
    const Eigen::VectorXd y = lu_.solve(x);
    inv_norm = y.norm();
    if (!(inv_norm > 0) || !std::isfinite(inv_norm)) return std::numeric_limits<double>::infinity();
    x = y / inv_norm;
  }
  return jac_.matrix().norm() * inv_norm;
}

SolveSummary NewtonSolver::Solve(const SolveOptions& options, SystemState* s) {
  SolveSummary sum;
  CalcPhi(sys_, *s, &phi_);
  sum.residual = ScaledResidual(phi_, rows_, scales_);
  double prev = std::numeric_limits<double>::infinity();
  while (!(sum.residual <= options.tolerance)) {
    if (sum.iterations >= options.max_iterations) {
      sum.message = "Newton did not converge in " + std::to_string(options.max_iterations) + " iterations";
      return sum;
    }
    if (!(sum.residual < prev) && sum.iterations > 2) {
      sum.message = "Newton iterations diverge (the residual grows)";
      return sum;
    }
    prev = sum.residual;
    if (!Factorize(*s)) {
      sum.message = "the constraint Jacobian is singular";
      return sum;
    }
    for (size_t k = 0; k < rows_.size(); ++k) rhs_[k] = -phi_[rows_[k]];
    dq_ = lu_.solve(rhs_);
    if (!dq_.allFinite()) {
      sum.message = "the Newton step is not finite (singular Jacobian)";
      return sum;
    }
    ApplyStep(dq_, s);
    ++sum.iterations;
    CalcPhi(sys_, *s, &phi_);
    sum.residual = ScaledResidual(phi_, rows_, scales_);
  }
  sum.success = true;
  sum.message = "converged";
  return sum;
}

}  // namespace mechkin
