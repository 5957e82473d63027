#include "kinematics/newton.hpp"

#include <cmath>
#include <limits>

namespace mechkin {

NewtonSolver::NewtonSolver(const ConstraintSystem& sys, std::vector<int> rows)
    : sys_(sys), rows_(std::move(rows)), scales_(RowScales(sys, rows_)), jac_(sys, Formulation::Omega, rows_) {
  const int n = 6 * sys.num_bodies();
  dense_ = n <= 120 && static_cast<int>(rows_.size()) == n;
  if (dense_) {
    dense_J_.setZero(n, n);
    const Eigen::SparseMatrix<double>& J = jac_.matrix();
    for (int c = 0; c < J.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(J, c); it; ++it) dense_offset_.push_back(it.row() + c * n);
  } else {
    lu_.analyzePattern(jac_.matrix());
  }
  rhs_.resize(rows_.size());
  dq_.resize(n);
  cond_x_ = Eigen::VectorXd::Ones(n).normalized();
  cond_y_.resize(n);
  cond_b_.resize(n);
  col_scales_ = DimensionlessColumnScales(sys);
  ext_poses_.resize(sys.num_bodies());
  ext_drivers_.resize(sys.model().drivers.size());
  ext_phi_.resize(sys.num_rows());
}

bool NewtonSolver::Factorize(const SystemState& s) {
  jac_.Fill(sys_, s);
  if (dense_) {
    // The pattern's values into the zeroed matrix (what dense_J_ = J does, without
    // walking the sparse structure): the LU overwrites it in place every time.
    dense_J_.setZero();
    const double* values = jac_.matrix().valuePtr();
    double* dense = dense_J_.data();
    for (size_t k = 0; k < dense_offset_.size(); ++k) dense[dense_offset_[k]] = values[k];
    factorized_ = dense_lu_.Compute(&dense_J_);
  } else {
    lu_.factorize(jac_.matrix());
    factorized_ = lu_.info() == Eigen::Success;
  }
  return factorized_;
}

void NewtonSolver::BackSolve(const Eigen::VectorXd& b, Eigen::VectorXd* x) {
  if (dense_) dense_lu_.Solve(b, x);
  else *x = lu_.solve(b);
}

bool NewtonSolver::SolveLinearTranspose(const Eigen::VectorXd& b, Eigen::VectorXd* x) {
  if (!factorized_) return false;
  if (dense_) dense_lu_.SolveTranspose(b, x);
  else *x = lu_.transpose().solve(b);
  return true;
}

double NewtonSolver::JacobianSign() {
  if (dense_) {
    // sign(det) = permutation sign × signs of U's diagonal.
    double s = dense_lu_.sign();
    for (int k = 0; k < dense_J_.rows(); ++k) if (dense_J_(k, k) < 0) s = -s;
    return s;
  }
  return lu_.signDeterminant();
}

double NewtonSolver::ConditionEstimate() {
  if (!factorized_) return std::numeric_limits<double>::infinity();
  // κ of the dimensionless Jacobian A = W Φ_q D (rows by 1/L^power, translation
  // columns by L; constraints.md §6), so the same mechanism gives the same number at
  // any size and in any unit. ‖A‖_F times ‖A⁻¹‖ from one step of inverse iteration
  // per call, A⁻¹x = D⁻¹ Φ_q⁻¹ W⁻¹ x, warm-started from the previous call's vector:
  // along a run it converges to the dominant direction of A⁻¹ (an underestimate at
  // worst) for one back-solve.
  cond_b_ = cond_x_.cwiseQuotient(scales_);
  BackSolve(cond_b_, &cond_y_);
  cond_y_.array() /= col_scales_.array();
  const double inv_norm = cond_y_.norm();
  if (!(inv_norm > 0) || !std::isfinite(inv_norm)) return std::numeric_limits<double>::infinity();
  cond_x_ = cond_y_ / inv_norm;
  cond_norm_ = DimensionlessNorm(jac_.matrix(), scales_, col_scales_);
  cond_last_ = cond_norm_ * inv_norm;
  return cond_last_;
}

// J_s⁻¹ = D⁻¹Φ_q⁻¹W⁻¹ and J_s⁻ᵀ = W⁻¹Φ_q⁻ᵀD⁻¹ alternately, on copies: the run's
// warm-started vector cond_x_ is left as it was.
double NewtonSolver::SharperConditionEstimate(int steps) {
  if (!factorized_) return std::numeric_limits<double>::infinity();
  double inv_norm = cond_norm_ > 0 ? cond_last_ / cond_norm_ : 0;
  sharp_x_ = cond_x_;
  for (int i = 0; i < steps; ++i) {
    sharp_b_ = sharp_x_.cwiseQuotient(col_scales_);
    if (!SolveLinearTranspose(sharp_b_, &sharp_y_)) break;
    sharp_y_.array() /= scales_.array();
    sharp_b_ = (sharp_y_ / sharp_y_.norm()).cwiseQuotient(scales_);
    BackSolve(sharp_b_, &sharp_y_);
    sharp_y_.array() /= col_scales_.array();
    const double n = sharp_y_.norm();
    if (!(n > 0) || !std::isfinite(n)) break;
    inv_norm = std::max(inv_norm, n);
    sharp_x_ = sharp_y_ / n;
  }
  return cond_norm_ * inv_norm;
}

SolveSummary NewtonSolver::Solve(const SolveOptions& options, SystemState* s, bool reuse) {
  SolveSummary sum;
  CalcPhi(sys_, *s, &phi_);
  sum.residual = ScaledResidual(phi_, rows_, scales_);
  double prev = std::numeric_limits<double>::infinity();
  bool stale = reuse && factorized_;  // held factorization from an earlier pose
  while (!(sum.residual <= options.tolerance)) {
    if (sum.iterations >= options.max_iterations) {
      sum.message = "Newton did not converge in " + std::to_string(options.max_iterations) + " iterations";
      return sum;
    }
    if (!(sum.residual < prev) && sum.iterations > 2) {
      sum.message = "Newton iterations diverge (the residual grows)";
      return sum;
    }
    // Modified Newton: keep the stale factorization while it contracts by 10× per step.
    if (stale && sum.iterations > 0 && !(sum.residual < 0.1 * prev)) stale = false;
    prev = sum.residual;
    if (!stale && !Factorize(*s)) {
      sum.message = "the constraint Jacobian is singular";
      return sum;
    }
    for (size_t k = 0; k < rows_.size(); ++k) rhs_[k] = -phi_[rows_[k]];
    BackSolve(rhs_, &dq_);
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
  // The extended phase supersedes the double one: its target lies below double round-off.
  if (options.extended_precision) RefineExtended(s, &sum);
  else RefineToTarget(options, s, &sum);
  return sum;
}

// The accuracy phase: the residual met the tolerance, but the derivatives' error
// bound needs options.target (κ² times less; analysis/error_bounds.hpp). Up to two
// more iterations with the factorization held (back-solves only), each required to
// halve the residual; stopping at round-off is not a failure.
void NewtonSolver::RefineToTarget(const SolveOptions& options, SystemState* s, SolveSummary* sum) {
  for (int extra = 0; extra < 2 && sum->residual > options.target && factorized_; ++extra) {
    for (size_t k = 0; k < rows_.size(); ++k) rhs_[k] = -phi_[rows_[k]];
    BackSolve(rhs_, &dq_);
    if (!dq_.allFinite()) return;
    ApplyStep(dq_, s);
    ++sum->iterations;
    CalcPhi(sys_, *s, &phi_);
    const double before = sum->residual;
    sum->residual = ScaledResidual(phi_, rows_, scales_);
    if (!(sum->residual < 0.5 * before)) return;
  }
}

}  // namespace mechkin

namespace mechkin {

Real NewtonSolver::ExtendedResidual() {
  Real m = 0;
  for (size_t k = 0; k < rows_.size(); ++k) m = std::max(m, std::abs(ext_phi_[rows_[k]]) * Real(scales_[k]));
  return m;
}

// The extended-precision accuracy phase (issue "Right at every order", item 2). Near a
// dead centre the k-th derivative amplifies the position error by about κ^k, and in
// double the residual cannot place the pose closer than round-off of the coordinates
// (a piston at 70 mm: 1.4e-17 m) divided by the small pivot. Here Φ is evaluated in
// long double at a long-double pose, and the corrections, back-solved with the double
// factorization (iterative refinement: it converges while κ·u < 1), accumulate there;
// the pose is rounded to double once at the end. Rounding the pose moves each coordinate
// by u relative, which the derivatives do not amplify like a residual: they read the
// orientations, which the rounding keeps to u.
void NewtonSolver::RefineExtended(SystemState* s, SolveSummary* sum) {
  if (!factorized_) return;
  for (size_t b = 0; b < s->bodies.size(); ++b) ext_poses_[b] = ExtendedPose::Of(s->bodies[b]);
  EvalDriverValuesExtended(sys_.model(), s->t, &ext_drivers_);
  CalcPhiExtended(sys_, ext_poses_, ext_drivers_, s->angle_ref, &ext_phi_);
  Real residual = ExtendedResidual();
  // Round-off of Φ in long double, scaled like the residual: 16 units of the largest
  // coordinate (relative to the characteristic length; 1 for the rotation rows).
  Real extent = 1;
  for (const ExtendedPose& pose : ext_poses_)
    extent = std::max(extent, pose.r.cwiseAbs().maxCoeff() / Real(sys_.model().characteristic_length));
  const Real floor = 16 * std::numeric_limits<Real>::epsilon() * extent;
  // The held factorization first (usually Φ_q at the previous step: no new
  // factorization where it contracts by 10x); a fresh one where it does not — near a
  // dead centre, where Φ_q turns fastest.
  bool fresh = false;
  for (int extra = 0; extra < 4 && residual > floor; ++extra) {
    for (size_t k = 0; k < rows_.size(); ++k) rhs_[k] = -static_cast<double>(ext_phi_[rows_[k]]);
    BackSolve(rhs_, &dq_);
    if (!dq_.allFinite()) break;
    for (size_t b = 0; b < s->bodies.size(); ++b) {
      ExtendedPose& pose = ext_poses_[b];
      pose.r += dq_.segment<3>(6 * b).cast<Real>();
      pose.p = RetractBody(pose.p, Vec3R(dq_.segment<3>(6 * b + 3).cast<Real>()));
      pose.A = RotationMatrix(pose.p);
    }
    ++sum->iterations;
    CalcPhiExtended(sys_, ext_poses_, ext_drivers_, s->angle_ref, &ext_phi_);
    const Real before = residual;
    residual = ExtendedResidual();
    if (residual < 0.1L * before || residual <= floor) continue;
    if (fresh) break;  // at round-off
    fresh = true;
    if (!Factorize(*s)) return;
  }
  for (size_t b = 0; b < s->bodies.size(); ++b) {
    BodyKinematics& k = s->bodies[b];
    k.r[0] = ext_poses_[b].r.cast<double>();
    k.p = ext_poses_[b].p.cast<double>();
    k.A = CalcA(k.p);
    k.AD[0] = k.A;
    k.AB[0] = k.A;
  }
  CalcPhi(sys_, *s, &phi_);
  sum->residual = ScaledResidual(phi_, rows_, scales_);
}

}  // namespace mechkin


