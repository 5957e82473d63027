// Inverse dynamics of the prescribed motion (issue: forces along the motion).
//
// With the equations of motion M q̈ + Φ_qᵀλ = Q^A (constraints.md §1.8) and the
// motion known, the multipliers follow from one transpose solve with the step's
// factorization:  Φ_qᵀ λ = R,  R = Q^A − M q̈  (per body, in the ω' layout: the
// force in global axes at the body origin, the torque in body axes about it).
// Their rates from the differentiated equations:  Φ_qᵀ λ̇ = Ṙ − κ(λ)  (§1.8).
// From λ: each driver's effort (the generalized force it applies, conjugate to
// its coordinate) and power, each joint's reaction (what body1 exerts on body2,
// at the joint origin), and the energy balance.
//
// Per body with mass m, centre s'_c, inertia J'_c (body axes), r_c = r + A s'_c:
//   inertial force  m r̈_c,   inertial torque  J'ω̇' + ω'×J'ω' + m s'_c × Aᵀ r̈_c.
// A force f at body point s' contributes (f, s' × Aᵀ f).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "analysis/row_selection.hpp"
#include "kinematics/workspace.hpp"

namespace mechkin {

/// One step's forces, SI. Rates are filled when the order is at least 3.
struct ForceResults {
  std::vector<double> effort, effort_rate, power, power_rate;  // per driver
  // Per joint: force and moment (about the joint origin) that body1 exerts on
  // body2, in global axes and in body2's joint frame (f, g, h; h = the axis).
  std::vector<Vec3> force, moment, force_rate, moment_rate;
  std::vector<Vec3> force_joint, moment_joint, force_joint_rate, moment_joint_rate;
  // Per coupler (constraints.md §3.11): the generalized force on each coordinate,
  // Q_k = −c_k λ (a torque on a rotation, a force on a slide, body2 relative to
  // body1), and the power it takes from the first coordinate, −Q_1 q̇_1 (what the
  // mesh transmits; Σ_k Q_k q̇_k = 0). A gear with a pitch radius adds its tooth
  // force to its two bearings' reactions (§3.11.1).
  std::vector<std::array<double, 3>> coupler_effort, coupler_effort_rate;
  std::vector<double> coupler_power, coupler_power_rate;
  double kinetic = 0, potential = 0;
  double balance = 0;  // Σ driver power + Σ load power − d(kinetic + potential)/dt
  bool rates = false;
};

class ForceSolver {
 public:
  /// `order`: the run's derivative order (≥ 2 needed; ≥ 3 gives the rates).
  ForceSolver(const ConstraintSystem& sys, const RowSelection& selection, int order);
  /// λ (and λ̇) at the solved step, then efforts, reactions, energies into `out`.
  /// Needs the step's factorization in `ws` (the whole system, not the block path).
  void Solve(KinematicsWorkspace& ws, const SystemState& s, ForceResults* out);
  /// With redundant equations: the reaction components that are not determined
  /// (found at the first step), in joint vocabulary; empty when all are.
  const std::vector<std::string>& indeterminate() const { return indeterminate_; }

 private:
  void GeneralizedForces(const SystemState& s, bool rates);
  void AddPointForce(const SystemState& s, BodyIndex b, const Vec3& local, const Vec3& f, const Vec3& f_rate, bool rates);
  void AddBodyTorque(const SystemState& s, BodyIndex b, const Vec3& torque_local, const Vec3& rate_local, bool rates);
  void AddInertia(const SystemState& s, int b, bool rates);
  void AddLoads(const SystemState& s, bool rates);
  void AddSpring(const SystemState& s, const Load& load, bool rates);
  void Multipliers(KinematicsWorkspace& ws, const SystemState& s, const Eigen::VectorXd& rhs, Eigen::VectorXd* lambda);
  void Kappa(const SystemState& s);
  void FindIndeterminate(const SystemState& s);
  void Efforts(const SystemState& s, ForceResults* out) const;
  void Reactions(const SystemState& s, ForceResults* out) const;
  void CouplerEfforts(const SystemState& s, ForceResults* out) const;
  void ToothForces(const SystemState& s, ForceResults* out) const;
  void AddReactionChange(const SystemState& s, int j, const BodyKinematics& k, const Vec3& force, const Vec3& force1,
                         const Vec3& moment, const Vec3& moment1, ForceResults* out) const;
  void Energies(const SystemState& s, ForceResults* out) const;

  const ConstraintSystem& sys_;
  const Model& model_;
  RowSelection selection_;
  int order_;
  bool redundant_ = false, checked_indeterminate_ = false;
  std::vector<std::string> indeterminate_;
  Eigen::VectorXd R_, R_rate_, kappa_, rhs_, lambda_active_, lambda_, lambda_rate_;
  Eigen::MatrixXd J_;
};

}  // namespace mechkin
