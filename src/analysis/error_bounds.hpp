// Relative error bounds per derivative order from the condition estimate.
#pragma once

namespace mechkin {

/// With κ the one-step condition estimate, r the scaled residual and u the unit
/// round-off (constraints.md §8):
///   e_0 = κ·max(r, 4u),   e_k = 8u·κ^k + κ·e_0   (k ≥ 1):
/// each solve's round-off is amplified by about κ per order, and the pose's error
/// perturbs Φ_q once more. Where the error of the orders below does grow by κ per
/// order (the piston's regular rows, κ ≈ 5) this understates the jerk up to 30×;
/// 2κ^k·(e_0 + 8u) would hold there but overstates the bundled four-bar's jerk 1e4× (its
/// errors do not grow with the order): only measuring tells, so a run measures a sample
/// of its rows and raises these bounds where the samples ask (bound_sampling.hpp), and
/// the rows near singular positions whole (row_error_estimate.hpp). Relative to
/// the magnitude of q^(k) over the motion. Checked against closed forms in
/// python/tests/test_error_bounds.py and tests/extremes/assembly_test.cpp.
/// Fills bound[0..max_order].
void CalcErrorBounds(double condition, double residual, int max_order, double* bound);

/// The scaled residual at which the residual's share of those bounds meets the
/// tolerance for every order up to `order`: κ·r ≤ tol (position) and κ²·r ≤ tol
/// (every derivative), never below the round-off floor 16u. The tolerance is then on
/// the answer, not only on the residual (issue "Right at every order", item 2).
double ResidualForAccuracy(double tolerance, double condition, int order);

/// True when that residual lies below the double round-off floor, so that only an
/// extended-precision residual (NewtonSolver's accuracy phase) can deliver it, and the
/// row is approaching a singular position: κ ≥ 100 and at least 10 times the smallest
/// condition seen along the run (`regular_condition`). A κ that is high all along (a
/// long geared chain: 6e3 at every row) costs no digits per derivative order the way a
/// dead centre does, and there the phase would cost more than it gains.
bool NeedsExtendedResidual(double tolerance, double condition, double regular_condition, int order);

}  // namespace mechkin
