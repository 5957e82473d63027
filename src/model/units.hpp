// Units of a mechanism file (format-v1 "units"). Internally everything is SI:
// lengths in metres, angles in radians, masses in kilograms, forces in newtons.
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
  // "force" and "torque" as the file names them; empty: derived from mass and length.
  std::string force_name, torque_name;
  double named_force_to_si = 0, named_torque_to_si = 0;  // newtons (newton-metres) per named unit
  /// Force unit: the named one, else mass × length / s² ("N" for kg and m); torque:
  /// the named one, else force × length. Energy is in the torque unit ("J" for N*m),
  /// power in energy / s.
  std::string ForceName() const;
  std::string TorqueName() const;
  std::string EnergyName() const;
  std::string PowerName() const;
  double force_to_si() const { return force_name.empty() ? mass_to_si * length_to_si : named_force_to_si; }
  double torque_to_si() const { return torque_name.empty() ? force_to_si() * length_to_si : named_torque_to_si; }
  /// Spring stiffness (force / length) and damping (force · s / length) per SI.
  double stiffness_to_si() const { return force_name.empty() ? mass_to_si : named_force_to_si / length_to_si; }
  /// The table's units: the file's, or SI (m, rad, kg, N, N*m) with `si`.
  Units TableUnits(bool si) const;
};

/// Metres per unit for "m", "mm", "cm", "in"; nullopt for anything else.
std::optional<double> LengthUnitToSi(const std::string& name);
/// Radians per unit for "rad", "deg"; nullopt for anything else.
std::optional<double> AngleUnitToSi(const std::string& name);
/// Kilograms per unit for "kg", "g", "lb"; nullopt for anything else.
std::optional<double> MassUnitToSi(const std::string& name);
/// Newtons per unit for "N", "kN", "mN", "lbf"; nullopt for anything else.
std::optional<double> ForceUnitToSi(const std::string& name);
/// Newton-metres per unit for "N*m", "N*mm", "N*cm", "kN*m", "lbf*in", "lbf*ft"; nullopt otherwise.
std::optional<double> TorqueUnitToSi(const std::string& name);
/// The accepted names, for error messages.
const std::vector<std::string>& LengthUnitNames();
const std::vector<std::string>& AngleUnitNames();
const std::vector<std::string>& MassUnitNames();
const std::vector<std::string>& ForceUnitNames();
const std::vector<std::string>& TorqueUnitNames();

}  // namespace mechkin
