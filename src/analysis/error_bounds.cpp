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

}  // namespace mechkin
