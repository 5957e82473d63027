// Per-body kinematic state at one instant, with the derived matrices every
// constraint family needs (constraints.md §1.3–§1.4).
//
// D[k] = Aᵀ d^k A/dt^k (so the k-th derivative of a body-fixed vector a = A a'
// is A D[k] a'), and B[k] is D[k] without its highest-derivative term, which
// multiplies the unknown of order k and belongs on the left-hand side:
//   D1 = ω̃',            B1 = 0
//   D2 = ω̃'ω̃' + ω̇̃',     B2 = ω̃'ω̃'
//   D3 = H' + ω̈̃',       B3 = H'   (H' boxed in §1.4)
//   D4 = W' + ω⃛̃',       B4 = W'   (W' boxed in §1.4)
// v and v3 are the p-version correction vectors of §1.3.
#pragma once

#include "math/rotation.hpp"
#include "math/taylor.hpp"

namespace mechkin {

struct BodyKinematics {
  Vec4 p = Vec4(1, 0, 0, 0);
  Mat3 A = Mat3::Identity();
  Vec3 r[kMaxOrder + 1] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  Vec3 w[kMaxOrder] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  // ω'^(k), body frame
  Mat3 D[kMaxOrder + 1];
  Mat3 B[kMaxOrder + 1];
  Mat3 AD[kMaxOrder + 1];  // A D[k]
  Mat3 AB[kMaxOrder + 1];  // A B[k]
  Vec3 v = Vec3::Zero(), v3 = Vec3::Zero();

  BodyKinematics() { SetPose(Vec3::Zero(), Vec4(1, 0, 0, 0)); }
  /// Sets r and p (p must be unit) and resets all rates to zero.
  void SetPose(const Vec3& position, const Vec4& euler);
  /// Recomputes D, B, AD, AB, v, v3 from r, p, w for derivative orders up to `order`.
  void UpdateDerived(int order);
  /// Incremental form for the derivative solves: before solving order k (ω'^(0..k−2)
  /// known) completes D[k−1] and forms B[k] (and v, v3 for k = 3, 4) — all that
  /// RHS_k reads. CompleteOrder(k) fills D[k] once ω'^(k−1) is known.
  void PrepareOrder(int k);
  void CompleteOrder(int k);

  /// The global point r + A s' and vector A a' (the pose interface Φ reads; ExtendedPose
  /// has the same two in extended precision).
  Vec3 Point(const Vec3& s) const { return r[0] + A * s; }
  Vec3 Vector(const Vec3& a) const { return A * a; }
  /// k-th derivative of the global point r + A s' (k = 0: the point itself).
  Vec3 PointDerivative(const Vec3& s, int k) const { return (k == 0 ? r[0] + A * s : Vec3(r[k] + AD[k] * s)); }
  /// Part of the k-th derivative of r + A s' that does not hold r^(k) or ω'^(k−1).
  Vec3 PointBias(const Vec3& s, int k) const { return AB[k] * s; }
  /// k-th derivative of the global vector A a'.
  Vec3 VectorDerivative(const Vec3& a, int k) const { return AD[k] * a; }
  Vec3 VectorBias(const Vec3& a, int k) const { return AB[k] * a; }

  /// Euler-parameter derivatives p^(k), k = 0..order, from the Leibniz recursion of §1.3:
  /// p^(n+1) = ½ Σ_k binom(n,k) G(p^(k))ᵀ ω'^(n−k).
  void CalcEulerDerivatives(int order, Vec4* out) const;
};

/// The fixed frame: r = 0, A = I, all rates zero. Inline: every family's input asks
/// for it (SystemState::Kin), some fifty times a step.
inline const BodyKinematics& GroundKinematics() {
  static const BodyKinematics ground;
  return ground;
}

}  // namespace mechkin
