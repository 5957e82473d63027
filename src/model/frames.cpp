#include "model/frames.hpp"

#include <vector>

namespace mechkin {

JointFrame MakeFrame(const Vec3& origin, const Vec3& axis) {
  JointFrame fr;
  fr.origin = origin;
  fr.h = axis.normalized();
  fr.f = AnyPerpendicular(fr.h);
  fr.g = fr.h.cross(fr.f);
  return fr;
}

JointFrame MakeFrame(const Vec3& origin, const Vec3& axis, const Vec3& f_hint) {
  JointFrame fr;
  fr.origin = origin;
  fr.h = axis.normalized();
  const Vec3 f = f_hint - f_hint.dot(fr.h) * fr.h;
  fr.f = f.norm() > 1e-9 * f_hint.norm() ? Vec3(f.normalized()) : AnyPerpendicular(fr.h);
  fr.g = fr.h.cross(fr.f);
  return fr;
}

JointFrame ToLocal(const JointFrame& global, const Vec3& r, const Mat3& A) {
  JointFrame fr;
  fr.origin = A.transpose() * (global.origin - r);
  fr.f = A.transpose() * global.f;
  fr.g = A.transpose() * global.g;
  fr.h = A.transpose() * global.h;
  return fr;
}

double CharacteristicLength(const Model& model) {
  std::vector<Vec3> pts;
  auto global = [&](BodyIndex b, const Vec3& local) -> Vec3 {
    if (b == kGround) return local;
    return model.bodies[b].position + CalcA(model.bodies[b].euler) * local;
  };
  for (const auto& b : model.bodies) pts.push_back(b.position);
  for (const auto& j : model.joints) {
    pts.push_back(global(j.body1, j.frame1.origin));
    pts.push_back(global(j.body2, j.frame2.origin));
  }
  for (const auto& d : model.drivers)
    if (d.kind == DriverKind::Distance) {
      pts.push_back(global(d.body1, d.point1));
      pts.push_back(global(d.body2, d.point2));
    }
  for (const auto& o : model.outputs)
    if (o.kind == OutputKind::Point || o.kind == OutputKind::Distance) pts.push_back(global(o.body1, o.point1));
  if (pts.empty()) return model.units.length_to_si;
  Vec3 c = Vec3::Zero();
  for (const auto& p : pts) c += p;
  c /= static_cast<double>(pts.size());
  double r = 0, far = 0;
  for (const auto& p : pts) {
    r = std::max(r, (p - c).norm());
    far = std::max(far, p.norm());
  }
  // When every point coincides, the spread is round-off: fall back to the
  // distance from the global origin, or to one file length unit.
  if (r > 1e-6 * far && r > 0) return r;
  return far > 0 ? far : model.units.length_to_si;
}

}  // namespace mechkin
