// Euler-parameter kinematics (constraints.md §1.2–§1.4).
//
// Notation: p = [e0, e1, e2, e3] (scalar first, unit), A(p) the rotation matrix
// from body to global, primed quantities are body-frame components.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mechkin {

using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Mat3 = Eigen::Matrix3d;
using Mat34 = Eigen::Matrix<double, 3, 4>;

/// Cross-product matrix: Tilde(a) * b == a.cross(b)  (§1.1).
inline Mat3 Tilde(const Vec3& a) {
  Mat3 t;
  t << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return t;
}

/// G(p) = [-e, -ẽ + e0 I]  (§1.2); ω' = 2 G ṗ. Inline: the predictor's Euler-parameter
/// series builds six of them per body and step.
inline Mat34 CalcG(const Vec4& p) {
  Mat34 G;
  G << -p[1], p[0], p[3], -p[2],
       -p[2], -p[3], p[0], p[1],
       -p[3], p[2], -p[1], p[0];
  return G;
}
/// E(p) = [-e, ẽ + e0 I]  (§1.2); ω = 2 E ṗ.
inline Mat34 CalcE(const Vec4& p) {
  Mat34 E;
  E << -p[1], p[0], -p[3], p[2],
       -p[2], p[3], p[0], -p[1],
       -p[3], -p[2], p[1], p[0];
  return E;
}
/// A(p) = E Gᵀ = (2e0² − 1) I + 2 (e eᵀ + e0 ẽ)  (§1.2), in any scalar type (double,
/// or long double for the extended-precision accuracy phase of the position solve).
template <typename S>
Eigen::Matrix<S, 3, 3> RotationMatrix(const Eigen::Matrix<S, 4, 1>& p) {
  const S e0 = p[0];
  const Eigen::Matrix<S, 3, 1> e = p.template tail<3>();
  Eigen::Matrix<S, 3, 3> e_tilde;
  e_tilde << 0, -e.z(), e.y(), e.z(), 0, -e.x(), -e.y(), e.x(), 0;
  return (2 * e0 * e0 - 1) * Eigen::Matrix<S, 3, 3>::Identity() + 2 * (e * e.transpose() + e0 * e_tilde);
}
inline Mat3 CalcA(const Vec4& p) { return RotationMatrix(p); }
/// Quaternion product a ⊗ b (scalar first); A(a ⊗ b) = A(a) A(b).
Vec4 QuatMultiply(const Vec4& a, const Vec4& b);
/// Unit Euler parameters of a rotation by `angle` (rad) about unit `axis`.
Vec4 QuatFromAxisAngle(const Vec3& unit_axis, double angle);
/// Euler parameters of a proper orthonormal matrix (Shepperd's method: picks the
/// largest of e0², e1², e2², e3² to stay accurate near 180° rotations).
Vec4 QuatFromMatrix(const Mat3& R);
/// Applies a body-frame rotation increment δπ' (rad): p ← p ⊗ [cos(|δπ'|/2), sin(|δπ'|/2) δπ'/|δπ'|]
/// (§1.5), then renormalizes. Any scalar type, like RotationMatrix.
template <typename S>
Eigen::Matrix<S, 4, 1> RetractBody(const Eigen::Matrix<S, 4, 1>& p, const Eigen::Matrix<S, 3, 1>& delta_pi) {
  using std::cos, std::sin;
  const S angle = delta_pi.norm();
  Eigen::Matrix<S, 4, 1> dq;
  if (angle < S(1e-300)) {
    dq << 1, 0, 0, 0;
  } else {
    dq[0] = cos(angle / 2);
    dq.template tail<3>() = (sin(angle / 2) / angle) * delta_pi;
  }
  Eigen::Matrix<S, 4, 1> c;  // p ⊗ dq
  c[0] = p[0] * dq[0] - p.template tail<3>().dot(dq.template tail<3>());
  c.template tail<3>() = p[0] * dq.template tail<3>() + dq[0] * p.template tail<3>() +
                         p.template tail<3>().cross(dq.template tail<3>());
  return c.normalized();
}
inline Vec4 QuatRetractBody(const Vec4& p, const Vec3& delta_pi) { return RetractBody(p, delta_pi); }

/// Any unit vector perpendicular to unit `h`, chosen deterministically.
Vec3 AnyPerpendicular(const Vec3& h);

}  // namespace mechkin
