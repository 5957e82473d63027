// Measured error bounds of one row near a singular position (constraints.md §8,
// "Measured"; issue "Loudly wrong exactly where it matters", item 2).
//
// The bounds from κ (error_bounds.hpp) pay k!·κ^k at order k, which near a singular
// position overstates the error by orders of magnitude, while the k-th derivative's
// actual error there grows like k!/σ_min^k. This estimator measures instead, at the
// solved, factorized row:
//   1. the pose's error ε = Φ_q⁻¹Φ(q̂), Φ in long double and in double (the larger);
//   2. its propagation into every derivative, q^(k) = F_k(q): δq^(k) = DF_k·ε from the
//      identities of the parameter sensitivities (sensitivity.hpp) with the pose moved
//      instead of a parameter, central differences at ±h;
//   3. each order's own solve error Φ_q⁻¹(Φ_q q̂^(k) − RHS_k);
// and states e_0 = max(2‖ε‖, 4u·κ), e_k = 4‖δq^(k)‖/‖q^(k)‖_max + κ(e_0 + 8u),
// ‖q^(k)‖_max the largest magnitude of order k seen along the run. Max-abs norms,
// translations over the characteristic length. No allocation per row once the
// active rows are known (buffers sized on the first row).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "kinematics/workspace.hpp"

namespace mechkin {

class RowErrorEstimator {
 public:
  RowErrorEstimator(const ConstraintSystem& sys, int order);
  ~RowErrorEstimator();

  /// Folds the row's derivative magnitudes into the run's scales (every accepted row).
  void Observe(const SystemState& s);
  /// At the solved, factorized row `s` (derivatives to `order`), raises bound[0..order]
  /// to the measured bounds. `extended`: the pose came from the long-double phase.
  /// Returns false (bounds untouched) when the factorization cannot solve.
  bool Raise(KinematicsWorkspace& ws, const SystemState& s, double condition, bool extended, double* bound);

 private:
  bool PositionError(KinematicsWorkspace& ws, const SystemState& s, double* kappa, double* y_norm);
  bool SolveErrors(KinematicsWorkspace& ws, const SystemState& s);
  void Propagate(KinematicsWorkspace& ws, const SystemState& s, int k);
  void OrderUnknowns(const SystemState& s, int k);
  void Moved(const SystemState& s, int upto, double sign, SystemState* out) const;

  const ConstraintSystem& sys_;
  int order_;
  std::vector<ExtendedPose> ext_poses_;
  std::vector<Real> ext_drivers_;
  Eigen::Matrix<Real, Eigen::Dynamic, 1> ext_phi_;
  std::vector<int> rows_;
  std::unique_ptr<SparseJacobian> jac_;
  std::unique_ptr<SystemState> plus_state_, minus_state_;
  Eigen::VectorXd col_scales_, row_scales_, full_, rhs_, x_, plus_, minus_, probe_, pose_error_;
  std::vector<Eigen::VectorXd> seed_;   // per order: the solve's own error
  std::vector<Eigen::VectorXd> delta_;  // per order: the propagated error direction (ω' layout)
  std::vector<double> scale_;           // per order: largest scaled ‖q^(k)‖ along the run
  double h_ = 1e-6;
};

}  // namespace mechkin
