// Universal U (constraints.md §5): Φ^SPH and Φ^DOT_1(h_i, h_j), h_i = axis1 on
// body1, h_j = axis2 on body2; two rotations about the cross axes.
#include "joints/descriptor.hpp"

namespace mechkin {

JointDescriptor UniversalJoint() {
  JointDescriptor d;
  d.name = "universal";
  d.frames = JointFrameRule::CrossAxes;
  d.equations = {
      SphericalEquation(),
      {JointPrimitive::Dot1, FrameAxis::H, FrameAxis::H, {"rotation about the common normal of its two axes"}}};
  d.coordinates = JointCoordinates::TwoAngles;
  d.relaxations = {"spherical"};
  d.glyph = "cross";
  return d;
}

}  // namespace mechkin
