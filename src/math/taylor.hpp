// Truncated Taylor series ("jets") in one variable, to order 4.
//
// A Jet holds normalized coefficients c[k] = f^(k)(t0) / k!, so arithmetic on
// jets propagates exact derivatives (Taylor-mode automatic differentiation).
// Used for driver functions of time (issue: exact derivatives to 4th order,
// not finite differences). Recurrences are the standard ones for power series
// (Griewank & Walther, "Evaluating Derivatives", ch. 13).
#pragma once

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mechkin {

constexpr int kMaxOrder = 4;

struct Jet {
  std::array<double, kMaxOrder + 1> c{};  // normalized Taylor coefficients

  static Jet Constant(double v) { Jet j; j.c[0] = v; return j; }
  static Jet Variable(double t0) { Jet j; j.c[0] = t0; j.c[1] = 1; return j; }
  bool IsConstant() const { for (int k = 1; k <= kMaxOrder; ++k) if (c[k] != 0) return false; return true; }
  /// k-th derivative f^(k)(t0).
  double Derivative(int k) const {
    static constexpr double kFact[] = {1, 1, 2, 6, 24};
    return c[k] * kFact[k];
  }
};

/// Error raised when a function leaves its domain (log of a negative number, ...).
struct JetDomainError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Jet operator+(const Jet& a, const Jet& b);
Jet operator-(const Jet& a, const Jet& b);
Jet operator-(const Jet& a);
Jet operator*(const Jet& a, const Jet& b);
Jet operator/(const Jet& a, const Jet& b);
Jet Pow(const Jet& a, const Jet& b);
Jet Sin(const Jet& a);
Jet Cos(const Jet& a);
Jet Tan(const Jet& a);
Jet Exp(const Jet& a);
Jet Log(const Jet& a);
Jet Sqrt(const Jet& a);
Jet Asin(const Jet& a);
Jet Acos(const Jet& a);
Jet Atan(const Jet& a);
Jet Atan2(const Jet& y, const Jet& x);

}  // namespace mechkin
