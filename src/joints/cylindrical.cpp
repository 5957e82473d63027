// Cylindrical C (constraints.md §5): parallel-1 and parallel-2; rotation about and
// slide along h.
#include "joints/equations.hpp"

namespace mechkin {

JointDescriptor CylindricalJoint() {
  JointDescriptor d;
  d.name = "cylindrical";
  d.frames = JointFrameRule::Axis;
  d.equations = Joined({ParallelOne(), ParallelTwo()});
  d.coordinates = JointCoordinates::AngleAndSlide;
  d.turns = true;
  d.slides = true;
  d.limit = JointLimit::Slide;
  d.relaxations = {"planar"};
  d.glyph = "sleeve";
  return d;
}

}  // namespace mechkin
