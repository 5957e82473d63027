// The extended-precision number types of the measured error bounds (constraints.md §8,
// "Measured"): Quad really carries quadruple precision where the compiler has it, and
// ExtendedJet's series arithmetic gives the Taylor coefficients of closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "math/extended_jet.hpp"
#include "math/quad.hpp"

namespace mechkin {
namespace {

// t as a series about t0 (c = t0, 1, 0, ...).
ExtendedJet Time(long double t0) {
  ExtendedJet t(t0);
  t.c[1] = 1;
  return t;
}

TEST(ExtendedPrecision, QuadResolvesBelowLongDouble) {
#if !defined(MECHKIN_QUAD_IS_FLOAT128)
  if (std::numeric_limits<long double>::digits < 113) GTEST_SKIP() << "no binary128 type on this platform";
#endif
  const Quad tiny = Quad(1) / (Quad(1ULL << 50) * Quad(1ULL << 50));  // 2^-100, below long double's 2^-63
  EXPECT_TRUE(Quad(1) + tiny - Quad(1) == tiny);
  EXPECT_FALSE(static_cast<long double>(1) + static_cast<long double>(tiny) - 1 == static_cast<long double>(tiny));
}

TEST(ExtendedPrecision, QuadSqrtToQuadruplePrecision) {
  for (double x : {2.0, 3.0, 1e-20, 7.5e12}) {
    const Quad r = QuadSqrt(Quad(x));
    const Quad rel = (r * r - Quad(x)) / Quad(x);
    EXPECT_LT(std::abs(static_cast<double>(rel)), 1e-31) << x;
  }
  EXPECT_EQ(static_cast<double>(QuadSqrt(Quad(0))), 0.0);
}

TEST(ExtendedPrecision, SeriesProductAndQuotient) {
  // (1 + t)² = 1 + 2t + t²; 1/(1 − t) = Σ t^k about t0 = 0.
  const ExtendedJet one_plus_t = ExtendedJet(1) + Time(0);
  const ExtendedJet square = one_plus_t * one_plus_t;
  EXPECT_EQ(static_cast<double>(square.c[0]), 1);
  EXPECT_EQ(static_cast<double>(square.c[1]), 2);
  EXPECT_EQ(static_cast<double>(square.c[2]), 1);
  EXPECT_EQ(static_cast<double>(square.c[3]), 0);
  const ExtendedJet geometric = ExtendedJet(1) / (ExtendedJet(1) - Time(0));
  for (int k = 0; k <= kMaxOrder; ++k) EXPECT_EQ(static_cast<double>(geometric.c[k]), 1) << k;
}

TEST(ExtendedPrecision, SeriesAtan2IsTheAngleSeries) {
  // atan2(sin θ(t), cos θ(t)) = θ(t) for θ = 0.7 + 1.3 t − 0.4 t²: sin and cos as series
  // from their derivatives; the series of atan2 must give back θ's coefficients.
  const long double a = 0.7L, b = 1.3L, c2 = -0.4L;
  ExtendedJet s, co;
  // d^k/dt^k of sin θ and cos θ at t = 0 for θ = a + b t + c2 t² (to 4th order).
  const long double th1 = b, th2 = 2 * c2;
  const long double S = std::sin(a), C = std::cos(a);
  s.c[0] = S;
  s.c[1] = C * th1;
  s.c[2] = (-S * th1 * th1 + C * th2) / 2;
  s.c[3] = (-C * th1 * th1 * th1 - 3 * S * th1 * th2) / 6;
  s.c[4] = (S * th1 * th1 * th1 * th1 - 6 * C * th1 * th1 * th2 - 3 * S * th2 * th2) / 24;
  co.c[0] = C;
  co.c[1] = -S * th1;
  co.c[2] = (-C * th1 * th1 - S * th2) / 2;
  co.c[3] = (S * th1 * th1 * th1 - 3 * C * th1 * th2) / 6;
  co.c[4] = (C * th1 * th1 * th1 * th1 + 6 * S * th1 * th1 * th2 - 3 * C * th2 * th2) / 24;
  const ExtendedJet theta = atan2(s, co);
  EXPECT_NEAR(static_cast<double>(theta.c[0]), 0.7, 1e-15);
  EXPECT_NEAR(static_cast<double>(theta.c[1]), 1.3, 1e-15);
  EXPECT_NEAR(static_cast<double>(theta.c[2]), -0.4, 1e-15);
  EXPECT_NEAR(static_cast<double>(theta.c[3]), 0, 1e-15);
  EXPECT_NEAR(static_cast<double>(theta.c[4]), 0, 1e-15);
  EXPECT_EQ(static_cast<double>(round(ExtendedJet(2.6L) + Time(0)).c[1]), 0);
  EXPECT_EQ(static_cast<double>(round(ExtendedJet(2.6L)).c[0]), 3);
}

}  // namespace
}  // namespace mechkin
