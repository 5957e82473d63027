// Truncated Taylor series in time with long double coefficients (c[k] = f^(k)/k!, to
// order kMaxOrder): Φ evaluated on them along the computed derivatives gives every
// order's residual d^kΦ/dt^k = Φ_q q^(k) − RHS_k at once, to long double's round-off
// (constraints.md §8, "Measured", step 3). Only what the families' Φ templates use:
// + − × ÷, atan2 and round (UnwrapAngle), and Eigen's scalar traits so that their
// Eigen::Matrix<S, 3, 1> expressions work on it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "math/taylor.hpp"

namespace mechkin {

struct ExtendedJet {
  std::array<long double, kMaxOrder + 1> c{};

  ExtendedJet() = default;
  // Implicit on purpose: the Φ templates write S(0), 2 * S(x) and S(length).
  ExtendedJet(long double value) { c[0] = value; }  // NOLINT(google-explicit-constructor)

  ExtendedJet& operator+=(const ExtendedJet& b) {
    for (int k = 0; k <= kMaxOrder; ++k) c[k] += b.c[k];
    return *this;
  }
  ExtendedJet& operator-=(const ExtendedJet& b) {
    for (int k = 0; k <= kMaxOrder; ++k) c[k] -= b.c[k];
    return *this;
  }
  ExtendedJet& operator*=(const ExtendedJet& b);
  ExtendedJet& operator/=(const ExtendedJet& b);

  // UnwrapAngle's atan2 and round, found only by argument-dependent lookup (hidden
  // friends): no other call in the namespace can pick them up through the implicit
  // constructor.
  /// atan2 of two series: the value from std::atan2, the rest from θ' = (x y' − y x')/(x² + y²)
  /// integrated term by term. NaN coefficients at x = y = 0 (no angle there).
  friend ExtendedJet atan2(const ExtendedJet& y, const ExtendedJet& x) { return Atan2(y, x); }
  /// The whole turns UnwrapAngle adds: a constant, the value rounded.
  friend ExtendedJet round(const ExtendedJet& a) { return ExtendedJet(std::round(a.c[0])); }

 private:
  static ExtendedJet Atan2(const ExtendedJet& y, const ExtendedJet& x);
};

inline ExtendedJet operator+(ExtendedJet a, const ExtendedJet& b) { return a += b; }
inline ExtendedJet operator-(ExtendedJet a, const ExtendedJet& b) { return a -= b; }
inline ExtendedJet operator-(const ExtendedJet& a) {
  ExtendedJet r;
  for (int k = 0; k <= kMaxOrder; ++k) r.c[k] = -a.c[k];
  return r;
}
// The Cauchy product, truncated.
inline ExtendedJet operator*(const ExtendedJet& a, const ExtendedJet& b) {
  ExtendedJet r;
  for (int k = 0; k <= kMaxOrder; ++k)
    for (int j = 0; j <= k; ++j) r.c[k] += a.c[j] * b.c[k - j];
  return r;
}
// r = a / b from r·b = a, coefficient by coefficient (b.c[0] ≠ 0; NaN otherwise).
inline ExtendedJet operator/(const ExtendedJet& a, const ExtendedJet& b) {
  ExtendedJet r;
  for (int k = 0; k <= kMaxOrder; ++k) {
    long double s = a.c[k];
    for (int j = 1; j <= k; ++j) s -= b.c[j] * r.c[k - j];
    r.c[k] = s / b.c[0];
  }
  return r;
}
inline ExtendedJet& ExtendedJet::operator*=(const ExtendedJet& b) { return *this = *this * b; }
inline ExtendedJet& ExtendedJet::operator/=(const ExtendedJet& b) { return *this = *this / b; }

inline ExtendedJet ExtendedJet::Atan2(const ExtendedJet& y, const ExtendedJet& x) {
  ExtendedJet dy, dx;  // the series of y' and x'
  for (int k = 0; k < kMaxOrder; ++k) {
    dy.c[k] = (k + 1) * y.c[k + 1];
    dx.c[k] = (k + 1) * x.c[k + 1];
  }
  const ExtendedJet rate = (x * dy - y * dx) / (x * x + y * y);
  ExtendedJet r;
  r.c[0] = std::atan2(y.c[0], x.c[0]);
  for (int k = 1; k <= kMaxOrder; ++k) r.c[k] = rate.c[k - 1] / k;
  return r;
}

}  // namespace mechkin

namespace Eigen {
template <>
struct NumTraits<mechkin::ExtendedJet> : GenericNumTraits<long double> {
  using Real = mechkin::ExtendedJet;
  using NonInteger = mechkin::ExtendedJet;
  using Nested = mechkin::ExtendedJet;
  using Literal = mechkin::ExtendedJet;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = mechkin::kMaxOrder + 1,
    AddCost = mechkin::kMaxOrder + 1,
    MulCost = (mechkin::kMaxOrder + 1) * (mechkin::kMaxOrder + 2) / 2,
  };
};
}  // namespace Eigen
