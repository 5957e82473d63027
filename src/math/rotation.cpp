#include "math/rotation.hpp"

#include <cmath>

namespace mechkin {

Vec4 QuatMultiply(const Vec4& a, const Vec4& b) {
  Vec4 c;
  c[0] = a[0] * b[0] - a.tail<3>().dot(b.tail<3>());
  c.tail<3>() = a[0] * b.tail<3>() + b[0] * a.tail<3>() + a.tail<3>().cross(b.tail<3>());
  return c;
}

Vec4 QuatFromAxisAngle(const Vec3& unit_axis, double angle) {
  Vec4 q;
  q[0] = std::cos(angle / 2);
  q.tail<3>() = std::sin(angle / 2) * unit_axis;
  return q;
}

Vec4 QuatFromMatrix(const Mat3& R) {
  const double tr = R.trace();
  Vec4 q;
  // Candidates 4e0² = 1+tr, 4e1² = 1+2R00−tr, ...; use the largest for accuracy.
  const double c0 = 1 + tr, c1 = 1 + 2 * R(0, 0) - tr, c2 = 1 + 2 * R(1, 1) - tr,
               c3 = 1 + 2 * R(2, 2) - tr;
  if (c0 >= c1 && c0 >= c2 && c0 >= c3) {
    const double s = 2 * std::sqrt(c0);
    q << s / 4, (R(2, 1) - R(1, 2)) / s, (R(0, 2) - R(2, 0)) / s, (R(1, 0) - R(0, 1)) / s;
  } else if (c1 >= c2 && c1 >= c3) {
    const double s = 2 * std::sqrt(c1);
    q << (R(2, 1) - R(1, 2)) / s, s / 4, (R(0, 1) + R(1, 0)) / s, (R(0, 2) + R(2, 0)) / s;
  } else if (c2 >= c3) {
    const double s = 2 * std::sqrt(c2);
    q << (R(0, 2) - R(2, 0)) / s, (R(0, 1) + R(1, 0)) / s, s / 4, (R(1, 2) + R(2, 1)) / s;
  } else {
    const double s = 2 * std::sqrt(c3);
    q << (R(1, 0) - R(0, 1)) / s, (R(0, 2) + R(2, 0)) / s, (R(1, 2) + R(2, 1)) / s, s / 4;
  }
  if (q[0] < 0) q = -q;  // canonical sign: e0 >= 0
  return q.normalized();
}

Vec3 AnyPerpendicular(const Vec3& h) {
  // Cross with the global axis least aligned with h: well conditioned for every h.
  Vec3 a = Vec3::UnitX();
  if (std::abs(h.y()) < std::abs(h.x()) && std::abs(h.y()) <= std::abs(h.z())) a = Vec3::UnitY();
  else if (std::abs(h.z()) < std::abs(h.x()) && std::abs(h.z()) < std::abs(h.y())) a = Vec3::UnitZ();
  else if (std::abs(h.x()) <= std::abs(h.y()) && std::abs(h.x()) <= std::abs(h.z())) a = Vec3::UnitX();
  return h.cross(a).normalized();
}

}  // namespace mechkin
