// `mechkin convert --to markers`: every joint on global geometry becomes two
// markers named after it, one on each of its bodies (in the body's coordinates:
// exactly the joint's frames there), and the joint names them.
#include <set>

#include "io/convert_internal.hpp"
#include "model/frames.hpp"

namespace mechkin::convert {

namespace {

const char* const kGeometryKeys[] = {"origin", "axis", "axis1", "axis2", "normal", "point1", "point2"};

bool IsGeometryKey(const std::string& key) {
  for (const char* k : kGeometryKeys)
    if (key == k) return true;
  return false;
}

// A global point of the file in body b's coordinates. Exact for ground and for a
// body drawn unrotated (the difference of the two texts, so --set moves it as
// before); otherwise the number at the current values, with a note when that
// drops a parameter.
Json LocalPoint(const Context& ctx, BodyIndex b, const Vector3Spec& global, const Vec3& local_si,
                const std::string& ptr) {
  if (b == kGround) return VectorJson(global);
  const BodySpec* body = ctx.Body(b);
  if (body && body->position && LiteralIdentity(body->orientation)) {
    Json out = Json::array();
    for (int k = 0; k < 3; ++k) out.push_back(Difference(global.c[k], body->position->c[k], ctx.scale));
    return out;
  }
  if (UsesParameters(global) || (body && (UsesParameters(body->position) || UsesParameters(body->orientation))))
    ctx.Note(ptr, "written in body '" + ctx.model.bodies[b].name +
                      "' coordinates at the current parameter values (the body is rotated: its dependence on the "
                      "parameters cannot be written exactly)");
  return NumberVector(local_si / ctx.unit, ctx.scale);
}

// A global direction of the file in body b's axes (exact for ground and unrotated bodies).
Json LocalDirection(const Context& ctx, BodyIndex b, const Vector3Spec& global, const Vec3& local,
                    const std::string& ptr) {
  const BodySpec* body = b == kGround ? nullptr : ctx.Body(b);
  if (b == kGround || (body && LiteralIdentity(body->orientation))) return VectorJson(global);
  if (UsesParameters(global) || (body && UsesParameters(body->orientation)))
    ctx.Note(ptr, "written in body '" + ctx.model.bodies[b].name + "' axes at the current parameter values");
  return NumberVector(local, 1);
}

struct Side {
  BodyIndex body;
  const JointFrame* frame;
  const std::optional<Vector3Spec>* point;   // global point of the file
  const std::optional<Vector3Spec>* axis;    // global axis of the file (nullopt: none)
  const std::optional<Vector3Spec>* x_hint;  // the file's direction that fixed the frame's x (universal body2)
};

Side JointSide(const JointSpec& js, const Joint& jm, int side) {
  static const std::optional<Vector3Spec> kNone;
  Side s{side == 1 ? jm.body1 : jm.body2, side == 1 ? &jm.frame1 : &jm.frame2, &js.origin, &kNone, &kNone};
  switch (jm.type->frames) {
    case JointFrameRule::TwoPoints: s.point = side == 1 ? &js.point1 : &js.point2; break;
    case JointFrameRule::Point: break;
    case JointFrameRule::Normal: s.axis = &js.normal; break;
    case JointFrameRule::CrossAxes:
      s.axis = side == 1 ? &js.axis1 : &js.axis2;
      if (side == 2) s.x_hint = &js.axis1;
      break;
    case JointFrameRule::Axis: s.axis = &js.axis; break;
  }
  return s;
}

// The marker carrying the joint's frame on one side (docs/format.md "Markers").
Json MarkerOf(const Context& ctx, const JointSpec& js, const Joint& jm, int side) {
  const Side s = JointSide(js, jm, side);
  const std::string ptr = js.pointer;
  Json m = Json::object();
  const bool points = jm.type->frames == JointFrameRule::TwoPoints;
  m["point"] = LocalPoint(ctx, s.body, **s.point, s.frame->origin, ptr + (points
                                                                              ? (side == 1 ? "/point1" : "/point2")
                                                                              : "/origin"));
  if (points) return m;
  const JointFrame& fr = *s.frame;
  if (*s.axis)
    m["axis"] = LocalDirection(ctx, s.body, **s.axis, fr.h, ptr + "/axis");
  else if ((fr.h - Vec3::UnitZ()).norm() > 1e-12)
    m["axis"] = NumberVector(fr.h, 1);
  // Without x_axis a marker's x is the body's x made normal to the axis.
  const Vec3 default_x = MakeFrame(Vec3::Zero(), fr.h, Vec3::UnitX()).f;
  if ((default_x - fr.f).norm() <= 1e-12) return m;
  if (*s.x_hint) {
    m["x_axis"] = LocalDirection(ctx, s.body, **s.x_hint, fr.f, ptr + "/axis1");
  } else {
    m["x_axis"] = NumberVector(fr.f, 1);
    if (*s.axis && UsesParameters(*s.axis))
      ctx.Note(ptr + (jm.type->frames == JointFrameRule::Normal ? "/normal" : "/axis"),
               "the frame's x direction (x_axis of marker" + std::to_string(side) +
                   ") is written at the current parameter values");
  }
  return m;
}

class MarkerNames {
 public:
  explicit MarkerNames(const MechanismSpec& spec) {
    for (const MarkerSpec& m : spec.ground_markers) used_["ground"].insert(m.name);
    for (const BodySpec& b : spec.bodies)
      if (b.name)
        for (const MarkerSpec& m : b.markers) used_[*b.name].insert(m.name);
  }
  // The joint's name, or with a suffix when the body already has a marker so named.
  std::string Take(const std::string& body, const std::string& joint) {
    std::string name = joint;
    for (int k = 2; used_[body].count(name); ++k) name = joint + "_" + std::to_string(k);
    used_[body].insert(name);
    return name;
  }

 private:
  std::map<std::string, std::set<std::string>> used_;
};

// The joint with its geometry keys replaced by the two marker names (where the first one was).
Json JointOnMarkers(const Json& joint, const std::string& name1, const std::string& name2) {
  Json out = Json::object();
  bool placed = false;
  for (const auto& item : joint.items()) {
    if (!IsGeometryKey(item.key())) {
      out[item.key()] = item.value();
      continue;
    }
    if (!placed) out["marker1"] = name1, out["marker2"] = name2;
    placed = true;
  }
  if (!placed) out["marker1"] = name1, out["marker2"] = name2;
  return out;
}

// Adds the marker to the body's "markers" (ground's: the top-level "ground", made
// before "bodies" when missing); false when the body is not in the document.
bool AddMarker(Json* doc, const std::string& body, const std::string& name, Json marker) {
  if (body == "ground") {
    if (!doc->contains("ground")) InsertBefore(doc, "bodies", "ground", Json::object());
    (*doc)["ground"]["markers"][name] = std::move(marker);
    return true;
  }
  for (Json& b : (*doc)["bodies"])
    if (b.is_object() && b.value("name", "") == body) {
      b["markers"][name] = std::move(marker);
      return true;
    }
  return false;
}

}  // namespace

bool ToMarkers(const Context& ctx, Json* doc, std::string* error) {
  MarkerNames names(ctx.spec);
  for (size_t k = 0; k < ctx.spec.joints.size() && k < (*doc)["joints"].size(); ++k) {
    const JointSpec& js = ctx.spec.joints[k];
    if (js.marker1 || js.marker2) continue;  // already on markers
    const auto it = js.name ? ctx.joint_index.find(*js.name) : ctx.joint_index.end();
    if (it == ctx.joint_index.end()) {
      *error = js.pointer + ": the joint is not in the compiled model";
      return false;
    }
    const Joint& jm = ctx.model.joints[it->second];
    const std::string b1 = ctx.model.BodyName(jm.body1), b2 = ctx.model.BodyName(jm.body2);
    const std::string n1 = names.Take(b1, jm.name), n2 = names.Take(b2, jm.name);
    if (!AddMarker(doc, b1, n1, MarkerOf(ctx, js, jm, 1)) || !AddMarker(doc, b2, n2, MarkerOf(ctx, js, jm, 2))) {
      *error = js.pointer + ": its bodies are not in the file's \"bodies\"";
      return false;
    }
    Json& joint = (*doc)["joints"][k];
    joint = JointOnMarkers(joint, n1, n2);
  }
  return true;
}

}  // namespace mechkin::convert
