#include "math/taylor.hpp"

namespace mechkin {
namespace {
constexpr int N = kMaxOrder;

// Series of f = ∫ f' given f(t0) and the series of f': f_k = (f')_{k-1} / k.
Jet Integrate(double value, const Jet& derivative) {
  Jet r;
  r.c[0] = value;
  for (int k = 1; k <= N; ++k) r.c[k] = derivative.c[k - 1] / k;
  return r;
}
// Series of a'(t).
Jet Differentiate(const Jet& a) {
  Jet r;
  for (int k = 0; k < N; ++k) r.c[k] = (k + 1) * a.c[k + 1];
  return r;
}
void RequireFinite(const Jet& r, const char* what) {
  for (double v : r.c)
    if (!std::isfinite(v)) throw JetDomainError(std::string(what) + " is not finite here");
}
}  // namespace

Jet operator+(const Jet& a, const Jet& b) { Jet r; for (int k = 0; k <= N; ++k) r.c[k] = a.c[k] + b.c[k]; return r; }
Jet operator-(const Jet& a, const Jet& b) { Jet r; for (int k = 0; k <= N; ++k) r.c[k] = a.c[k] - b.c[k]; return r; }
Jet operator-(const Jet& a) { Jet r; for (int k = 0; k <= N; ++k) r.c[k] = -a.c[k]; return r; }

Jet operator*(const Jet& a, const Jet& b) {
  Jet r;
  for (int k = 0; k <= N; ++k)
    for (int j = 0; j <= k; ++j) r.c[k] += a.c[j] * b.c[k - j];
  return r;
}

Jet operator/(const Jet& a, const Jet& b) {
  if (b.c[0] == 0) throw JetDomainError("division by zero");
  Jet r;
  for (int k = 0; k <= N; ++k) {
    double s = a.c[k];
    for (int j = 1; j <= k; ++j) s -= b.c[j] * r.c[k - j];
    r.c[k] = s / b.c[0];
  }
  RequireFinite(r, "quotient");
  return r;
}

Jet Exp(const Jet& a) {
  Jet r;
  r.c[0] = std::exp(a.c[0]);
  for (int k = 1; k <= N; ++k) {
    double s = 0;
    for (int j = 1; j <= k; ++j) s += j * a.c[j] * r.c[k - j];
    r.c[k] = s / k;
  }
  RequireFinite(r, "exp");
  return r;
}

Jet Log(const Jet& a) {
  if (!(a.c[0] > 0)) throw JetDomainError("log of a number <= 0");
  Jet r;
  r.c[0] = std::log(a.c[0]);
  for (int k = 1; k <= N; ++k) {
    double s = a.c[k];
    for (int j = 1; j < k; ++j) s -= (double(j) / k) * r.c[j] * a.c[k - j];
    r.c[k] = s / a.c[0];
  }
  return r;
}

Jet Sqrt(const Jet& a) {
  if (a.c[0] < 0) throw JetDomainError("sqrt of a negative number");
  if (a.c[0] == 0) {
    if (a.IsConstant()) return Jet::Constant(0);
    throw JetDomainError("sqrt is not differentiable at 0");
  }
  Jet r;
  r.c[0] = std::sqrt(a.c[0]);
  for (int k = 1; k <= N; ++k) {
    double s = a.c[k];
    for (int j = 1; j < k; ++j) s -= r.c[j] * r.c[k - j];
    r.c[k] = s / (2 * r.c[0]);
  }
  return r;
}

namespace {
void SinCos(const Jet& a, Jet* s, Jet* c) {
  s->c = {};
  c->c = {};
  s->c[0] = std::sin(a.c[0]);
  c->c[0] = std::cos(a.c[0]);
  for (int k = 1; k <= N; ++k) {
    double ss = 0, cc = 0;
    for (int j = 1; j <= k; ++j) {
      ss += j * a.c[j] * c->c[k - j];
      cc -= j * a.c[j] * s->c[k - j];
    }
    s->c[k] = ss / k;
    c->c[k] = cc / k;
  }
}
}  // namespace

Jet Sin(const Jet& a) { Jet s, c; SinCos(a, &s, &c); return s; }
Jet Cos(const Jet& a) { Jet s, c; SinCos(a, &s, &c); return c; }
Jet Tan(const Jet& a) {
  Jet s, c;
  SinCos(a, &s, &c);
  if (std::abs(c.c[0]) < 1e-300) throw JetDomainError("tan at an odd multiple of pi/2");
  return s / c;
}

Jet Asin(const Jet& a) {
  if (!(std::abs(a.c[0]) < 1)) {
    if (std::abs(a.c[0]) == 1 && a.IsConstant()) return Jet::Constant(std::asin(a.c[0]));
    throw JetDomainError("asin outside (-1, 1)");
  }
  return Integrate(std::asin(a.c[0]), Differentiate(a) / Sqrt(Jet::Constant(1) - a * a));
}
Jet Acos(const Jet& a) {
  if (!(std::abs(a.c[0]) < 1)) {
    if (std::abs(a.c[0]) == 1 && a.IsConstant()) return Jet::Constant(std::acos(a.c[0]));
    throw JetDomainError("acos outside (-1, 1)");
  }
  return Integrate(std::acos(a.c[0]), -(Differentiate(a) / Sqrt(Jet::Constant(1) - a * a)));
}
Jet Atan(const Jet& a) {
  return Integrate(std::atan(a.c[0]), Differentiate(a) / (Jet::Constant(1) + a * a));
}
Jet Atan2(const Jet& y, const Jet& x) {
  const Jet r2 = x * x + y * y;
  if (r2.c[0] == 0) {
    if (x.IsConstant() && y.IsConstant()) return Jet::Constant(std::atan2(y.c[0], x.c[0]));
    throw JetDomainError("atan2(0, 0) is not differentiable");
  }
  return Integrate(std::atan2(y.c[0], x.c[0]), (x * Differentiate(y) - y * Differentiate(x)) / r2);
}

Jet Pow(const Jet& a, const Jet& b) {
  if (b.IsConstant()) {
    const double e = b.c[0];
    if (e == std::round(e) && std::abs(e) <= 64) {
      // Integer exponent: repeated squaring keeps a^n exact at a = 0 and for a < 0.
      long n = static_cast<long>(std::abs(e));
      Jet result = Jet::Constant(1), base = a;
      while (n > 0) {
        if (n & 1) result = result * base;
        base = base * base;
        n >>= 1;
      }
      return e < 0 ? Jet::Constant(1) / result : result;
    }
    if (a.c[0] > 0) {
      // p_k = 1/(k a0) Σ_{j=1..k} ((e+1) j − k) a_j p_{k−j}
      Jet r;
      r.c[0] = std::pow(a.c[0], e);
      for (int k = 1; k <= N; ++k) {
        double s = 0;
        for (int j = 1; j <= k; ++j) s += ((e + 1) * j - k) * a.c[j] * r.c[k - j];
        r.c[k] = s / (k * a.c[0]);
      }
      RequireFinite(r, "power");
      return r;
    }
    if (a.c[0] == 0 && a.IsConstant() && e > 0) return Jet::Constant(0);
    throw JetDomainError("non-integer power of a number <= 0");
  }
  if (!(a.c[0] > 0)) throw JetDomainError("variable power of a number <= 0");
  return Exp(b * Log(a));
}

}  // namespace mechkin
