// Units of a mechanism file (format-v1 "units"). Internally everything is SI:
// lengths in metres, angles in radians.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace mechkin {

struct Units {
  std::string length_name = "m";
  std::string angle_name = "rad";
  double length_to_si = 1.0;  // metres per file length unit
  double angle_to_si = 1.0;   // radians per file angle unit
  std::string mass_name = "kg";
  double mass_to_si = 1.0;    // kilograms per file mass unit
  /// Force unit: mass × length / s² ("N" for kg and m), and torque: force × length.
  std::string ForceName() const;
  std::string TorqueName() const;
  std::string EnergyName() const;
  std::string PowerName() const;
  double force_to_si() const { return mass_to_si * length_to_si; }
  double torque_to_si() const { return force_to_si() * length_to_si; }
};

/// Metres per unit for "m", "mm", "cm", "in"; nullopt for anything else.
std::optional<double> LengthUnitToSi(const std::string& name);
/// Radians per unit for "rad", "deg"; nullopt for anything else.
std::optional<double> AngleUnitToSi(const std::string& name);
/// Kilograms per unit for "kg", "g", "lb"; nullopt for anything else.
std::optional<double> MassUnitToSi(const std::string& name);
/// The accepted names, for error messages.
const std::vector<std::string>& LengthUnitNames();
const std::vector<std::string>& AngleUnitNames();
const std::vector<std::string>& MassUnitNames();

}  // namespace mechkin
