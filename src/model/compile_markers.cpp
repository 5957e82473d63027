// Markers: frames fixed in a body (its own coordinates, SI), which joints and
// point outputs name instead of global design coordinates.
#include <algorithm>
#include <cmath>

#include "model/compiler.hpp"

namespace mechkin {

// h along the marker's axis (default the body's z), f toward x_axis (default the
// body's x) made normal to h (constraints.md §4): without x_axis and axis, the
// marker's frame is its body's axes moved to the point.
void Compiler::CompileMarkers(BodyIndex body, const std::vector<MarkerSpec>& markers) {
  auto& table = markers_[body];
  for (const MarkerSpec& m : markers) {
    auto point = LengthVector(m.point);
    std::optional<Vec3> axis = Vec3::UnitZ(), x = Vec3::UnitX();
    if (m.axis) axis = Vector(m.axis, true);
    if (m.x_axis) x = Vector(m.x_axis, true);
    if (point && axis && x && m.x_axis && axis->normalized().cross(x->normalized()).norm() < 1e-6) {
      Error(m.pointer + "/x_axis", "'x_axis' is parallel to 'axis': it fixes no direction",
            "give a direction across the axis");
      x.reset();
    }
    if (!point || !axis || !x)
      table.emplace(m.name, std::nullopt);  // known name, invalid marker
    else
      table.emplace(m.name, MakeFrame(*point, *axis, *x));
  }
}

// Marker `name` of `body` (body coordinates); an error when unknown, silence when
// the marker itself failed.
std::optional<JointFrame> Compiler::Marker(BodyIndex body, const std::optional<std::string>& name,
                                           const std::string& ptr) {
  if (!name) return std::nullopt;
  const auto& table = markers_[body];
  if (const auto it = table.find(*name); it != table.end()) return it->second;
  std::vector<std::string> names;
  for (const auto& kv : table) names.push_back(kv.first);
  const std::string g = DidYouMean(*name, names);
  const std::string owner = body == kGround ? std::string("ground") : "body '" + model_.BodyName(body) + "'";
  const std::string declare = body == kGround ? "declare it in the top-level \"ground\": {\"markers\": {...}}"
                                              : "declare it in the body's \"markers\"";
  Error(ptr, "unknown marker '" + Shorten(*name) + "' on " + owner,
        !g.empty() ? "did you mean '" + g + "'?" : names.empty() ? declare : "markers of " + owner + ": " + Join(names));
  return std::nullopt;
}

// A joint on two markers: its frames are the markers' (already in body coordinates),
// so its coordinate is 0 where the markers coincide, not at the pose drawn.
void Compiler::CompileMarkerJoint(const JointSpec& j, const JointDescriptor& type, const std::string* name,
                                  std::optional<BodyIndex> body1, std::optional<BodyIndex> body2) {
  const std::string& ptr = j.pointer;
  std::optional<JointFrame> m1, m2;
  if (body1) m1 = Marker(*body1, j.marker1, ptr + "/marker1");
  if (body2) m2 = Marker(*body2, j.marker2, ptr + "/marker2");
  Joint joint;
  joint.type = &type;
  bool ok = name && m1 && m2;
  if (type.scalar == JointScalar::Pitch) ok = CompileScrewPitch(j, &joint) && ok;
  if (!ok) return;
  const auto [r1, A1] = Pose(*body1);
  const auto [r2, A2] = Pose(*body2);
  const bool posed = HasFilePose(*body1) && HasFilePose(*body2);  // else the assembly places them
  if (type.frames == JointFrameRule::CrossAxes && posed) {
    const double c = (A1 * m1->h).dot(A2 * m2->h);
    if (std::abs(c) > 1e-6) {
      Error(ptr + "/marker2",
            "universal joint axes are not perpendicular (angle " +
                std::to_string(std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI) + " deg)",
            "give marker2 an axis perpendicular to marker1's (the cross axes of a Hooke joint are at 90 deg)");
      return;
    }
  }
  if (type.scalar == JointScalar::Length && !posed && !j.length) {
    Error(ptr, "distance link '" + *name + "' has no 'length' and a body without a position",
          "give the link's \"length\" (or positions of both bodies, whose distance is then the length)");
    return;
  }
  if (type.scalar == JointScalar::Length &&
      !CompileDistanceLength(j, r1 + A1 * m1->origin, r2 + A2 * m2->origin, true, "/marker2", &joint))
    return;
  joint.name = *name;
  joint.body1 = *body1;
  joint.body2 = *body2;
  joint.frame1 = *m1;
  joint.frame2 = *m2;
  joint.on_markers = true;
  joint_index_[joint.name] = static_cast<int>(model_.joints.size());
  model_.joints.push_back(joint);
}

}  // namespace mechkin
