// Drivers: the driven coordinate's frames in both bodies, and its function of time.
#include <cmath>

#include "model/compiler.hpp"

namespace mechkin {

void Compiler::CompileDriver(const DriverSpec& d) {
  const std::string& ptr = d.pointer;
  const auto& name = d.name;
  const std::string type = d.type.value_or("");
  bool ok = name.has_value() && d.type.has_value();
  if (name) {
    if (driver_names_.count(*name)) {
      Error(ptr + "/name", "duplicate driver name '" + *name + "'", "give every driver a unique name");
      ok = false;
    }
    driver_names_.insert(*name);
  }
  Driver drv;
  double scale = length_;
  if (type == "rotation" && d.by_body) {
    ok = DriverOnBody(d, &drv) && ok;
    scale = angle_;
  } else if (type == "rotation" || type == "translation") {
    ok = DriverOnJoint(d, type == "rotation", &drv) && ok;
    scale = type == "rotation" ? angle_ : length_;
  } else if (type == "distance") {
    ok = DriverBetweenPoints(d, &drv) && ok;
  } else if (type == "coordinate") {
    ok = DriverOnCoordinate(d, &drv) && ok;
  } else if (type == "angle") {
    ok = DriverOnAngle(d, &drv) && ok;
    scale = angle_;
  } else {
    ok = false;
  }
  if (d.function) {
    auto f = CompileFunction(*d.function, scale);
    if (f)
      drv.function = *f;
    else
      ok = false;
  } else
    ok = false;
  if (!ok) return;
  drv.name = *name;
  model_.drivers.push_back(drv);
  driver_pointers_.push_back(ptr);
}

bool Compiler::DriverOnBody(const DriverSpec& d, Driver* drv) {
  drv->kind = DriverKind::BodyRotation;
  auto b = BodyRef(d.body, "body", d.pointer);
  auto axis = Vector(d.axis, true);
  if (b && *b == kGround) {
    Error(d.pointer + "/body", "ground cannot be driven", "name a moving body");
    return false;
  }
  if (!b || !axis) return false;
  // GRRD with ground as body i (constraints.md §3.6 seed note).
  const JointFrame global = MakeFrame(Vec3::Zero(), *axis);
  drv->body1 = kGround;
  drv->body2 = *b;
  drv->frame1 = global;
  drv->frame2 = LocalFrame(*b, global);
  return true;
}

// A joint by name: -1 with an error when unknown, -2 when it failed itself.
std::optional<int> Compiler::FindJoint(const std::optional<std::string>& name, const std::string& ptr,
                                       bool did_you_mean) {
  if (!name) return std::nullopt;
  const auto it = joint_index_.find(*name);
  if (it == joint_index_.end()) {
    std::vector<std::string> names;
    for (const auto& kv : joint_index_) names.push_back(kv.first);
    const std::string g = did_you_mean ? DidYouMean(*name, names) : "";
    Error(ptr + "/joint", "unknown joint '" + Shorten(*name) + "'",
          (g.empty() ? "" : "did you mean '" + g + "'? ") + "valid joints: " + Join(names));
    return -1;
  }
  return it->second;
}

bool Compiler::DriverOnJoint(const DriverSpec& d, bool rot, Driver* drv) {
  drv->kind = rot ? DriverKind::JointRotation : DriverKind::JointTranslation;
  const auto index = FindJoint(d.joint, d.pointer, true);
  if (!index || *index < 0) return false;  // unknown (reported), or that joint already has an error
  const Joint& j = model_.joints[*index];
  const bool can = rot ? j.type->turns : j.type->slides;
  if (!can) {
    Error(d.pointer + "/joint",
          std::string("a ") + (rot ? "rotation" : "translation") + " driver cannot drive " + j.type->name +
              " joint '" + j.name + "'",
          rot ? "rotation drivers act on revolute, cylindrical or screw joints"
              : "translation drivers act on prismatic, cylindrical or screw joints");
    return false;
  }
  drv->joint = *index;
  drv->body1 = j.body1;
  drv->body2 = j.body2;
  drv->frame1 = j.frame1;
  drv->frame2 = j.frame2;
  return true;
}

// {"type": "coordinate", "body", "point", "axis", "axis_body"?}: the body point's
// coordinate along an axis fixed in ground (or in axis_body), 0 at the design pose
// (the seed's dot-2 distance driver: Φ = a_iᵀ(P_j − P_i) − f(t), P_i the design
// position of the point, fixed in the axis body).
bool Compiler::DriverOnCoordinate(const DriverSpec& d, Driver* drv) {
  drv->kind = DriverKind::JointTranslation;
  auto b = BodyRef(d.body, "body", d.pointer);
  auto p = LengthVector(d.point);
  auto axis = Vector(d.axis, true);
  std::optional<BodyIndex> ab = kGround;
  if (d.axis_body) ab = BodyRef(d.axis_body, "axis_body", d.pointer);
  if (!b || !p || !axis || !ab) return false;
  if (*b == *ab) {
    Error(d.pointer + "/axis_body", "the axis is fixed in the driven body itself: its coordinate cannot change",
          "fix the axis in ground (omit axis_body) or in another body");
    return false;
  }
  SetDriverFrames(drv, *ab, *b, MakeFrame(*p, *axis));
  return true;
}

// {"type": "angle", "body1", "body2", "about", "vector"?}: the turn of body2's
// `vector` (default: a direction across `about`) about `about` (fixed in body1),
// relative to body1, 0 at the design pose — the general rotation driver (§3.9) on
// two bodies that no revolute keeps aligned.
bool Compiler::DriverOnAngle(const DriverSpec& d, Driver* drv) {
  drv->kind = DriverKind::BodyRotation;
  drv->general_angle = true;
  auto b1 = BodyRef(d.body1, "body1", d.pointer);
  auto b2 = BodyRef(d.body2, "body2", d.pointer);
  auto about = Vector(d.about, true);
  std::optional<Vec3> vector;
  if (d.vector) {
    vector = Vector(d.vector, true);
    if (!vector) return false;
    if (about && vector->normalized().cross(about->normalized()).norm() < 1e-6) {
      Error(d.pointer + "/vector", "'vector' is parallel to 'about': its turn about it is undefined",
            "give a direction across the axis");
      return false;
    }
  }
  if (!b1 || !b2 || !about) return false;
  if (*b1 == *b2) {
    Error(d.pointer + "/body2", "an angle driver between body '" + model_.BodyName(*b1) + "' and itself",
          "name two different bodies");
    return false;
  }
  const JointFrame global = vector ? MakeFrame(Vec3::Zero(), *about, *vector) : MakeFrame(Vec3::Zero(), *about);
  SetDriverFrames(drv, *b1, *b2, global);
  return true;
}

bool Compiler::DriverBetweenPoints(const DriverSpec& d, Driver* drv) {
  drv->kind = DriverKind::Distance;
  auto b1 = BodyRef(d.body1, "body1", d.pointer);
  auto b2 = BodyRef(d.body2, "body2", d.pointer);
  auto p1 = LengthVector(d.point1);
  auto p2 = LengthVector(d.point2);
  if (b1 && b2 && *b1 == *b2) {
    Error(d.pointer + "/body2", "distance driver between body '" + model_.BodyName(*b1) + "' and itself",
          "name two different bodies");
    return false;
  }
  if (!b1 || !b2 || !p1 || !p2) return false;
  drv->body1 = *b1;
  drv->body2 = *b2;
  drv->point1 = LocalPoint(*b1, *p1);
  drv->point2 = LocalPoint(*b2, *p2);
  return true;
}

}  // namespace mechkin
