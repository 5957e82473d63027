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
};

/// Metres per unit for "m", "mm", "cm", "in"; nullopt for anything else.
std::optional<double> LengthUnitToSi(const std::string& name);
/// Radians per unit for "rad", "deg"; nullopt for anything else.
std::optional<double> AngleUnitToSi(const std::string& name);
/// The accepted names, for error messages.
const std::vector<std::string>& LengthUnitNames();
const std::vector<std::string>& AngleUnitNames();

}  // namespace mechkin
