#include "joints/descriptor.hpp"
#include "joints/equations.hpp"

#include <algorithm>

namespace mechkin {

int JointDescriptor::Rows() const {
  int rows = 0;
  for (const JointEquation& e : equations) rows += static_cast<int>(e.rows.size());
  return rows;
}

bool JointDescriptor::HoldsPoints() const {
  return std::any_of(equations.begin(), equations.end(), [](const JointEquation& e) {
    return e.primitive == JointPrimitive::Spherical || e.primitive == JointPrimitive::Distance;
  });
}

namespace {

std::vector<std::string> FrameKeys(JointFrameRule rule) {
  switch (rule) {
    case JointFrameRule::Axis:
      return {"origin", "axis"};
    case JointFrameRule::Normal:
      return {"origin", "normal"};
    case JointFrameRule::CrossAxes:
      return {"origin", "axis1", "axis2"};
    case JointFrameRule::Point:
      return {"origin"};
    case JointFrameRule::TwoPoints:
      return {"point1", "point2"};
  }
  return {};
}

}  // namespace

std::vector<std::string> JointDescriptor::RequiredKeys() const {
  std::vector<std::string> keys = FrameKeys(frames);
  if (scalar == JointScalar::Pitch) keys.push_back("pitch");
  return keys;
}

std::vector<std::string> JointDescriptor::OptionalKeys() const {
  std::vector<std::string> keys;
  if (limit != JointLimit::None) keys.push_back("limits");
  if (scalar == JointScalar::Length) keys.push_back("length");
  return keys;
}

// On markers the markers are the frame: the scalars stay (a screw's pitch, a link's
// optional length), and so do the limits.
std::vector<std::string> JointDescriptor::MarkerRequiredKeys() const {
  if (scalar == JointScalar::Pitch) return {"pitch"};
  return {};
}

std::vector<std::string> JointDescriptor::MarkerOptionalKeys() const {
  std::vector<std::string> keys;
  if (scalar == JointScalar::Length) keys.push_back("length");
  if (limit != JointLimit::None) keys.push_back("limits");
  return keys;
}

JointEquation SphericalEquation() {
  return {JointPrimitive::Spherical,
          FrameAxis::H,
          FrameAxis::H,
          {"translation along global x", "translation along global y", "translation along global z"}};
}

std::vector<JointEquation> ParallelOne() {
  return {{JointPrimitive::Dot1, FrameAxis::F, FrameAxis::H, {"rotation about its frame's g axis"}},
          {JointPrimitive::Dot1, FrameAxis::G, FrameAxis::H, {"rotation about its frame's f axis"}}};
}

std::vector<JointEquation> ParallelTwo() {
  return {{JointPrimitive::Dot2, FrameAxis::F, FrameAxis::H, {"translation along its frame's f axis"}},
          {JointPrimitive::Dot2, FrameAxis::G, FrameAxis::H, {"translation along its frame's g axis"}}};
}

std::vector<JointEquation> Joined(const std::vector<std::vector<JointEquation>>& groups) {
  std::vector<JointEquation> out;
  for (const auto& g : groups) out.insert(out.end(), g.begin(), g.end());
  return out;
}

}  // namespace mechkin
