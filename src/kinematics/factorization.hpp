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
};

}  // namespace mechkin
