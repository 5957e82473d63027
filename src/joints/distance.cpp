// Distance SS (constraints.md §5): Φ^SPH_SPH (§3.2) between point1 on body1 and
// point2 on body2, length L > 0; five freedoms.
#include "joints/descriptor.hpp"

namespace mechkin {

JointDescriptor DistanceJoint() {
  JointDescriptor d;
  d.name = "distance";
  d.frames = JointFrameRule::TwoPoints;
  d.scalar = JointScalar::Length;
  d.equations = {{JointPrimitive::Distance, FrameAxis::H, FrameAxis::H, {"distance between its two points"}}};
  d.coordinates = JointCoordinates::None;
  d.planar = PlanarRole::Link;
  d.glyph = "link";
  return d;
}

}  // namespace mechkin
