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

const std::vector<std::string>& ForceUnitNames() {
  static const std::vector<std::string> names = {"N", "kN", "mN", "lbf"};
  return names;
}

// lbf: the pound mass under standard gravity, 0.45359237 kg × 9.80665 m/s² (exact).
constexpr double kPoundForce = 4.4482216152605;

std::optional<double> ForceUnitToSi(const std::string& name) {
  if (name == "N") return 1.0;
  if (name == "kN") return 1e3;
  if (name == "mN") return 1e-3;
  if (name == "lbf") return kPoundForce;
  return std::nullopt;
}

const std::vector<std::string>& TorqueUnitNames() {
  static const std::vector<std::string> names = {"N*m", "N*mm", "N*cm", "kN*m", "lbf*in", "lbf*ft"};
  return names;
}

std::optional<double> TorqueUnitToSi(const std::string& name) {
  if (name == "N*m") return 1.0;
  if (name == "N*mm") return 1e-3;
  if (name == "N*cm") return 1e-2;
  if (name == "kN*m") return 1e3;
  if (name == "lbf*in") return kPoundForce * 0.0254;
  if (name == "lbf*ft") return kPoundForce * 0.3048;
  return std::nullopt;
}

std::string Units::ForceName() const {
  if (!force_name.empty()) return force_name;
  if (mass_name == "kg" && length_name == "m") return "N";
  return mass_name + "*" + length_name + "/s^2";
}
std::string Units::TorqueName() const {
  if (!torque_name.empty()) return torque_name;
  if (!force_name.empty()) return force_name + "*" + length_name;
  if (mass_name == "kg" && length_name == "m") return "N*m";
  return mass_name + "*" + length_name + "^2/s^2";
}
// Energy in the torque unit: a named one (or one derived from a named force) spelled
// as the torque, N*m and kN*m as J and kJ; otherwise as before the force keys.
std::string Units::EnergyName() const {
  if (!force_name.empty() || !torque_name.empty()) {
    const std::string t = TorqueName();
    return t == "N*m" ? "J" : t == "kN*m" ? "kJ" : t;
  }
  if (mass_name == "kg" && length_name == "m") return "J";
  return mass_name + "*" + length_name + "^2/s^2";
}
std::string Units::PowerName() const {
  if (!force_name.empty() || !torque_name.empty()) {
    const std::string t = TorqueName();
    return t == "N*m" ? "W" : t == "kN*m" ? "kW" : t + "/s";
  }
  if (mass_name == "kg" && length_name == "m") return "W";
  return mass_name + "*" + length_name + "^2/s^3";
}

Units Units::TableUnits(bool si) const {
  if (!si) return *this;
  Units u;  // m, rad, kg; forces derived: N, N*m, J, W
  return u;
}

}  // namespace mechkin
