// Screw H (constraints.md §5): parallel-1, parallel-2 and Φ^SDA (§3.10) with the
// file's pitch; rotation and slide coupled.
#include "joints/equations.hpp"

namespace mechkin {

JointDescriptor ScrewJoint() {
  JointDescriptor d;
  d.name = "screw";
  d.frames = JointFrameRule::Axis;
  d.scalar = JointScalar::Pitch;
  d.equations =
      Joined({ParallelOne(),
              ParallelTwo(),
              {{JointPrimitive::Screw, FrameAxis::H, FrameAxis::H, {"slide coupled to rotation by the pitch"}}}});
  d.coordinates = JointCoordinates::AngleAndSlide;
  d.turns = true;
  d.slides = true;
  d.limit = JointLimit::Angle;
  d.relaxations = {"cylindrical"};
  d.glyph = "pin";
  return d;
}

}  // namespace mechkin
