// Measured error bounds of one row near a singular position (constraints.md §8,
// "Measured"; issue "Loudly wrong exactly where it matters", item 2).
//
// The bounds from κ (error_bounds.hpp) pay about κ per order, which near a singular
// position misjudges the error by orders of magnitude either way, while the k-th
// derivative's actual error there grows like k!/σ_min^k. This estimator measures
// instead, at the solved, factorized row:
//   1. the pose's error ε = Φ_q⁻¹Φ(q̂), Φ in long double at the pose with its Euler
//      parameters normalized — again in quadruple precision (math/quad.hpp) where
//      long double's round-off through Φ_q could reach ε/10 — and apart the stretch
//      |p| − 1 of each stored p;
//   2. their propagation into every derivative, q^(k) = F_k(q): δq^(k) = DF_k·(2ε) from
//      the identities of the parameter sensitivities (sensitivity.hpp) with the pose
//      moved instead of a parameter, central differences at ±h;
//   3. each order's own solve error Φ_q⁻¹R_k, R_k = d^kΦ/dt^k at the computed orders
//      from Φ on Taylor series in long double (JetResiduals), plus the worst what R_k
//      cannot see can leave (RoundOff);
// and states e_0 = max(2‖ε‖, 2 max|p| − 1, κ·ε_ld), e_k = 4‖δq^(k)‖/‖q^(k)‖_max + 8uκ,
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
  /// At the solved, factorized row `s` (derivatives to `order`), sets bound[1..order] to
  /// the measured bounds and raises bound[0] to its measured one. Returns false (bounds
  /// untouched) when the factorization cannot solve.
  bool Raise(KinematicsWorkspace& ws, const SystemState& s, double condition, double* bound);

 private:
  bool PositionError(KinematicsWorkspace& ws, const SystemState& s, double* kappa);
  void NormalizedPoses(const SystemState& s);
  void QuadPoses(const SystemState& s);
  bool PoseError(KinematicsWorkspace& ws, const SystemState& s, double kappa);
  bool RoundOff(KinematicsWorkspace& ws, int k, bool residual_exact);
  bool JetResiduals(const SystemState& s);
  bool SolveErrors(KinematicsWorkspace& ws, const SystemState& s);
  void Propagate(KinematicsWorkspace& ws, const SystemState& s, int k);
  void OrderUnknowns(const SystemState& s, int k);
  void Moved(const SystemState& s, int upto, double sign, SystemState* out) const;

  const ConstraintSystem& sys_;
  int order_;
  std::vector<ExtendedPose> ext_poses_;
  std::vector<Real> ext_drivers_;
  Eigen::Matrix<Real, Eigen::Dynamic, 1> ext_phi_;
  std::vector<QuadPose> quad_poses_;
  std::vector<Quad> quad_phi_;
  std::vector<int> rows_;
  std::unique_ptr<SparseJacobian> jac_;
  std::unique_ptr<SystemState> plus_state_, minus_state_;
  Eigen::VectorXd col_scales_, row_scales_, full_, rhs_, x_, plus_, minus_, probe_, pose_error_;
  std::vector<Eigen::VectorXd> seed_;      // per order: the solve's own error, sampled
  std::vector<Eigen::VectorXd> roundoff_;  // per order: the worst its round-off can leave
  std::vector<Eigen::VectorXd> delta_;  // per order: the propagated error direction (ω' layout)
  std::vector<double> scale_;           // per order: largest scaled ‖q^(k)‖ along the run
  std::vector<std::vector<double>> driver_scale_;  // per order, per driver: largest |f^(k)|
  std::vector<int> row_driver_;         // per system row: its driver, or −1
  std::vector<double> unit_excess_;     // per body: |p| − 1 of the stored Euler parameters
  double stretch_ = 0;                  // the multiple of unit_excess_ the chain moves along
  Eigen::VectorXd left_;                // Φ_q⁻ᵀ probe_: signs of the most amplified direction
  std::vector<int> set_aside_;          // the system rows not solved (redundant), and their scales
  Eigen::VectorXd set_aside_scales_;
  bool aside_unsatisfied_ = false;      // a set-aside row unsatisfied beyond round-off (RoundOff)
  std::vector<JetPose> jet_poses_;      // per body: the pose as series along the computed derivatives
  std::vector<ExtendedJet> jet_drivers_, jet_phi_;  // per driver, per system row
  double h_ = 1e-6;
};

}  // namespace mechkin
