// Constants every layer reads the same way.
#pragma once

#include <limits>

namespace mechkin {

/// A value not computed (a column or report field with no number: written as an empty
/// CSV cell or JSON null by the io layer).
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace mechkin
