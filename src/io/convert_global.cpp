// `mechkin convert --to global`: every joint on markers gets its global geometry
// (origin and axes where its markers are at the design pose), point outputs on
// markers get their global point, and the markers, then unused, are dropped.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/convert_internal.hpp"
#include "model/frames.hpp"

namespace mechkin::convert {

namespace {

const MarkerSpec* FindMarker(const Context& ctx, BodyIndex b, const std::optional<std::string>& name) {
  if (!name) return nullptr;
  const std::vector<MarkerSpec>* markers = &ctx.spec.ground_markers;
  if (b != kGround) {
    const BodySpec* body = ctx.Body(b);
    if (!body) return nullptr;
    markers = &body->markers;
  }
  for (const MarkerSpec& m : *markers)
    if (m.name == *name) return &m;
  return nullptr;
}

bool MovedFromSketch(const Context& ctx, BodyIndex b);

// A body point of the file (a marker's) in global design coordinates: exact for
// ground and for a body drawn unrotated at a written position the assembly kept
// (the sum of the texts).
Json GlobalPoint(const Context& ctx, BodyIndex b, const MarkerSpec& m, const Vec3& local_si) {
  if (b == kGround) return VectorJson(*m.point);
  const BodySpec* body = ctx.Body(b);
  if (body && body->position && LiteralIdentity(body->orientation) && !MovedFromSketch(ctx, b)) {
    Json out = Json::array();
    for (int k = 0; k < 3; ++k) out.push_back(Sum(body->position->c[k], m.point->c[k], ctx.scale));
    return out;
  }
  if (UsesParameters(m.point) || (body && (UsesParameters(body->position) || UsesParameters(body->orientation))))
    ctx.Note(m.pointer + "/point", "written in global coordinates at the current parameter values (body '" +
                                       ctx.model.bodies[b].name + "' is rotated or placed by the assembly)");
  const auto [r, A] = ctx.Pose(b);
  return NumberVector((r + A * local_si) / ctx.unit, ctx.scale);
}

// A marker's axis (default: its body's z) in global axes.
Json GlobalAxis(const Context& ctx, BodyIndex b, const MarkerSpec& m, const Vec3& local_h) {
  const BodySpec* body = b == kGround ? nullptr : ctx.Body(b);
  // the body's file orientation holds unless the assembly placed or moved it
  const bool placed = b != kGround && ctx.model.assembly &&
                      b < static_cast<int>(ctx.model.assembly->sketched.size()) &&
                      (!ctx.model.assembly->sketched[b] || MovedFromSketch(ctx, b));
  if (b == kGround || (body && LiteralIdentity(body->orientation) && !placed))
    return m.axis ? VectorJson(*m.axis) : Json::array({0, 0, 1});
  if (UsesParameters(m.axis) || (body && UsesParameters(body->orientation)))
    ctx.Note(m.pointer + "/axis", "written in global axes at the current parameter values (body '" +
                                      ctx.model.bodies[b].name + "' is rotated)");
  return NumberVector(ctx.Pose(b).second * local_h, 1);
}

JointFrame GlobalFrame(const Context& ctx, BodyIndex b, const JointFrame& local) {
  const auto [r, A] = ctx.Pose(b);
  JointFrame g;
  g.origin = r + A * local.origin;
  g.f = A * local.f;
  g.g = A * local.g;
  g.h = A * local.h;
  return g;
}

double Degrees(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI;
}

bool NamedByJointOutput(const Context& ctx, const std::string& joint) {
  return std::any_of(ctx.spec.outputs.begin(), ctx.spec.outputs.end(), [&](const OutputSpec& o) {
    return o.type && *o.type == "joint" && o.joint && *o.joint == joint;
  });
}

// A joint whose coordinate something reads: a driver on it or a joint output.
// (Branch hints are rewritten to the design-pose zero instead: RebaseHints.)
bool CoordinateObserved(const Context& ctx, const std::string& joint) {
  const bool driven = std::any_of(ctx.spec.drivers.begin(), ctx.spec.drivers.end(),
                                  [&](const DriverSpec& d) { return d.joint && *d.joint == joint; });
  return driven || NamedByJointOutput(ctx, joint);
}

// The revolute coordinate at the design pose (rad): marker 2's x from marker 1's about the axis.
double DesignAngle(const JointFrame& g1, const JointFrame& g2) {
  return std::atan2(g1.f.cross(g2.f).dot(g1.h), g1.f.dot(g2.f));
}

// Why the global form cannot say this marker joint (empty: it can). The global
// form fixes one frame in both bodies where they are drawn, so the markers must
// coincide at the design pose; a joint output of a universal, planar or spherical
// joint also reads the frame's own x axis, which the global form chooses itself.
std::string Mismatch(const Context& ctx, const Joint& jm) {
  const JointFrame g1 = GlobalFrame(ctx, jm.body1, jm.frame1), g2 = GlobalFrame(ctx, jm.body2, jm.frame2);
  const double gap = (g1.origin - g2.origin).norm(), tol = 1e-9;
  std::ostringstream why;
  const JointFrameRule rule = jm.type->frames;
  const bool one_axis = rule == JointFrameRule::Axis || rule == JointFrameRule::Normal;  // h shared by both
  if (rule != JointFrameRule::TwoPoints && gap > tol * ctx.model.characteristic_length)
    why << "its markers are " << gap / ctx.unit << " " << ctx.model.units.length_name << " apart at the design pose";
  else if (one_axis && (g1.h - g2.h).norm() > tol)
    why << "its markers' axes are " << Degrees(g1.h, g2.h) << " deg apart at the design pose";
  else if (one_axis && (g1.f - g2.f).norm() > tol && CoordinateObserved(ctx, jm.name))
    why << "its markers are turned " << Degrees(g1.f, g2.f)
        << " deg about the axis at the design pose (its coordinate is not 0 there)";
  if (!why.str().empty() || !NamedByJointOutput(ctx, jm.name)) return why.str();
  bool own_axes = true;
  if (rule == JointFrameRule::CrossAxes)
    own_axes = (g1.f - AnyPerpendicular(g1.h)).norm() <= tol &&
               (g2.f - MakeFrame(Vec3::Zero(), g2.h, g1.h).f).norm() <= tol;
  if (rule == JointFrameRule::Normal) own_axes = (g1.f - AnyPerpendicular(g1.h)).norm() <= tol;
  if (rule == JointFrameRule::Point)
    own_axes = (g1.f - Vec3::UnitX()).norm() <= tol && (g1.h - Vec3::UnitZ()).norm() <= tol &&
               (g2.f - Vec3::UnitX()).norm() <= tol && (g2.h - Vec3::UnitZ()).norm() <= tol;
  if (!own_axes) why << "a joint output reads its markers' x axes, which the global form does not keep";
  return why.str();
}

// The joint with "marker1"/"marker2" replaced by its global geometry keys.
Json JointOnGlobal(const Json& joint, const Json& geometry) {
  Json out = Json::object();
  for (const auto& item : joint.items()) {
    if (item.key() == "marker1")
      for (const auto& g : geometry.items()) out[g.key()] = g.value();
    if (item.key() != "marker1" && item.key() != "marker2") out[item.key()] = item.value();
  }
  return out;
}

Json GlobalGeometry(const Context& ctx, const Joint& jm, const MarkerSpec& m1, const MarkerSpec& m2) {
  Json g = Json::object();
  const JointFrameRule rule = jm.type->frames;
  if (rule == JointFrameRule::TwoPoints) {
    g["point1"] = GlobalPoint(ctx, jm.body1, m1, jm.frame1.origin);
    g["point2"] = GlobalPoint(ctx, jm.body2, m2, jm.frame2.origin);
    return g;
  }
  g["origin"] = GlobalPoint(ctx, jm.body1, m1, jm.frame1.origin);
  if (rule == JointFrameRule::CrossAxes) {
    g["axis1"] = GlobalAxis(ctx, jm.body1, m1, jm.frame1.h);
    g["axis2"] = GlobalAxis(ctx, jm.body2, m2, jm.frame2.h);
  } else if (rule == JointFrameRule::Normal) {
    g["normal"] = GlobalAxis(ctx, jm.body1, m1, jm.frame1.h);
  } else if (rule != JointFrameRule::Point) {
    g["axis"] = GlobalAxis(ctx, jm.body1, m1, jm.frame1.h);
  }
  return g;
}

bool ConvertJoints(const Context& ctx, Json* doc, std::string* error) {
  for (size_t k = 0; k < ctx.spec.joints.size() && k < (*doc)["joints"].size(); ++k) {
    const JointSpec& js = ctx.spec.joints[k];
    if (!js.marker1 && !js.marker2) continue;
    const auto it = js.name ? ctx.joint_index.find(*js.name) : ctx.joint_index.end();
    if (it == ctx.joint_index.end()) return *error = js.pointer + ": the joint is not in the compiled model", false;
    const Joint& jm = ctx.model.joints[it->second];
    const MarkerSpec* m1 = FindMarker(ctx, jm.body1, js.marker1);
    const MarkerSpec* m2 = FindMarker(ctx, jm.body2, js.marker2);
    if (!m1 || !m2 || !m1->point || !m2->point)
      return *error = js.pointer + ": its markers are not in the file", false;
    const std::string why = Mismatch(ctx, jm);
    if (!why.empty()) {
      *error = js.pointer + ": joint '" + jm.name + "': " + why +
               "; the global form fixes each joint where its bodies are drawn, so the motion would change "
               "(draw the bodies where the markers coincide, or keep the markers form)";
      return false;
    }
    Json& joint = (*doc)["joints"][k];
    joint = JointOnGlobal(joint, GlobalGeometry(ctx, jm, *m1, *m2));
  }
  return true;
}

// A point output on a marker names the marker's global design point instead.
void ConvertOutputs(const Context& ctx, Json* doc) {
  for (size_t k = 0; k < ctx.spec.outputs.size() && k < (*doc)["outputs"].size(); ++k) {
    const OutputSpec& os = ctx.spec.outputs[k];
    if (!os.marker || !os.name || !os.body) continue;
    const Output& om = ctx.model.outputs[ctx.output_index.at(*os.name)];
    const MarkerSpec* m = FindMarker(ctx, om.body1, os.marker);
    if (!m || !m->point) continue;
    Json& out = (*doc)["outputs"][k];
    Json rewritten = Json::object();
    for (const auto& item : out.items())
      rewritten[item.key() == "marker" ? "point" : item.key()] =
          item.key() == "marker" ? GlobalPoint(ctx, om.body1, *m, om.point1) : item.value();
    out = std::move(rewritten);
  }
}

// Whether the assembly moved body b from the pose the file gives it (its sketch).
bool MovedFromSketch(const Context& ctx, BodyIndex b) {
  const AssemblyRecord* rec = ctx.model.assembly ? &*ctx.model.assembly : nullptr;
  if (!rec || b < 0 || b >= static_cast<int>(rec->sketched.size()) || !rec->sketched[b]) return false;
  const Body& body = ctx.model.bodies[b];
  return (body.position - rec->guess_position[b]).norm() > 1e-12 * ctx.model.characteristic_length ||
         std::min((body.euler - rec->guess_euler[b]).norm(), (body.euler + rec->guess_euler[b]).norm()) > 1e-12;
}

// A body the assembly placed (no "position" in the file, or a sketch it moved) gets
// its assembled design pose written: the global joints are where the bodies are.
void WritePlacedPoses(const Context& ctx, Json* doc) {
  Json& bodies = (*doc)["bodies"];
  for (size_t k = 0; k < bodies.size(); ++k) {
    Json& b = bodies[k];
    if (!b.is_object()) continue;
    const auto it = ctx.body_index.find(b.value("name", ""));
    if (it == ctx.body_index.end() || it->second == kGround) continue;
    const bool moved = MovedFromSketch(ctx, it->second);
    if (b.contains("position") && !moved) continue;
    const Body& body = ctx.model.bodies[it->second];
    Json placed = Json::object();
    for (const auto& item : b.items()) {
      if (moved && (item.key() == "position" || item.key() == "orientation")) continue;
      placed[item.key()] = item.value();
      if (item.key() == "name") placed["position"] = NumberVector(body.position / ctx.unit, ctx.scale);
    }
    if (!placed.contains("orientation") && (body.euler - Vec4(1, 0, 0, 0)).norm() > 1e-15)
      placed["orientation"] = Json::object(
          {{"euler_parameters", Json::array({Number(body.euler[0], 1), Number(body.euler[1], 1),
                                             Number(body.euler[2], 1), Number(body.euler[3], 1)})}});
    ctx.Note("/bodies/" + std::to_string(k), "the assembled design pose is written at the current parameter values");
    b = std::move(placed);
  }
}

// A hint on a marker joint turned at the design pose is measured from the markers'
// coincidence; the global form measures it from the design pose: subtract.
void RebaseHints(const Context& ctx, Json* doc) {
  if (!doc->contains("analysis") || !(*doc)["analysis"].contains("branch")) return;
  Json& branch = (*doc)["analysis"]["branch"];
  if (!branch.contains("joints") || !branch["joints"].is_object()) return;
  for (auto& item : branch["joints"].items()) {
    const auto it = ctx.joint_index.find(item.key());
    if (it == ctx.joint_index.end() || !item.value().is_number()) continue;
    const Joint& jm = ctx.model.joints[it->second];
    if (!jm.on_markers || jm.type->coordinates != JointCoordinates::Angle) continue;
    const double zero = DesignAngle(GlobalFrame(ctx, jm.body1, jm.frame1), GlobalFrame(ctx, jm.body2, jm.frame2));
    if (std::abs(zero) < 1e-12) continue;
    item.value() = Number(item.value().get<double>() - zero / ctx.model.units.angle_to_si, 1);
  }
}

// Global design points of a body the assembly moved from its sketch name another
// point of it in the global form (they were taken at the sketch): refuse, naming one.
bool RefuseMovedGlobalPoints(const Context& ctx, std::string* error) {
  auto moved = [&](const std::optional<std::string>& name) {
    const auto it = name ? ctx.body_index.find(*name) : ctx.body_index.end();
    return it != ctx.body_index.end() && it->second != kGround && MovedFromSketch(ctx, it->second);
  };
  std::string where, body;
  for (const OutputSpec& o : ctx.spec.outputs)
    if (where.empty() && o.body && !o.marker && (o.point || o.point1) && moved(o.body)) where = o.pointer, body = *o.body;
  for (const LoadSpec& l : ctx.spec.loads)
    if (where.empty() && ((l.point && moved(l.body)) || (l.point1 && moved(l.body1)) || (l.point2 && moved(l.body2))))
      where = l.pointer, body = l.body ? *l.body : l.body1 ? *l.body1 : "";
  for (const DriverSpec& d : ctx.spec.drivers)
    if (where.empty() && ((d.point1 && moved(d.body1)) || (d.point2 && moved(d.body2)))) where = d.pointer, body = "";
  for (const BodySpec& b : ctx.spec.bodies)
    if (where.empty() && b.inertia && b.inertia->center && moved(b.name)) where = b.pointer + "/inertia", body = *b.name;
  if (where.empty()) return true;
  *error = where + ": a global design point on " + (body.empty() ? std::string("a body") : "body '" + body + "'") +
           ", which the assembly moved from its sketch: the global form would read it at the assembled pose, "
           "another point of the body (give the point as a marker, or draw the body where it assembles)";
  return false;
}

void DropMarkers(Json* doc) {
  for (Json& b : (*doc)["bodies"])
    if (b.is_object()) b.erase("markers");
  if (!doc->contains("ground")) return;
  (*doc)["ground"].erase("markers");
  if ((*doc)["ground"].empty()) doc->erase("ground");
}

}  // namespace

bool ToGlobal(const Context& ctx, Json* doc, std::string* error) {
  if (!RefuseMovedGlobalPoints(ctx, error)) return false;
  if (!ConvertJoints(ctx, doc, error)) return false;
  if (doc->contains("outputs")) ConvertOutputs(ctx, doc);
  RebaseHints(ctx, doc);
  WritePlacedPoses(ctx, doc);
  DropMarkers(doc);
  return true;
}

}  // namespace mechkin::convert
