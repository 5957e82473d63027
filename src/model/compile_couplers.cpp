// "couplers": each coupler as one equation Σ c_k q_k = c_0 between joint
// coordinates (constraints.md §3.11), checked against its joints' types.
#include <cmath>

#include "model/compiler.hpp"

namespace mechkin {

namespace {

std::optional<CouplerKind> KindOf(const std::string& type) {
  if (type == "gear") return CouplerKind::Gear;
  if (type == "belt") return CouplerKind::Belt;
  if (type == "rack_pinion") return CouplerKind::RackPinion;
  if (type == "screw_coupling") return CouplerKind::ScrewCoupling;
  if (type == "coupling") return CouplerKind::Coupling;
  return std::nullopt;
}

}  // namespace

// A joint named by a coupler at pointer `ptr`: its index, or nullopt (unknown:
// reported; a joint that failed itself: silent).
std::optional<int> Compiler::CouplerJoint(const std::string& name, const std::string& ptr) {
  const auto it = joint_index_.find(name);
  if (it == joint_index_.end()) {
    std::vector<std::string> names;
    for (const auto& kv : joint_index_) names.push_back(kv.first);
    const std::string g = DidYouMean(name, names);
    Error(ptr, "unknown joint '" + Shorten(name) + "'",
          (g.empty() ? "" : "did you mean '" + g + "'? ") + "valid joints: " + Join(names));
    return std::nullopt;
  }
  if (it->second < 0) return std::nullopt;
  return it->second;
}

// The coordinate of joint `joint` the coupler reads; `rotation` as the coupler
// type needs (nullopt: whichever the joint has, "coordinates" deciding for a
// cylindrical or screw joint).
std::optional<CouplerCoordinate> Compiler::CouplerTerm(const std::string& name, const std::string& ptr,
                                                        std::optional<bool> rotation, const std::string& type) {
  const auto joint = CouplerJoint(name, ptr);
  if (!joint) return std::nullopt;
  const Joint& j = model_.joints[*joint];
  const bool rot = j.type->turns, slide = j.type->slides;
  if (!rotation && rot && slide) {
    Error(ptr, "joint '" + j.name + "' (" + j.type->name + ") has a rotation and a translation",
          "say which one the coupling reads: \"coordinates\": [\"rotation\" or \"translation\", ...], one per joint");
    return std::nullopt;
  }
  const bool want_rotation = rotation.value_or(rot);
  if (want_rotation ? !rot : !slide) {
    const std::string what = rotation ? (want_rotation ? "a rotation" : "a translation") : "a single coordinate";
    Error(ptr, "a " + type + " coupler needs " + what + ", and " + j.type->name + " joint '" + j.name +
                   "' has none",
          want_rotation || !rotation ? "name a revolute, cylindrical or screw joint (rotation), or a prismatic one"
                                     : "name a prismatic, cylindrical or screw joint (translation)");
    return std::nullopt;
  }
  return CouplerCoordinate{*joint, want_rotation, 1.0};
}

// A gear's ratio, a pinion's pitch radius, a screw's pitch: finite and not zero.
std::optional<double> Compiler::CouplerFactor(const std::optional<Scalar>& s, const std::string& key,
                                              const std::string& ptr, double unit) {
  const auto v = Value(s);
  if (!v) return std::nullopt;
  if (!std::isfinite(*v) || *v == 0) {
    Error(ptr + "/" + key, "'" + key + "' must be a non-zero finite number, not " + FormatNumber(*v),
          key == "ratio" ? "θ₂ = ratio × θ₁: a zero ratio would lock joint2; give e.g. -2 for an external pair"
                         : "give the " + key + " in the file's length unit");
    return std::nullopt;
  }
  return *v * unit;
}

void Compiler::CompileCoupler(const CouplerSpec& c) {
  const std::string& ptr = c.pointer;
  const auto kind = c.type ? KindOf(*c.type) : std::nullopt;
  if (!c.name || !kind || !c.ok) return;
  if (!coupler_names_.insert(*c.name).second) {
    Error(ptr + "/name", "duplicate coupler name '" + *c.name + "'", "give every coupler a unique name");
    return;
  }
  Coupler cp;
  cp.name = *c.name;
  cp.kind = *kind;
  bool ok = true;
  if (*kind == CouplerKind::Coupling) {
    ok = CompileCoupling(c, &cp);
  } else {
    if (!c.joint1 || !c.joint2) return;  // missing: reported by the reader
    const bool two_rotations = *kind == CouplerKind::Gear || *kind == CouplerKind::Belt;
    const auto t1 = CouplerTerm(*c.joint1, ptr + "/joint1", true, *c.type);
    const auto t2 = CouplerTerm(*c.joint2, ptr + "/joint2", two_rotations, *c.type);
    std::optional<double> factor;
    if (two_rotations) factor = CouplerFactor(c.ratio, "ratio", ptr, 1.0);
    else if (*kind == CouplerKind::RackPinion) factor = CouplerFactor(c.pitch_radius, "pitch_radius", ptr, length_);
    else factor = CouplerFactor(c.pitch, "pitch", ptr, length_);
    if (!t1 || !t2 || !factor) return;
    if (t1->joint == t2->joint) {
      Error(ptr + "/joint2", "joint1 and joint2 are the same joint '" + *c.joint1 + "'",
            *kind == CouplerKind::ScrewCoupling ? "a screw joint couples one joint's rotation and slide itself"
                                                 : "couple two different joints");
      return;
    }
    cp.coordinates = {*t1, *t2};
    cp.ratio = *factor;
    if (*kind == CouplerKind::Gear && (c.pitch_radius || c.pressure_angle)) {
      cp.mesh = CompileGearMesh(c, cp);
      if (!cp.mesh) return;
    }
  }
  if (!ok) return;
  model_.couplers.push_back(cp);
}

// A tooth force needs two revolutes with parallel axes on one frame body (body1 of
// both): §3.11.1 moves the difference between the coupler's torques and the force
// at the pitch point into those two bearings, which is exact only then.
bool Compiler::GearMeshJoints(const std::string& ptr, const Joint& j1, const Joint& j2) {
  const std::string drop = "or drop pitch_radius (the gear then acts on the joints as torques only)";
  for (const Joint* j : {&j1, &j2})
    if (j->type->coordinates != JointCoordinates::Angle) {  // a bearing: turning about h only
      Error(ptr, "a tooth force needs revolute bearings, and joint '" + j->name + "' is " + j->type->name,
            "mount both gears on revolute joints, " + drop);
      return false;
    }
  if (j1.body1 != j2.body1) {
    Error(ptr, "the tooth force needs both gears' bearings on one frame body, and joint '" + j1.name +
                   "' has body1 '" + model_.BodyName(j1.body1) + "', joint '" + j2.name + "' body1 '" +
                   model_.BodyName(j2.body1) + "'",
          "make the common frame (ground, a gearbox, a carrier) body1 of both joints, " + drop);
    return false;
  }
  if (j1.frame1.h.cross(j2.frame1.h).norm() > 1e-9) {
    Error(ptr, "the tooth force is for parallel axes, and joints '" + j1.name + "' and '" + j2.name +
                   "' are not parallel (a bevel or worm pair)",
          drop);
    return false;
  }
  return true;
}

// §3.11.1: the pitch point on the line of centres, ρ₁ from axis 1, ρ₂ = ρ₁/|r|; an
// external mesh when the gears turn opposite ways (r h₁ᵀh₂ < 0), else internal.
std::optional<GearMesh> Compiler::CompileGearMesh(const CouplerSpec& c, const Coupler& cp) {
  const std::string ptr = c.pointer + (c.pitch_radius ? "/pitch_radius" : "/pressure_angle");
  if (!c.pitch_radius) {
    Error(ptr, "'pressure_angle' without 'pitch_radius'", "give gear 1's pitch radius too, or drop pressure_angle");
    return std::nullopt;
  }
  const auto rho = CouplerFactor(c.pitch_radius, "pitch_radius", c.pointer, length_);
  const auto phi = c.pressure_angle ? Value(c.pressure_angle) : std::optional<double>(20.0 * M_PI / 180 / angle_);
  if (!rho || !phi) return std::nullopt;
  if (*rho < 0) {
    Error(ptr, "'pitch_radius' must be positive, not " + FormatNumber(*rho / length_), "the sense is the ratio's sign");
    return std::nullopt;
  }
  const double angle = *phi * angle_;
  if (!(angle >= 0 && angle < M_PI / 2 - 1e-9)) {
    Error(c.pointer + "/pressure_angle", "'pressure_angle' must be at least 0 and less than a right angle, not " + FormatNumber(*phi),
          "give the pressure angle in the file's angle unit (20 degrees is the standard)");
    return std::nullopt;
  }
  const Joint& j1 = model_.joints[cp.coordinates[0].joint];
  const Joint& j2 = model_.joints[cp.coordinates[1].joint];
  if (!GearMeshJoints(ptr, j1, j2)) return std::nullopt;
  GearMesh m;
  m.frame = j1.body1;
  m.pitch_radius = *rho;
  m.tan_pressure = std::tan(angle);
  m.axis = j1.frame1.h;
  const Vec3 d = j2.frame1.origin - j1.frame1.origin;
  const Vec3 across = d - m.axis * m.axis.dot(d);
  const double r = std::abs(cp.ratio), rho2 = *rho / r, centres = across.norm();
  const bool external = cp.ratio * j1.frame1.h.dot(j2.frame1.h) < 0;
  const double expected = external ? *rho + rho2 : std::abs(*rho - rho2);
  if (!(centres > 0) || std::abs(centres - expected) > 1e-6 * std::max(centres, expected)) {
    const double fit = external ? centres / (1 + 1 / r) : (r == 1 ? 0 : centres / std::abs(1 - 1 / r));
    Error(ptr, std::string(external ? "external" : "internal") + " gears of pitch radii " + FormatNumber(*rho / length_) +
                   " and " + FormatNumber(rho2 / length_) + " need centres " + FormatNumber(expected / length_) +
                   " apart, and the joints' axes are " + FormatNumber(centres / length_) + " apart",
          fit > 0 ? "for these bearings and ratio the pitch radius is " + FormatNumber(fit / length_)
                  : "coaxial bearings or an internal pair of ratio 1 cannot mesh: drop pitch_radius");
    return std::nullopt;
  }
  // Gear 1 is the smaller of an internal pair: the pitch point lies away from gear 2's axis.
  const bool ring1 = !external && *rho > rho2;
  m.radial = (!external && !ring1 ? -1.0 : 1.0) * across / centres;
  m.radial_sign = ring1 ? 1 : -1;
  m.axial_offset = -m.axis.dot(d);
  return m;
}

// Σ c_k q_k = c_0, the coordinates in the file's units (angle unit for rotations,
// length unit for slides); in SI a_k = c_k / unit_k, scaled by the largest slide
// coefficient (Φ in metres) or, without slides, the largest rotation one (§3.11).
bool Compiler::CompileCoupling(const CouplerSpec& c, Coupler* cp) {
  const std::string& ptr = c.pointer;
  const size_t n = c.joints.size();
  if (n < 2 || n > 3) {
    Error(ptr + "/joints", "a coupling reads 2 or 3 joint coordinates, not " + std::to_string(n),
          "list two or three joints");
    return false;
  }
  if (c.coefficients.size() != n) {
    Error(ptr + "/coefficients", std::to_string(c.coefficients.size()) + " coefficients for " + std::to_string(n) + " joints",
          "give one coefficient per joint, in the same order");
    return false;
  }
  if (!c.coordinates.empty() && c.coordinates.size() != n) {
    Error(ptr + "/coordinates", "'coordinates' must have one entry per joint", "list \"rotation\" or \"translation\" per joint");
    return false;
  }
  bool ok = true;
  double slide_scale = 0, rotation_scale = 0;
  for (size_t k = 0; k < n; ++k) {
    const std::string jp = ptr + "/joints/" + std::to_string(k);
    std::optional<bool> rotation;
    if (!c.coordinates.empty()) {
      const std::string& w = c.coordinates[k];
      if (w != "rotation" && w != "translation") {
        Error(ptr + "/coordinates/" + std::to_string(k), "unknown coordinate '" + Shorten(w) + "'",
              "use \"rotation\" or \"translation\"");
        ok = false;
        continue;
      }
      rotation = w == "rotation";
    }
    for (size_t m = 0; m < k; ++m)
      if (c.joints[m] == c.joints[k] && (c.coordinates.empty() || c.coordinates[m] == c.coordinates[k])) {
        Error(jp, "joint '" + Shorten(c.joints[k]) + "' is listed twice", "list each joint coordinate once");
        ok = false;
      }
    const auto term = CouplerTerm(c.joints[k], jp, rotation, "coupling");
    const auto coef = Value(c.coefficients[k]);
    if (coef && (!std::isfinite(*coef) || *coef == 0)) {
      Error(c.coefficients[k].pointer, "coefficient must be a non-zero finite number, not " + FormatNumber(*coef),
            "drop the joint from the coupling instead of giving it 0");
      ok = false;
      continue;
    }
    if (!term || !coef) {
      ok = false;
      continue;
    }
    CouplerCoordinate cc = *term;
    cc.coefficient = *coef / (cc.rotation ? angle_ : length_);
    double& scale = cc.rotation ? rotation_scale : slide_scale;
    scale = std::max(scale, std::abs(cc.coefficient));
    cp->coordinates.push_back(cc);
  }
  const auto c0 = c.constant ? Value(c.constant) : std::optional<double>(0.0);
  if (!ok || !c0) return false;
  const double scale = slide_scale > 0 ? slide_scale : rotation_scale;
  for (CouplerCoordinate& cc : cp->coordinates) cc.coefficient /= scale;
  cp->constant = *c0 / scale;
  return true;
}

}  // namespace mechkin
