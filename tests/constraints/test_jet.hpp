// Test-only truncated Taylor arithmetic, written independently of
// src/math/taylor.* so that the conformance harness does not check the code
// against itself. TJet holds normalized coefficients c[k] = f^(k)/k!.
#pragma once

#include <array>
#include <cmath>

namespace mechkin::testing {

constexpr int kJ = 6;  // order of the test jets (≥ 5: ω' to 3rd order needs p to 4th)

struct TJet {
  std::array<double, kJ + 1> c{};
  TJet() = default;
  TJet(double v) { c[0] = v; }  // NOLINT: implicit constants are convenient here
  double D(int k) const {
    double f = 1;
    for (int i = 2; i <= k; ++i) f *= i;
    return c[k] * f;
  }
  TJet Dt() const {  // time derivative as a series
    TJet r;
    for (int k = 0; k < kJ; ++k) r.c[k] = (k + 1) * c[k + 1];
    return r;
  }
  double At(double t) const {  // evaluate the polynomial
    double s = 0;
    for (int k = kJ; k >= 0; --k) s = s * t + c[k];
    return s;
  }
};
inline TJet operator+(TJet a, const TJet& b) { for (int k = 0; k <= kJ; ++k) a.c[k] += b.c[k]; return a; }
inline TJet operator-(TJet a, const TJet& b) { for (int k = 0; k <= kJ; ++k) a.c[k] -= b.c[k]; return a; }
inline TJet operator-(TJet a) { for (auto& x : a.c) x = -x; return a; }
inline TJet operator*(const TJet& a, const TJet& b) {
  TJet r;
  for (int i = 0; i <= kJ; ++i)
    for (int j = 0; i + j <= kJ; ++j) r.c[i + j] += a.c[i] * b.c[j];
  return r;
}
inline TJet operator*(double s, TJet a) { for (auto& x : a.c) x *= s; return a; }
inline TJet Inverse(const TJet& a) {  // 1/a by solving a·r = 1 term by term
  TJet r;
  r.c[0] = 1 / a.c[0];
  for (int k = 1; k <= kJ; ++k) {
    double s = 0;
    for (int j = 1; j <= k; ++j) s += a.c[j] * r.c[k - j];
    r.c[k] = -s / a.c[0];
  }
  return r;
}
inline TJet operator/(const TJet& a, const TJet& b) { return a * Inverse(b); }
inline TJet Sqrt(const TJet& a) {  // r·r = a
  TJet r;
  r.c[0] = std::sqrt(a.c[0]);
  for (int k = 1; k <= kJ; ++k) {
    double s = 0;
    for (int j = 1; j < k; ++j) s += r.c[j] * r.c[k - j];
    r.c[k] = (a.c[k] - s) / (2 * r.c[0]);
  }
  return r;
}
// sin and cos through the ODE s' = c a', c' = −s a'.
inline void SinCos(const TJet& a, TJet* s, TJet* c) {
  *s = TJet(std::sin(a.c[0]));
  *c = TJet(std::cos(a.c[0]));
  const TJet da = a.Dt();
  for (int k = 1; k <= kJ; ++k) {
    double ss = 0, cc = 0;
    for (int j = 0; j < k; ++j) { ss += c->c[j] * da.c[k - 1 - j]; cc -= s->c[j] * da.c[k - 1 - j]; }
    s->c[k] = ss / k;
    c->c[k] = cc / k;
  }
}

using V3 = std::array<TJet, 3>;
using Q4 = std::array<TJet, 4>;
using M3 = std::array<std::array<TJet, 3>, 3>;

inline V3 Add(const V3& a, const V3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline V3 Sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline TJet Dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 MulMV(const M3& A, const V3& v) {
  V3 r;
  for (int i = 0; i < 3; ++i) r[i] = A[i][0] * v[0] + A[i][1] * v[1] + A[i][2] * v[2];
  return r;
}
inline V3 Const(const double* v) { return {TJet(v[0]), TJet(v[1]), TJet(v[2])}; }
// Rotation matrix of unit Euler parameters (scalar first), written out entry by entry.
inline M3 RotationOf(const Q4& p) {
  const TJet &e0 = p[0], &e1 = p[1], &e2 = p[2], &e3 = p[3];
  M3 A;
  A[0][0] = 2.0 * (e0 * e0 + e1 * e1) - 1.0; A[0][1] = 2.0 * (e1 * e2 - e0 * e3); A[0][2] = 2.0 * (e1 * e3 + e0 * e2);
  A[1][0] = 2.0 * (e1 * e2 + e0 * e3); A[1][1] = 2.0 * (e0 * e0 + e2 * e2) - 1.0; A[1][2] = 2.0 * (e2 * e3 - e0 * e1);
  A[2][0] = 2.0 * (e1 * e3 - e0 * e2); A[2][1] = 2.0 * (e2 * e3 + e0 * e1); A[2][2] = 2.0 * (e0 * e0 + e3 * e3) - 1.0;
  return A;
}
inline Q4 QuatProduct(const Q4& a, const Q4& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

}  // namespace mechkin::testing

namespace mechkin::testing {
// atan through its derivative u'/(1 + u²).
inline TJet Atan(const TJet& u) {
  const TJet d = u.Dt() / (TJet(1.0) + u * u);
  TJet r(std::atan(u.c[0]));
  for (int k = 1; k <= kJ; ++k) r.c[k] = d.c[k - 1] / k;
  return r;
}
// Angle of (x, y): value from atan2, derivatives from the better-conditioned atan form.
inline TJet Angle(const TJet& y, const TJet& x) {
  TJet r = std::abs(x.c[0]) >= std::abs(y.c[0]) ? Atan(y / x) : -Atan(x / y);
  r.c[0] = std::atan2(y.c[0], x.c[0]);
  return r;
}
inline TJet Sin(const TJet& a) { TJet s, c; SinCos(a, &s, &c); return s; }
inline TJet Cos(const TJet& a) { TJet s, c; SinCos(a, &s, &c); return c; }
}  // namespace mechkin::testing
