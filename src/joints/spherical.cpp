// Spherical S (constraints.md §5): Φ^SPH; three rotations about the common point.
#include "joints/descriptor.hpp"

namespace mechkin {

JointDescriptor SphericalJoint() {
  JointDescriptor d;
  d.name = "spherical";
  d.frames = JointFrameRule::Point;
  d.equations = {SphericalEquation()};
  d.coordinates = JointCoordinates::Orientation;
  d.glyph = "ball";
  return d;
}

}  // namespace mechkin
