// Planar F (constraints.md §5): parallel-1 and Φ^DOT_2(h_i, d_ij); two slides in the
// plane and the rotation about its normal.
#include "joints/equations.hpp"

namespace mechkin {

JointDescriptor PlanarJoint() {
  JointDescriptor d;
  d.name = "planar";
  d.frames = JointFrameRule::Normal;
  d.equations =
      Joined({ParallelOne(), {{JointPrimitive::Dot2, FrameAxis::H, FrameAxis::H, {"translation along its normal"}}}});
  d.coordinates = JointCoordinates::PlaneSlidesAndAngle;
  d.planar = PlanarRole::Plane;
  d.glyph = "plate";
  return d;
}

}  // namespace mechkin
