#include "model/units.hpp"

#include <cmath>

namespace mechkin {

const std::vector<std::string>& LengthUnitNames() {
  static const std::vector<std::string> names = {"m", "mm", "cm", "in"};
  return names;
}
const std::vector<std::string>& AngleUnitNames() {
  static const std::vector<std::string> names = {"rad", "deg"};
  return names;
}

std::optional<double> LengthUnitToSi(const std::string& name) {
  if (name == "m") return 1.0;
  if (name == "mm") return 1e-3;
  if (name == "cm") return 1e-2;
  if (name == "in") return 0.0254;  // exact by definition
  return std::nullopt;
}

std::optional<double> AngleUnitToSi(const std::string& name) {
  if (name == "rad") return 1.0;
  if (name == "deg") return M_PI / 180.0;
  return std::nullopt;
}

}  // namespace mechkin
