// One interface over the factorizations of Φ_q that a run uses: the dense and
// the sparse LU of the whole Jacobian (NewtonSolver) and the block-triangular
// solve (BlockSolver). The step engine only talks to this interface.
#pragma once

#include <Eigen/Core>

#include "constraints/system.hpp"

namespace mechkin {

class Factorization {
 public:
  virtual ~Factorization() = default;
  /// Factorizes Φ_q (ω' columns, active rows) at the current pose; false if singular.
  virtual bool Factorize(const SystemState& s) = 0;
  /// Solves Φ_q x = b with the current factorization; false when this
  /// factorization cannot (the block path solves only the blocks it needs).
  virtual bool SolveLinear(const Eigen::VectorXd& b, Eigen::VectorXd* x) = 0;
  /// Solves Φ_qᵀ x = b (reaction forces: Φ_qᵀλ = Q); false when not available.
  virtual bool SolveLinearTranspose(const Eigen::VectorXd& b, Eigen::VectorXd* x) = 0;
  /// sign(det Φ_q): it flips exactly where the path crosses a singular position.
  virtual double Sign() = 0;
  /// Estimate of cond(Φ_q) from the current factorization.
  virtual double ConditionEstimate() = 0;
  /// A sharper estimate after ConditionEstimate at the same pose: `steps` more
  /// iterations on (J_sᵀJ_s)⁻¹ (a solve and a transposed solve each) from its vector,
  /// which converge to 1/σ_min where the one-step estimate lags a collapsing pivot
  /// (error bounds near singular positions, constraints.md §8). The one-step
  /// estimate where no transposed solve is available.
  virtual double SharperConditionEstimate(int steps) = 0;
};

}  // namespace mechkin
