// Position solve with Ceres Solver, behind a thin adapter (style example 4):
// one residual block per constraint entry, parameter blocks r_k (3) and p_k (4)
// per moving body, analytic Jacobians from the constraint library.
//
// Unit Euler parameters: ceres::QuaternionManifold (scalar first, like p).
// The alternative, a normalization residual pᵀp − 1 per body, was rejected: it
// adds n equations whose weight against the constraint rows is arbitrary, and
// between iterations p drifts off the unit sphere so that A(p) is not a
// rotation; the manifold keeps p unit exactly, and our Φ_p = 2Φ_π'G is the
// gradient of Φ(p/|p|), which is exactly what the manifold's chain rule needs.
#pragma once

#include "solvers/position.hpp"

namespace mechkin {

/// Minimizes Σ (Φ_k / L^power_k)² over `rows` from the state's pose; success only
/// if the scaled residual ends ≤ tolerance (a least-squares minimum of an
/// impossible mechanism is not an assembly).
SolveSummary SolvePositionCeres(const ConstraintSystem& sys, const std::vector<int>& rows, const SolveOptions& options,
                                SystemState* s);

}  // namespace mechkin
