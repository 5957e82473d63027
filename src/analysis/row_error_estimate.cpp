#include "analysis/row_error_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mechkin {

namespace {

constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2;
// Safety on the measured (first-order) terms: the errors are samples of round-off
// (their size, not their worst case) and the chain is linearized about a pose that is
// itself only known to e_0.
constexpr double kPositionSafety = 2;
constexpr double kExtendedRoundoff = std::numeric_limits<Real>::epsilon();
constexpr double kDerivativeSafety = 4;
// Units of round-off per right-hand-side entry and per term of Φ_q·q^(k) in the
// worst-case solve error (step 3 of the header): 2 halved the piston's jerk bound
// below its error at --tol 1e-13 (python/tests/test_error_bounds.py), 4 holds.
constexpr double kRoundoffUnits = 4;
// A set-aside equation's scaled residual beyond this many units of long double's
// round-off: the geometry does not satisfy it exactly (PositionError).
constexpr double kInconsistentUnits = 64;
// PoseError's finer forms where long double's round-off through Φ_q could reach this
// part of the pose error it measures.
constexpr double kResolution = 0.1;

// max-abs of a ω'-layout vector with translations divided by the characteristic length.
double ScaledNorm(const Eigen::VectorXd& x, const Eigen::VectorXd& col_scales) {
  double m = 0;
  for (int i = 0; i < x.size(); ++i) m = std::max(m, std::abs(x[i] / col_scales[i]));
  return m;
}

}  // namespace

RowErrorEstimator::RowErrorEstimator(const ConstraintSystem& sys, int order)
    : sys_(sys), order_(order), ext_poses_(sys.num_bodies()), ext_drivers_(sys.model().drivers.size()), col_scales_(DimensionlessColumnScales(sys)), seed_(order + 1), roundoff_(order + 1), delta_(order + 1),
      scale_(order + 1, 0.0), driver_scale_(order + 1, std::vector<double>(sys.model().drivers.size(), 0.0)),
      row_driver_(sys.num_rows(), -1), unit_excess_(sys.num_bodies(), 0.0) {
  ext_phi_.resize(sys.num_rows());
  quad_poses_.resize(sys.num_bodies());
  quad_phi_.resize(sys.num_rows());
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    if (!entries[e].from_driver) continue;
    const int end = e + 1 < entries.size() ? entries[e + 1].first_row : sys.num_rows();
    for (int r = entries[e].first_row; r < end; ++r) row_driver_[r] = entries[e].source;
  }
  jet_poses_.resize(sys.num_bodies());
  jet_drivers_.resize(sys.model().drivers.size());
  jet_phi_.resize(sys.num_rows());
  plus_state_ = std::make_unique<SystemState>(sys);
  minus_state_ = std::make_unique<SystemState>(sys);
  const int n = 6 * sys.num_bodies();
  for (auto& d : delta_) d.setZero(n);
  x_.resize(n);
}

RowErrorEstimator::~RowErrorEstimator() = default;

void RowErrorEstimator::Observe(const SystemState& s) {
  for (int k = 1; k <= order_; ++k) {
    double m = 0;
    for (const BodyKinematics& b : s.bodies)
      m = std::max({m, b.r[k].cwiseAbs().maxCoeff() / col_scales_[0], b.w[k - 1].cwiseAbs().maxCoeff()});
    scale_[k] = std::max(scale_[k], m);
    for (size_t d = 0; d < s.driver_values.size(); ++d)
      driver_scale_[k][d] = std::max(driver_scale_[k][d], std::abs(s.driver_values[d].Derivative(k)));
  }
}

// κ ≥ ‖J_s‖_F ‖J_s⁻¹x‖ for x the scaled residual's direction and for ŷ, y = Φ_q⁻¹(−Φ)
// the Newton correction (one inverse-iteration step, its result in probe_, unscaled);
// left_ = Φ_q⁻ᵀ probe_, whose signs are those of the direction Φ_q⁻¹ amplifies most.
// pose_error_: the pose's error (below).
bool RowErrorEstimator::PositionError(KinematicsWorkspace& ws, const SystemState& s, double* kappa) {
  if (rows_ != ws.active()) {
    rows_ = ws.active();
    jac_ = std::make_unique<SparseJacobian>(sys_, Formulation::Omega, rows_);
    row_scales_ = RowScales(sys_, rows_);
    rhs_.resize(rows_.size());
    set_aside_.clear();
    std::vector<char> active(sys_.num_rows(), 0);
    for (int r : rows_) active[r] = 1;
    for (int r = 0; r < sys_.num_rows(); ++r)
      if (!active[r]) set_aside_.push_back(r);
    set_aside_scales_ = RowScales(sys_, set_aside_);
  }
  jac_->Fill(sys_, s);
  const double norm = DimensionlessNorm(jac_->matrix(), row_scales_, col_scales_);
  CalcPhi(sys_, s, &full_);
  for (size_t r = 0; r < rows_.size(); ++r) rhs_[r] = -full_[rows_[r]];
  if (!ws.factorization().SolveLinear(rhs_, &delta_[0]) || !delta_[0].allFinite()) return false;
  const double residual_norm = rhs_.cwiseProduct(row_scales_).norm();
  const double y2 = delta_[0].cwiseQuotient(col_scales_).norm();
  double inverse = residual_norm > 0 ? y2 / residual_norm : 0;
  // The start of the inverse iteration: ŷ, or any vector when the pose closes exactly.
  if (y2 > 0) rhs_ = delta_[0].cwiseQuotient(col_scales_) / y2;
  else rhs_.setConstant(1 / std::sqrt(static_cast<double>(rhs_.size())));
  rhs_ = rhs_.cwiseQuotient(row_scales_);
  if (!ws.factorization().SolveLinear(rhs_, &probe_) || !probe_.allFinite()) return false;
  inverse = std::max(inverse, probe_.cwiseQuotient(col_scales_).norm());
  *kappa = std::max(*kappa, norm * inverse);
  if (!ws.factorization().SolveLinearTranspose(probe_, &left_) || !left_.allFinite()) return false;
  return PoseError(ws, s, *kappa);
}

// The stored pose with each p normalized, in long double (ext_poses_) and in quadruple
// precision (quad_poses_); unit_excess_ = |p| − 1. A stored p is unit only to
// round-off, and A(p) of §1.2 then stretches the body by |p|² − 1, which the residual
// would read as a displacement amplified up to κ (100× the piston's real error after
// the long-double phase); the stretch is propagated apart, as unit_excess_ (Moved).
void RowErrorEstimator::NormalizedPoses(const SystemState& s) {
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    ext_poses_[b] = ExtendedPose::Of(s.bodies[b]);
    const Real norm = ext_poses_[b].p.norm();
    unit_excess_[b] = static_cast<double>(norm - 1);
    ext_poses_[b].p /= norm;
    ext_poses_[b].A = RotationMatrix(ext_poses_[b].p);
  }
}

// The same in quadruple precision (quad_poses_), for PoseError's finer residual.
void RowErrorEstimator::QuadPoses(const SystemState& s) {
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    Eigen::Matrix<Quad, 4, 1> p = s.bodies[b].p.cast<Quad>();
    p /= QuadSqrt(p.squaredNorm());
    quad_poses_[b].r = s.bodies[b].r[0].cast<Quad>();
    quad_poses_[b].A = RotationMatrix(p);
  }
}

// The pose's actual error pose_error_ = Φ_q⁻¹Φ(q̂) at the normalized pose, the residual
// Newton in double cannot see below its own round-off; Φ in long double (§9). Where
// that round-off, solved through Φ_q — about κ_s·ε_ld — could reach a tenth of the
// error it measures (near a singular position; the factor 2 on ε covers less, and
// κ_s·ε_ld estimates the round-off to within an order of magnitude), Φ again in
// quadruple precision (§8, "Measured", step 1). On the N-four-bar's rows nearest ±90° long double's
// round-off gives 1.6e-17 to 5.9e-17 rad in the rockers' turn against the crank,
// where the stored pose's error is exactly 0. First, whether the pose leaves a
// set-aside (redundant) equation unsatisfied beyond long double's round-off: then the
// stored model does not move exactly — its redundancy holds only to the rounding of
// its numbers (Bennett's condition in double; any redundant mechanism outside the
// coordinate planes) — the motion it stands for is known only to that
// (aside_unsatisfied_, RoundOff), and the finer forms here and in SolveErrors would
// resolve nothing.
bool RowErrorEstimator::PoseError(KinematicsWorkspace& ws, const SystemState& s, double kappa) {
  NormalizedPoses(s);
  EvalDriverValuesExtended(sys_.model(), s.t, &ext_drivers_);
  CalcPhiExtended(sys_, ext_poses_, ext_drivers_, s.angle_ref, &ext_phi_);
  aside_unsatisfied_ = false;
  for (size_t a = 0; a < set_aside_.size(); ++a)
    if (std::abs(static_cast<double>(ext_phi_[set_aside_[a]])) * set_aside_scales_[a] > kInconsistentUnits * kExtendedRoundoff)
      aside_unsatisfied_ = true;
  for (size_t r = 0; r < rows_.size(); ++r) rhs_[r] = static_cast<double>(ext_phi_[rows_[r]]);
  if (!ws.factorization().SolveLinear(rhs_, &pose_error_) || !pose_error_.allFinite()) return false;
  if (aside_unsatisfied_ || !(kappa * kExtendedRoundoff > kResolution * ScaledNorm(pose_error_, col_scales_))) return true;
  QuadPoses(s);
  CalcPhiQuad(sys_, quad_poses_, ext_poses_, ext_drivers_, s.angle_ref, &quad_phi_);
  for (size_t r = 0; r < rows_.size(); ++r) rhs_[r] = static_cast<double>(quad_phi_[rows_[r]]);
  return ws.factorization().SolveLinear(rhs_, &pose_error_) && pose_error_.allFinite();
}

// x_ = the order-k unknowns (r^(k), ω'^(k−1)) per body, ω' layout.
void RowErrorEstimator::OrderUnknowns(const SystemState& s, int k) {
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    x_.segment<3>(6 * b) = s.bodies[b].r[k];
    x_.segment<3>(6 * b + 3) = s.bodies[b].w[k - 1];
  }
}

// out = s moved by sign·h·delta_ in the pose and the derivative orders 1..upto, in
// the ω' chart (as SensitivitySolver::PerturbedState does for a parameter).
void RowErrorEstimator::Moved(const SystemState& s, int upto, double sign, SystemState* out) const {
  out->t = s.t;
  out->bodies = s.bodies;
  out->driver_values = s.driver_values;
  out->angle_ref = s.angle_ref;
  const double e = sign * h_;
  for (size_t b = 0; b < out->bodies.size(); ++b) {
    BodyKinematics& bk = out->bodies[b];
    bk.r[0] += e * delta_[0].segment<3>(6 * b);
    bk.p = QuatRetractBody(bk.p, e * delta_[0].segment<3>(6 * b + 3)) * (1 + e * stretch_ * unit_excess_[b]);
    bk.A = CalcA(bk.p);
    bk.AD[0] = bk.AB[0] = bk.A;
    for (int k = 1; k <= upto; ++k) {
      bk.r[k] += e * delta_[k].segment<3>(6 * b);
      bk.w[k - 1] += e * delta_[k].segment<3>(6 * b + 3);
    }
    bk.UpdateDerived(order_);
  }
}

// delta_[k] = D F_k · delta_[0]: Φ_q δq^(k) = −[R_k(s₊) − R_k(s₋)] / 2h with
// R_k = Φ_q q^(k) − RHS_k and the lower orders moved along their own δ.
void RowErrorEstimator::Propagate(KinematicsWorkspace& ws, const SystemState& s, int k) {
  // h: the largest move 1e-6 of its order's scale (linear, above the residuals' round-off).
  double extent = ScaledNorm(delta_[0], col_scales_);
  for (double excess : unit_excess_) extent = std::max(extent, std::abs(stretch_ * excess));
  for (int j = 1; j < k; ++j) extent = std::max(extent, ScaledNorm(delta_[j], col_scales_) / std::max(scale_[j], 1e-300));
  h_ = extent > 0 ? 1e-6 / extent : 1e-6;
  OrderUnknowns(s, k);
  for (int side = 0; side < 2; ++side) {
    SystemState& moved = side == 0 ? *plus_state_ : *minus_state_;
    Moved(s, k - 1, side == 0 ? 1.0 : -1.0, &moved);
    jac_->Fill(sys_, moved);
    CalcRhs(sys_, moved, k, Formulation::Omega, &full_);
    Eigen::VectorXd& residual = side == 0 ? plus_ : minus_;
    residual.noalias() = jac_->matrix() * x_;  // into the held buffer: no temporary per row
    for (size_t r = 0; r < rows_.size(); ++r) residual[r] -= full_[rows_[r]];
  }
  rhs_ = (minus_ - plus_) / (2 * h_);
  if (!ws.factorization().SolveLinear(rhs_, &delta_[k]) || !delta_[k].allFinite()) delta_[k].setZero();
}

// The pose along the computed derivatives as Taylor series in long double (JetPoseOf),
// at the normalized orientation PositionError left in ext_poses_; the drivers' series
// as the step used them (their value in long double). jet_phi_ = Φ on them: its k-th
// coefficient times k! is d^kΦ/dt^k = Φ_q q^(k) − RHS_k at the computed orders ≤ k.
// False where a family's series is not finite (an angle at a zero-length vector).
bool RowErrorEstimator::JetResiduals(const SystemState& s) {
  for (size_t b = 0; b < s.bodies.size(); ++b) jet_poses_[b] = JetPoseOf(s.bodies[b], ext_poses_[b].A, order_);
  for (size_t d = 0; d < jet_drivers_.size(); ++d) {
    jet_drivers_[d] = ExtendedJet(ext_drivers_[d]);
    for (int k = 1; k <= order_; ++k) jet_drivers_[d].c[k] = s.driver_values[d].c[k];
  }
  CalcPhiJets(sys_, jet_poses_, jet_drivers_, s.angle_ref, &jet_phi_);
  for (int row : rows_)
    for (int k = 1; k <= order_; ++k)
      if (!std::isfinite(jet_phi_[row].c[k])) return false;
  return true;
}

// seed_[k] = Φ_q⁻¹ R_k(s): the order-k solve's own error, k = 1..order, before the chain
// moves jac_ off s; R_k = Φ_q q̂^(k) − RHS_k from the series (JetResiduals: in long
// double, so that R_k holds the step's whole round-off — its Φ_q and RHS_k evaluated in
// double, its back-solve — and not the round-off of evaluating R_k), else evaluated in
// double as the step did (then the round-off R_k cannot see is bounded: RoundOff).
// And roundoff_[k] (RoundOff).
bool RowErrorEstimator::SolveErrors(KinematicsWorkspace& ws, const SystemState& s) {
  static constexpr double kFactorial[] = {1, 1, 2, 6, 24};
  const bool exact = !aside_unsatisfied_ && JetResiduals(s);
  for (int k = 1; k <= order_; ++k) {
    OrderUnknowns(s, k);
    CalcRhs(sys_, s, k, Formulation::Omega, &full_);
    if (exact) {
      plus_.resize(rows_.size());
      for (size_t r = 0; r < rows_.size(); ++r) plus_[r] = static_cast<double>(jet_phi_[rows_[r]].c[k] * kFactorial[k]);
    } else {
      plus_.noalias() = jac_->matrix() * x_;
      for (size_t r = 0; r < rows_.size(); ++r) plus_[r] -= full_[rows_[r]];
    }
    if (!ws.factorization().SolveLinear(plus_, &seed_[k]) || !seed_[k].allFinite()) return false;
    if (!RoundOff(ws, k, exact)) return false;
  }
  return true;
}

// roundoff_[k] = Φ_q⁻¹ρ: the error a solve's round-off can leave that the residual of
// seed_ does not see, with the signs of left_, so that ρ lies along the direction Φ_q⁻¹
// amplifies most. ρ_r is kRoundoffUnits units of round-off times the row's magnitudes
// Σ_j |J_rj x_j| + |RHS_r|, plus on a driver's row the largest |f^(k)| along the run
// (f^(k) can cancel to nearly 0 from terms of that size: the piston toward its dead
// centre). The unit is long double's where the residual came from the series, but
// double's on a driver's row (the drivers' series are the double ones the step used,
// and how a row reads f is its family's: −f² for a driven distance), where the series
// were not finite (the residual was then evaluated in double, which cannot resolve
// the back-solve's backward error) and where the stored model does not move exactly
// (aside_unsatisfied_). x_ and full_ hold order k.
bool RowErrorEstimator::RoundOff(KinematicsWorkspace& ws, int k, bool residual_exact) {
  rhs_.setZero();
  const Eigen::SparseMatrix<double>& J = jac_->matrix();
  for (int col = 0; col < J.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, col); it; ++it) rhs_[it.row()] += std::abs(it.value() * x_[it.col()]);
  const double unit = residual_exact && !aside_unsatisfied_ ? kExtendedRoundoff : kUnitRoundoff;
  for (size_t r = 0; r < rows_.size(); ++r) {
    const int driver = row_driver_[rows_[r]];
    const double row = rhs_[r] + std::abs(full_[rows_[r]]);
    const double magnitude = driver >= 0 ? kUnitRoundoff * (row + driver_scale_[k][driver]) : unit * row;
    rhs_[r] = kRoundoffUnits * magnitude * (left_[r] >= 0 ? 1 : -1);
  }
  return ws.factorization().SolveLinear(rhs_, &roundoff_[k]) && roundoff_[k].allFinite();
}

bool RowErrorEstimator::Raise(KinematicsWorkspace& ws, const SystemState& s, double condition, double* bound) {
  double kappa = condition;
  if (!PositionError(ws, s, &kappa) || !SolveErrors(ws, s)) return false;
  // e_0: the pose's error ε and the Euler parameters' stretch, doubled, and never
  // below what the long-double residual can resolve. The chain propagates 2ε itself (and twice the stretch): a floor such
  // as 4uκ, had it been propagated along ε, would overstate the derivatives' error by
  // the floor's ratio to ε (up to 2e4× on the N-four-bar, constraints.md §8).
  const double eps = ScaledNorm(pose_error_, col_scales_);
  double stretch = 0;
  for (double excess : unit_excess_) stretch = std::max(stretch, std::abs(excess));
  const double e0 = std::max({kPositionSafety * eps, kPositionSafety * stretch, kappa * kExtendedRoundoff});
  bound[0] = std::max(bound[0], e0);
  delta_[0] = kPositionSafety * pose_error_;
  stretch_ = kPositionSafety;
  for (int k = 1; k <= order_; ++k) {
    Propagate(ws, s, k);
    // The round-off's direction is a worst case: taken to add to the propagated error.
    if (delta_[k].dot(roundoff_[k]) < 0) roundoff_[k] = -roundoff_[k];
    delta_[k] += seed_[k] + roundoff_[k];
    const double scale = scale_[k] > 0 ? scale_[k] : 1;
    bound[k] = kDerivativeSafety * ScaledNorm(delta_[k], col_scales_) / scale + kappa * 8 * kUnitRoundoff;
  }
  return true;
}

}  // namespace mechkin
