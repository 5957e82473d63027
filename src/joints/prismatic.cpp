// Prismatic P (constraints.md §5): parallel-1, parallel-2 and Φ^DOT_1(f_i, g_j),
// regular at θ = 0 ("Prismatic with aligned frames"); one slide along h.
#include "joints/equations.hpp"

namespace mechkin {

JointDescriptor PrismaticJoint() {
  JointDescriptor d;
  d.name = "prismatic";
  d.frames = JointFrameRule::Axis;
  d.equations = Joined({ParallelOne(),
                        ParallelTwo(),
                        {{JointPrimitive::Dot1, FrameAxis::F, FrameAxis::G, {"rotation about its axis"}}}});
  d.coordinates = JointCoordinates::Slide;
  d.slides = true;
  d.limit = JointLimit::Slide;
  d.planar = PlanarRole::Slide;
  d.relaxations = {"cylindrical"};
  d.glyph = "slider";
  return d;
}

}  // namespace mechkin
