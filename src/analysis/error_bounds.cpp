#include "analysis/error_bounds.hpp"

#include <algorithm>
#include <limits>

namespace mechkin {

void CalcErrorBounds(double condition, double residual, int max_order, double* bound) {
  const double u = std::numeric_limits<double>::epsilon() / 2;
  bound[0] = condition * std::max(residual, 4 * u);
  double kk = 1;
  for (int k = 1; k <= max_order; ++k) {
    kk *= condition;
    bound[k] = 8 * u * kk + condition * bound[0];
  }
}

namespace {

// No residual below the round-off floor 16u is reachable in double; asking for one
// would only spend iterations that cannot halve it.
constexpr double kResidualFloor = 16 * std::numeric_limits<double>::epsilon() / 2;

// Below this condition number a double solve is already within a few units of κ·u
// and the extended phase gains at most κ there, for about 80 % more time per step at
// --tol 1e-14 (planar four-bar: 5.3 → 10 µs); above it, near a dead centre, the double
// floor is what limits the derivatives (the piston: jerk 3.7e-5 → 1.9e-7). A condition
// that has not grown 10× over the run's best is the mechanism's gearing, not an
// approaching singular position (a chain of 100 four-bars, κ 5.5e3–6.5e3 throughout:
// the phase changed its table by 5e-11 relative for 50 % more time per step).
constexpr double kMinExtendedCondition = 100;
constexpr double kMinConditionGrowth = 10;

double UnclampedResidual(double tolerance, double condition, int order) {
  const double k = std::max(condition, 1.0);
  return order >= 1 ? tolerance / (k * k) : tolerance / k;
}

}  // namespace

double ResidualForAccuracy(double tolerance, double condition, int order) {
  return std::max(kResidualFloor, UnclampedResidual(tolerance, condition, order));
}

bool NeedsExtendedResidual(double tolerance, double condition, double regular_condition, int order) {
  return condition >= kMinExtendedCondition && condition >= kMinConditionGrowth * regular_condition &&
         UnclampedResidual(tolerance, condition, order) < kResidualFloor;
}

}  // namespace mechkin
