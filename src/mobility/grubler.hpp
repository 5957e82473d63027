// Grübler–Kutzbach count (constraints.md §6):
//   M = 6 n − 5 n_J1 − 4 n_J2 − 3 n_J3 − 1 n_SS,
// i.e. 6 per moving body minus the equations each joint removes, minus one per
// coupler between joint coordinates (§3.11). Drivers are not counted. For a planar mechanism also the planar count 3 n − 2 j₁ − j₂.
#pragma once

#include <optional>

#include "model/model.hpp"

namespace mechkin {

int CalcGrublerCount(const Model& model);

/// A mechanism whose joints keep every body moving parallel to one plane.
struct PlanarStructure {
  Vec3 normal = Vec3::UnitZ();  // of the plane of motion (unit, global)
  int lower_pairs = 0;          // j₁: revolute (axes along the normal) and prismatic (across it)
  int higher_pairs = 0;         // j₂: distance links (one equation in the plane)
  int planar_joints = 0;        // planar joints on the plane: no equation in the plane
  int couplers = 0;             // couplers between joint coordinates: one equation each (§3.11)
  int count = 0;                // 3 n − 2 j₁ − j₂ − couplers
};

/// The planar structure, when at least one joint has an axis and every revolute
/// and planar joint's axis (normal) is parallel to one normal, every prismatic
/// axis normal to it (1e-9), and the other joints are distance links; a spherical,
/// universal, screw or cylindrical joint (whose slide along its axis leaves any
/// plane it turns in) makes a mechanism spatial. nullopt otherwise.
std::optional<PlanarStructure> FindPlanarStructure(const Model& model);

}  // namespace mechkin
