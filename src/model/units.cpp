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

const std::vector<std::string>& MassUnitNames() {
  static const std::vector<std::string> names = {"kg", "g", "lb"};
  return names;
}

std::optional<double> MassUnitToSi(const std::string& name) {
  if (name == "kg") return 1.0;
  if (name == "g") return 1e-3;
  if (name == "lb") return 0.45359237;  // exact by definition
  return std::nullopt;
}

std::string Units::ForceName() const {
  if (mass_name == "kg" && length_name == "m") return "N";
  return mass_name + "*" + length_name + "/s^2";
}
std::string Units::TorqueName() const {
  if (mass_name == "kg" && length_name == "m") return "N*m";
  return mass_name + "*" + length_name + "^2/s^2";
}
std::string Units::EnergyName() const {
  if (mass_name == "kg" && length_name == "m") return "J";
  return mass_name + "*" + length_name + "^2/s^2";
}
std::string Units::PowerName() const {
  if (mass_name == "kg" && length_name == "m") return "W";
  return mass_name + "*" + length_name + "^2/s^3";
}

}  // namespace mechkin
