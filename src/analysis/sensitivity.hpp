// Parameter sensitivities along the motion (issue "Parametric designs", item 4).
//
// At a solved step the constraints hold for every parameter value p, so by the
// implicit-function theorem (constraints.md §1.6 differentiated in p):
//   order 0:  Φ_q δq = −∂Φ/∂p
//   order k:  Φ_q δq^(k) = −∂/∂(q, q̇, …, q^(k−1), p) [Φ_q q^(k) − RHS_k] · (δq, …, δq^(k−1), 1)
// with the step's own factorization of Φ_q: one back-solve per parameter and order.
// The right-hand sides are directional derivatives of residuals the constraint
// families already evaluate, taken as central differences between the model
// compiled at p − h and at p + h (the same file, the parameter overridden) on
// states moved by ∓h δ in the ω' chart (δr, body-frame δπ'). Φ is at most
// quadratic in the local geometry, so the differences carry round-off only
// (≈ u/h ≈ 1e-11 relative for h = 5e-6 of the parameter's scale); the
// sensitivity itself is the solve, not a difference of re-solved runs.
//
// The perturbed states s ± h δ (all orders) are kept: any reported quantity's
// total derivative d o/dp = [o(model₊, s₊) − o(model₋, s₋)] / 2h includes the
// output's own ∂o/∂p (a point whose coordinates are parameters).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "kinematics/workspace.hpp"
#include "model/model.hpp"

namespace mechkin {

class SensitivitySolver {
 public:
  /// Compiles the model at p ± h for each named parameter. Throws
  /// std::invalid_argument (a message for the user) for an unknown name or a
  /// parameter that changes the analysis span or the mechanism's structure.
  SensitivitySolver(const Model& model, const std::vector<std::string>& names, int order);
  ~SensitivitySolver();

  /// δq^(k), k = 0..order, for every parameter at the solved, factorized step `s`;
  /// then the perturbed states. Returns false when the factorization cannot solve.
  bool Solve(KinematicsWorkspace& ws, const SystemState& s);

  int size() const { return static_cast<int>(variants_.size()); }
  const std::string& name(int k) const;
  double step(int k) const;  // h, in the parameter's unit
  /// The model compiled at p + h (sign > 0) or p − h, and the state s ± h δ.
  const Model& model(int k, int sign) const;
  const SystemState& state(int k, int sign) const;

 private:
  struct Side;
  struct Variant;
  void SolveOrder(KinematicsWorkspace& ws, const SystemState& s, Variant& v, int k);
  void PerturbedState(const SystemState& s, const Variant& v, int upto, double sign, Side& side) const;

  int order_;
  std::vector<std::unique_ptr<Variant>> variants_;
  std::vector<int> rows_;  // the active rows the Jacobians were built for
  // full_: all rows (Φ, RHS_k); the others the active rows, so no buffer changes size per order.
  Eigen::VectorXd full_, plus_, minus_, rhs_, x_, dx_;
};

/// The finite-difference step of a parameter: 5e-6 of its scale (its value, else
/// its tolerance, else its range, else 1).
double SensitivityStep(const Parameter& p);

}  // namespace mechkin
