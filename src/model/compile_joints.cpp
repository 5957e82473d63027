// Joints (frames in both bodies' coordinates) and drivers.
#include <algorithm>
#include <cmath>

#include "joints/registry.hpp"
#include "model/compiler.hpp"

namespace mechkin {

void Compiler::CompileJoint(const JointSpec& j) {
  const std::string& ptr = j.pointer;
  const auto& name = j.name;
  auto b1 = BodyRef(j.body1, "body1", ptr);
  auto b2 = BodyRef(j.body2, "body2", ptr);
  const JointDescriptor* type = j.type ? FindJointType(*j.type) : nullptr;
  bool ok = name && b1 && b2 && type;
  if (name) {
    if (joint_index_.count(*name)) {
      Error(ptr + "/name", "duplicate joint name '" + *name + "'", "give every joint a unique name");
      ok = false;
    }
    joint_index_.emplace(*name, -2);
  }
  if (b1 && b2 && *b1 == *b2) {
    Error(ptr + "/body2", "joint connects body '" + model_.BodyName(*b1) + "' to itself",
          "a joint needs two different bodies (either may be ground)");
    ok = false;
  }
  if (!type) return;
  if (j.marker1 || j.marker2) return CompileMarkerJoint(j, *type, ok ? &*name : nullptr, b1, b2);
  CompileJointGeometry(j, *type, ok ? &*name : nullptr, b1 ? *b1 : kGround, b2 ? *b2 : kGround);
}

// The geometry of a joint of known type, validated; adds the joint when `name`
// is given (the joint's name, bodies and type were valid).
void Compiler::CompileJointGeometry(const JointSpec& j, const JointDescriptor& type, const std::string* name,
                                    BodyIndex body1, BodyIndex body2) {
  const std::string& ptr = j.pointer;
  bool ok = name != nullptr;
  Joint joint;
  joint.type = &type;
  std::optional<Vec3> origin, axis, axis1, axis2, normal, p1, p2;
  auto read = [&](const std::optional<Vector3Spec>& spec, bool length, std::optional<Vec3>* out) {
    if (!spec) return;
    *out = length ? LengthVector(spec) : Vector(spec, true);
    ok = ok && out->has_value();
  };
  read(j.origin, true, &origin);
  read(j.axis, false, &axis);
  read(j.axis1, false, &axis1);
  read(j.axis2, false, &axis2);
  read(j.normal, false, &normal);
  read(j.point1, true, &p1);
  read(j.point2, true, &p2);
  if (!j.geometry_complete) ok = false;
  if (type.scalar == JointScalar::Pitch) ok = CompileScrewPitch(j, &joint) && ok;
  if (axis1 && axis2) {
    const double c = axis1->normalized().dot(axis2->normalized());
    if (std::abs(c) > 1e-6) {
      Error(ptr + "/axis2",
            "universal joint axes are not perpendicular (angle " +
                std::to_string(std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI) + " deg)",
            "make axis2 perpendicular to axis1 (the cross axes of a Hooke joint are at 90 deg)");
      ok = false;
    }
  }
  if (type.scalar == JointScalar::Length && p1 && p2) ok = CompileDistanceLength(j, *p1, *p2, ok, "/point2", &joint);
  if (!ok) return;
  joint.body1 = body1;
  joint.body2 = body2;
  AddJoint(*name, origin, axis, axis1, axis2, normal, p1, p2, &joint);
}

bool Compiler::CompileScrewPitch(const JointSpec& j, Joint* joint) {
  const std::string& ptr = j.pointer;
  auto pitch = Value(j.pitch);
  if (pitch && *pitch == 0) {
    Error(ptr + "/pitch", "screw pitch is zero", "use a revolute joint, or give the lead per revolution");
    return false;
  }
  if (pitch && std::abs(*pitch * length_) > kMaxCoordinate) {
    Error(ptr + "/pitch", "screw pitch is beyond 1e12 m per revolution", "check the number and the length unit");
    return false;
  }
  if (!pitch) return false;
  joint->pitch = *pitch * length_;
  return true;
}

// A distance link's length: "length", or the design distance of its two points.
bool Compiler::CompileDistanceLength(const JointSpec& j, const Vec3& p1, const Vec3& p2, bool ok,
                                     const char* point2_key, Joint* joint) {
  const std::string& ptr = j.pointer;
  double len = (p2 - p1).norm();
  if (j.length) {
    auto l = Value(j.length);
    if (!l)
      ok = false;
    else if (!(*l > 0)) {
      Error(ptr + "/length", "distance length must be positive", "give the link length");
      ok = false;
    } else
      len = *l * length_;
    if (len > kMaxCoordinate) {
      Error(ptr + "/length", "distance length is beyond 1e12 m", "check the number and the length unit");
      ok = false;
    }
  }
  if (ok && !(len > 0)) {
    Error(ptr + point2_key, "distance joint points coincide at the design pose and no length is given",
          "a distance link of zero length is singular; use a spherical joint");
    ok = false;
  }
  joint->length = len;
  return ok;
}

void Compiler::SetBothFrames(const JointFrame& global, Joint* joint) {
  joint->frame1 = LocalFrame(joint->body1, global);
  joint->frame2 = LocalFrame(joint->body2, global);
}

void Compiler::AddJoint(const std::string& name, const std::optional<Vec3>& origin, const std::optional<Vec3>& axis,
                        const std::optional<Vec3>& axis1, const std::optional<Vec3>& axis2,
                        const std::optional<Vec3>& normal, const std::optional<Vec3>& p1,
                        const std::optional<Vec3>& p2, Joint* joint_ptr) {
  Joint& joint = *joint_ptr;
  joint.name = name;
  // The frame the file's keys give (JointFrameRule), fixed in both bodies (§4).
  switch (joint.type->frames) {
    case JointFrameRule::Axis:
      SetBothFrames(MakeFrame(*origin, *axis), &joint);
      break;
    case JointFrameRule::Normal:
      SetBothFrames(MakeFrame(*origin, *normal), &joint);
      break;
    case JointFrameRule::CrossAxes:
      SetBothFrames(MakeFrame(*origin, *axis1, *axis2), &joint);
      // body2 carries axis2 as its h (constraints.md §5, U row).
      joint.frame2 = LocalFrame(joint.body2, MakeFrame(*origin, *axis2, *axis1));
      break;
    case JointFrameRule::Point: {
      JointFrame global;
      global.origin = *origin;
      SetBothFrames(global, &joint);
      break;
    }
    case JointFrameRule::TwoPoints:
      joint.frame1.origin = LocalPoint(joint.body1, *p1);
      joint.frame2.origin = LocalPoint(joint.body2, *p2);
      break;
  }
  joint_index_[joint.name] = static_cast<int>(model_.joints.size());
  model_.joints.push_back(joint);
}

// "limits": [lo, hi] in the angle unit (revolute, screw) or the length unit
// (prismatic, cylindrical), lo < hi; the joint must have compiled.
void Compiler::CompileJointLimits(const JointSpec& j) {
  if (!j.limits || !j.name) return;
  const auto it = joint_index_.find(*j.name);
  if (it == joint_index_.end() || it->second < 0) return;
  Joint& joint = model_.joints[it->second];
  const auto lo = Value((*j.limits)[0]), hi = Value((*j.limits)[1]);
  if (!lo || !hi) return;
  if (!std::isfinite(*lo) || !std::isfinite(*hi) || !(*lo < *hi)) {
    Error(j.pointer + "/limits", "'limits' must be [lo, hi] with lo < hi, not [" + FormatNumber(*lo) + ", " +
                                     FormatNumber(*hi) + "]",
          "give the lower limit first; the design pose (or the markers' coincidence) is 0");
    return;
  }
  const bool rotation = joint.type->limit == JointLimit::Angle;
  const double unit = rotation ? angle_ : length_;
  joint.limits = std::make_pair(*lo * unit, *hi * unit);
}

}  // namespace mechkin
