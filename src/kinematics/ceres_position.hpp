// Position solve with Ceres Solver, behind a thin adapter (style example 4):
// one residual block per constraint entry, parameter blocks r_k (3) and p_k (4)
// per moving body, analytic Jacobians from the constraint library.
//
// Unit Euler parameters: both ways are implemented, the manifold is the default.
//  * ceres::QuaternionManifold (scalar first, like p): p stays unit exactly, and
//    Φ_p = 2Φ_π'G is the gradient of Φ(p/|p|), what the manifold's chain rule needs.
//  * A normalization residual pᵀp − 1 per body: n more equations, whose weight
//    against the constraint rows is arbitrary, and p drifts off the unit sphere
//    between iterations.
// Measured (./build/tools/bench_ceres, 60 tracking steps, iterations per step and
// time per step): slider-crank 4.7 vs 5.7 it., 100 vs 119 µs; Bennett 19 vs 27 it.,
// 216 vs 307 µs; Stewart platform 37 vs 39 it., 172 vs 179 µs — the manifold wins.
#pragma once

#include "kinematics/position.hpp"

namespace mechkin {

/// How the Euler parameters stay unit inside Ceres.
enum class CeresUnitQuaternion { Manifold, NormalizationResidual };

/// Minimizes Σ (Φ_k / L^power_k)² over `rows` from the state's pose; success only
/// if the scaled residual ends ≤ tolerance (a least-squares minimum of an
/// impossible mechanism is not an assembly).
SolveSummary SolvePositionCeres(const ConstraintSystem& sys, const std::vector<int>& rows, const SolveOptions& options,
                                SystemState* s, CeresUnitQuaternion unit = CeresUnitQuaternion::Manifold);

}  // namespace mechkin
