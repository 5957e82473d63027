// Loads: forces, torques and spring-dampers (SI).
#include "model/compiler.hpp"

namespace mechkin {

void Compiler::CompileLoad(const LoadSpec& o) {
  Load load;
  const bool spring = o.type == "spring";
  const bool ok = spring ? CompileSpring(o, &load) : CompileForceOrTorque(o, o.type == "force", &load);
  if (!ok || !o.name) return;
  load.name = *o.name;
  model_.loads.push_back(load);
}

bool Compiler::CompileForceOrTorque(const LoadSpec& o, bool force, Load* load) {
  const std::string& ptr = o.pointer;
  load->kind = force ? LoadKind::Force : LoadKind::Torque;
  auto b = BodyRef(o.body, "body", ptr);
  bool ok = b.has_value();
  if (b && *b == kGround) {
    Error(ptr + "/body", "a load on ground does nothing", "name a moving body");
    ok = false;
  }
  if (force) {
    auto p = LengthVector(o.point);
    if (p && ok) load->point1 = LocalPoint(*b, *p);
    ok = ok && p;
  }
  if (o.frame) {
    if (*o.frame != "global" && *o.frame != "body") {
      Error(ptr + "/frame", "unknown frame '" + Shorten(*o.frame) + "'", "use \"global\" or \"body\"");
      ok = false;
    }
    load->in_body_axes = *o.frame == "body";
  }
  if (!o.components_error.empty()) {
    Error(ptr + "/components", o.components_error);
    return false;
  }
  if (!o.components) return false;  // missing (reported by the reader)
  const double scale = force ? model_.units.force_to_si() : model_.units.torque_to_si();
  for (int k = 0; k < 3; ++k) {
    auto f = CompileFunction((*o.components)[k], scale);
    if (f) load->components[k] = *f;
    else ok = false;
  }
  if (b) load->body1 = *b;
  return ok;
}

// Tension k (L − L0) + c L̇ + preload; L0 defaults to the design distance.
bool Compiler::CompileSpring(const LoadSpec& o, Load* load) {
  const std::string& ptr = o.pointer;
  load->kind = LoadKind::Spring;
  auto b1 = BodyRef(o.body1, "body1", ptr), b2 = BodyRef(o.body2, "body2", ptr);
  auto p1 = LengthVector(o.point1), p2 = LengthVector(o.point2);
  auto k = Value(o.stiffness);
  if (!b1 || !b2 || !p1 || !p2 || !k) return false;
  if (*b1 == *b2) {
    Error(ptr + "/body2", "a spring between a body and itself does nothing", "name two different bodies");
    return false;
  }
  const double stiffness_to_si = model_.units.stiffness_to_si();  // force / length (damping: force·s / length)
  load->body1 = *b1;
  load->body2 = *b2;
  load->point1 = LocalPoint(*b1, *p1);
  load->point2 = LocalPoint(*b2, *p2);
  load->stiffness = *k * stiffness_to_si;
  load->free_length = (*p2 - *p1).norm();
  if (auto L0 = Value(o.free_length)) load->free_length = *L0 * length_;
  if (auto c = Value(o.damping)) load->damping = *c * stiffness_to_si;
  if (auto f = Value(o.preload)) load->preload = *f * model_.units.force_to_si();
  if (!(load->free_length >= 0) || load->stiffness < 0 || load->damping < 0) {
    Error(ptr, "stiffness, damping and free length must not be negative", "check the signs");
    return false;
  }
  return true;
}

}  // namespace mechkin
