// Revolute R (constraints.md §5): Φ^SPH and parallel-1; one rotation about h.
#include "joints/equations.hpp"

namespace mechkin {

JointDescriptor RevoluteJoint() {
  JointDescriptor d;
  d.name = "revolute";
  d.frames = JointFrameRule::Axis;
  d.equations = Joined({{SphericalEquation()}, ParallelOne()});
  d.coordinates = JointCoordinates::Angle;
  d.turns = true;
  d.limit = JointLimit::Angle;
  d.planar = PlanarRole::Turn;
  d.relaxations = {"cylindrical", "universal", "spherical"};
  d.glyph = "pin";
  return d;
}

}  // namespace mechkin
