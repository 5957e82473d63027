#include "constraints/body_kinematics.hpp"

namespace mechkin {

namespace {

// M + ã, entry by entry: the same sums as `M + Tilde(a)` (x + 0 and x + (−y) kept, so
// the signs of zeros too), without the temporary. GCC writes Tilde's nine entries to the
// stack one by one and Eigen reads them back in pairs; a load that spans two pending
// stores waits until both retire (`perf annotate` of CompleteOrder under
// `bench_step --benchmark_filter=StepParts/derivatives` showed most samples there).
Mat3 PlusTilde(const Mat3& m, const Vec3& a) {
  Mat3 t;
  t(0, 0) = m(0, 0) + 0.0;
  t(1, 0) = m(1, 0) + a.z();
  t(2, 0) = m(2, 0) + -a.y();
  t(0, 1) = m(0, 1) + -a.z();
  t(1, 1) = m(1, 1) + 0.0;
  t(2, 1) = m(2, 1) + a.x();
  t(0, 2) = m(0, 2) + a.y();
  t(1, 2) = m(1, 2) + -a.x();
  t(2, 2) = m(2, 2) + 0.0;
  return t;
}

}  // namespace

void BodyKinematics::SetPose(const Vec3& position, const Vec4& euler) {
  p = euler;
  A = CalcA(p);
  r[0] = position;
  for (int k = 1; k <= kMaxOrder; ++k) r[k].setZero();
  for (int k = 0; k < kMaxOrder; ++k) w[k].setZero();
  UpdateDerived(kMaxOrder);
}

void BodyKinematics::UpdateDerived(int order) {
  const Mat3 W0 = Tilde(w[0]), W1 = Tilde(w[1]), W2 = Tilde(w[2]), W3 = Tilde(w[3]);
  D[0] = Mat3::Identity();
  B[0] = Mat3::Identity();
  D[1] = W0;
  B[1].setZero();
  const Mat3 W00 = W0 * W0;
  if (order >= 2) {
    B[2] = W00;
    D[2] = W00 + W1;
  }
  if (order >= 3) {
    // H' = 2 ω̃ω̇̃ + ω̇̃ω̃ + ω̃³   (§1.4)
    B[3] = 2 * W0 * W1 + W1 * W0 + W00 * W0;
    D[3] = B[3] + W2;
  }
  if (order >= 4) {
    // W' = ω̈̃ω̃ + 3ω̇̃ω̇̃ + 3ω̃ω̈̃ + ω̇̃ω̃ω̃ + 2ω̃ω̇̃ω̃ + 3ω̃ω̃ω̇̃ + ω̃⁴   (§1.4)
    B[4] = W2 * W0 + 3 * W1 * W1 + 3 * W0 * W2 + W1 * W00 + 2 * W0 * W1 * W0 + 3 * W00 * W1 + W00 * W00;
    D[4] = B[4] + W3;
  }
  for (int k = 0; k <= order && k <= kMaxOrder; ++k) {
    AD[k] = A * D[k];
    AB[k] = A * B[k];
  }
  // v = −½ ω̃ω̇ + ¼ (ωᵀω) ω;  v3 = −ω̃ω̈ − ½ ω̃ω̃ω̇ + 3/2 (ωᵀω̇) ω   (§1.3)
  const double ww = w[0].squaredNorm();
  v = -0.5 * W0 * w[1] + 0.25 * ww * w[0];
  v3 = -W0 * w[2] - 0.5 * W00 * w[1] + 1.5 * w[0].dot(w[1]) * w[0];
}

void BodyKinematics::CompleteOrder(int k) {
  if (k < 1) return;
  D[k] = PlusTilde(B[k], w[k - 1]);
  AD[k] = A * D[k];
}

void BodyKinematics::PrepareOrder(int k) {
  if (k == 1) {
    // One assignment each: a chained one reads back the matrix it just stored (a
    // store-forwarding stall, as in PlusTilde).
    D[0].setIdentity();
    B[0].setIdentity();
    AD[0] = A;
    AB[0] = A;
    B[1].setZero();
    AB[1].setZero();
    return;
  }
  CompleteOrder(k - 1);
  const Mat3 W0 = Tilde(w[0]);
  if (k == 2) {
    B[2] = W0 * W0;
  } else if (k == 3) {
    const Mat3 W1 = Tilde(w[1]);
    B[3] = 2 * W0 * W1 + W1 * W0 + W0 * W0 * W0;  // H' (§1.4)
    v = -0.5 * W0 * w[1] + 0.25 * w[0].squaredNorm() * w[0];
  } else if (k == 4) {
    const Mat3 W1 = Tilde(w[1]), W2 = Tilde(w[2]), W00 = W0 * W0;
    B[4] = W2 * W0 + 3 * W1 * W1 + 3 * W0 * W2 + W1 * W00 + 2 * W0 * W1 * W0 + 3 * W00 * W1 + W00 * W00;  // W' (§1.4)
    v3 = -W0 * w[2] - 0.5 * W00 * w[1] + 1.5 * w[0].dot(w[1]) * w[0];
  }
  AB[k] = A * B[k];
}

void BodyKinematics::CalcEulerDerivatives(int order, Vec4* out) const {
  static constexpr double kBinom[4][4] = {{1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}};
  out[0] = p;
  for (int n = 0; n < order; ++n) {
    Vec4 s = Vec4::Zero();
    for (int k = 0; k <= n; ++k) s += kBinom[n][k] * CalcG(out[k]).transpose() * w[n - k];
    out[n + 1] = 0.5 * s;
  }
}

}  // namespace mechkin
