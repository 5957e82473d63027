#include "analysis/orientation.hpp"

#include <cmath>

namespace mechkin {

namespace {

constexpr double kInvFact[] = {1, 1, 0.5, 1.0 / 6, 1.0 / 24};

// The jet of one component of a body-fixed vector's global series.
Jet Component(const BodyKinematics& b, const Vec3& local, int a, int order) {
  Jet j;
  for (int k = 0; k <= order; ++k) j.c[k] = b.VectorDerivative(local, k)[a] * kInvFact[k];
  return j;
}

int Axis(char c) { return c - 'X'; }

// +1 when (i, j, k) is a cyclic permutation of (0, 1, 2).
double Parity(int i, int j, int k) { return (j - i + 3) % 3 == 1 && (k - j + 3) % 3 == 1 ? 1.0 : -1.0; }

}  // namespace

RotationJet RelativeRotation(const BodyKinematics& b1, const BodyKinematics& b2, int order) {
  return RelativeRotation(b1, Mat3::Identity(), b2, Mat3::Identity(), order);
}

RotationJet RelativeRotation(const BodyKinematics& b1, const Mat3& F1, const BodyKinematics& b2, const Mat3& F2,
                             int order) {
  std::array<std::array<Jet, 3>, 3> e1, e2;  // [axis][global component]
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      e1[a][c] = Component(b1, F1.col(a), c, order);
      e2[a][c] = Component(b2, F2.col(a), c, order);
    }
  RotationJet R;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) R[a][b] = e1[a][0] * e2[b][0] + e1[a][1] * e2[b][1] + e1[a][2] * e2[b][2];
  return R;
}

// Tait–Bryan R = R_i(α) R_j(β) R_k(γ), ε the parity of (i, j, k):
//   sin β = ε R_ik,  α = atan2(−ε R_jk, R_kk),  γ = atan2(−ε R_ij, R_ii).
// Proper Euler R = R_i(α) R_j(β) R_i(γ), k the third axis, ε the parity of (i, j, k):
//   β = atan2(√(R_ij² + R_ik²), R_ii),  α = atan2(R_ji, −ε R_ki),  γ = atan2(R_ij, ε R_ik).
bool SequenceAngles(const RotationJet& R, const std::string& seq, std::array<Jet, 3>* out) {
  const int i = Axis(seq[0]), j = Axis(seq[1]);
  const bool proper = seq[2] == seq[0];
  const int k = proper ? 3 - i - j : Axis(seq[2]);
  const double eps = Parity(i, j, k);
  const Jet E = Jet::Constant(eps);
  auto& a = *out;
  if (!proper) {
    const double cos_beta = std::hypot(R[i][i].c[0], R[i][j].c[0]);
    if (cos_beta < 1e-7) {
      a[1] = Jet::Constant(eps * R[i][k].c[0] > 0 ? M_PI / 2 : -M_PI / 2);
      return false;
    }
    a[1] = Atan2(E * R[i][k], Sqrt(R[i][i] * R[i][i] + R[i][j] * R[i][j]));
    a[0] = Atan2(-(E * R[j][k]), R[k][k]);
    a[2] = Atan2(-(E * R[i][j]), R[i][i]);
    return true;
  }
  const double sin_beta = std::hypot(R[i][j].c[0], R[i][k].c[0]);
  if (sin_beta < 1e-7) {
    a[1] = Jet::Constant(R[i][i].c[0] > 0 ? 0.0 : M_PI);
    return false;
  }
  a[1] = Atan2(Sqrt(R[i][j] * R[i][j] + R[i][k] * R[i][k]), R[i][i]);
  a[0] = Atan2(R[j][i], -(E * R[k][i]));
  a[2] = Atan2(R[i][j], E * R[i][k]);
  return true;
}

std::array<Jet, 4> RelativeEulerParameters(const BodyKinematics& b1, const BodyKinematics& b2, int order) {
  return RelativeEulerParameters(b1, Vec4(1, 0, 0, 0), b2, Vec4(1, 0, 0, 0), order);
}

std::array<Jet, 4> RelativeEulerParameters(const BodyKinematics& b1, const Vec4& q1, const BodyKinematics& b2,
                                           const Vec4& q2, int order) {
  Vec4 p1[kMaxOrder + 1], p2[kMaxOrder + 1];
  b1.CalcEulerDerivatives(order, p1);
  b2.CalcEulerDerivatives(order, p2);
  // The frames' orientations p ⊗ q (q constant), order by order.
  for (int k = 0; k <= order; ++k) p1[k] = QuatMultiply(p1[k], q1), p2[k] = QuatMultiply(p2[k], q2);
  std::array<Jet, 4> a, b;
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k <= order; ++k) {
      a[c].c[k] = (c == 0 ? 1 : -1) * p1[k][c] * kInvFact[k];  // conj(p1)
      b[c].c[k] = p2[k][c] * kInvFact[k];
    }
  // Quaternion product conj(p1) ⊗ p2 (scalar first).
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

// θn = f(s)·v with s = |v|², f = 2 atan2(√s, q0)/√s; near θ = 0 (q0 > 0) the series
// f = (2/q0)(1 − s/(3q0²) + s²/(5q0⁴)) keeps the derivatives finite.
std::array<Jet, 3> RotationVector(const std::array<Jet, 4>& q) {
  const Jet s = q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  Jet f;
  if (s.c[0] < 1e-12 && q[0].c[0] > 0) {
    const Jet w2 = q[0] * q[0];
    const Jet x = s / w2;
    f = Jet::Constant(2) / q[0] * (Jet::Constant(1) - x / Jet::Constant(3) + x * x / Jet::Constant(5));
  } else {
    const Jet r = Sqrt(s);
    f = Jet::Constant(2) * Atan2(r, q[0]) / r;
  }
  return {f * q[1], f * q[2], f * q[3]};
}

}  // namespace mechkin
