// Driver functions of time: exact derivatives to the 4th order.
#include <gtest/gtest.h>

#include <memory>

#include "model/time_function.hpp"

namespace mechkin {
namespace time_function_test {

void ExpectDerivatives(const std::string& text, double t, const std::array<double, 5>& want) {
  const Expression e = Expression::Parse(text);
  const Jet j = e.Eval(t);
  for (int k = 0; k <= 4; ++k)
    EXPECT_NEAR(j.Derivative(k), want[k], 1e-12 * (1 + std::abs(want[k]))) << text << " order " << k;
}

TEST(Expression, ClosedForms) {
  const double t = 0.7;
  ExpectDerivatives("3*t^4 - 2*t + 1", t, {3 * std::pow(t, 4) - 2 * t + 1, 12 * t * t * t - 2, 36 * t * t, 72 * t, 72});
  const double w = 2 * M_PI;
  ExpectDerivatives("sin(2*pi*t)", t, {std::sin(w * t), w * std::cos(w * t), -w * w * std::sin(w * t),
                                       -w * w * w * std::cos(w * t), w * w * w * w * std::sin(w * t)});
  ExpectDerivatives("exp(-2*t)", t, {std::exp(-2 * t), -2 * std::exp(-2 * t), 4 * std::exp(-2 * t),
                                     -8 * std::exp(-2 * t), 16 * std::exp(-2 * t)});
  ExpectDerivatives("log(t)", t, {std::log(t), 1 / t, -1 / (t * t), 2 / (t * t * t), -6 / (t * t * t * t)});
  ExpectDerivatives("sqrt(t)", t, {std::sqrt(t), 0.5 / std::sqrt(t), -0.25 * std::pow(t, -1.5),
                                   0.375 * std::pow(t, -2.5), -0.9375 * std::pow(t, -3.5)});
  ExpectDerivatives("1/(1+t)", t, {1 / (1 + t), -1 / std::pow(1 + t, 2), 2 / std::pow(1 + t, 3),
                                   -6 / std::pow(1 + t, 4), 24 / std::pow(1 + t, 5)});
  ExpectDerivatives("atan(t)", t, {std::atan(t), 1 / (1 + t * t), -2 * t / std::pow(1 + t * t, 2),
                                   (6 * t * t - 2) / std::pow(1 + t * t, 3), 24 * t * (1 - t * t) / std::pow(1 + t * t, 4)});
  ExpectDerivatives("t^2.5", t, {std::pow(t, 2.5), 2.5 * std::pow(t, 1.5), 3.75 * std::pow(t, 0.5),
                                 1.875 * std::pow(t, -0.5), -0.9375 * std::pow(t, -1.5)});
  ExpectDerivatives("-2^2", t, {-4, 0, 0, 0, 0});  // unary minus binds looser than ^
  ExpectDerivatives("2^3^2", t, {512, 0, 0, 0, 0});  // right-associative
}

// The extended-precision value (the position solve's accuracy phase) is the same
// function: it agrees with Eval everywhere, and where double cancels it keeps the
// 11 more bits long double has: (1 + t) − 1 at t = 1e-10 is t to 2^-64, while double
// loses 7 of its digits.
TEST(Expression, ExtendedValueKeepsTheDigitsDoubleCancels) {
  for (const char* text : {"3*t^4 - 2*t + 1", "sin(2*pi*t)", "exp(-2*t)", "log(t)", "sqrt(t)", "atan2(sin(t), 2+cos(t))",
                           "t^2.5", "asin(t/2) + acos(t/3) + tan(t/3) + atan(t) - 1/(1+t)"}) {
    const Expression e = Expression::Parse(text);
    EXPECT_NEAR(static_cast<double>(e.ValueExtended(0.7)), e.Eval(0.7).c[0], 4e-16 * (1 + std::abs(e.Eval(0.7).c[0]))) << text;
  }
  const Expression e = Expression::Parse("(1 + t) - 1");
  const double t = 1e-10;
  EXPECT_GT(std::abs(e.Eval(t).c[0] - t), 1e-18);
  EXPECT_LT(std::abs(e.ValueExtended(t) - static_cast<long double>(t)), 1.1e-19L);
  const TimeFunction in_mm(std::make_shared<Expression>(e), 1e-3);
  EXPECT_LT(std::abs(in_mm.ValueExtended(t) - static_cast<long double>(t) * 1e-3L), 1e-22L);
}

// The names a parameter expression depends on, by scanning: exponents are part of
// their numbers, reserved names are not parameters, repeats stay.
TEST(Expression, NamesAreTheParametersUsed) {
  EXPECT_EQ(Expression::Names("2e-3*a + sin(b_1) - t*pi + 1.5E+2*c/a"),
            (std::vector<std::string>{"a", "b_1", "c", "a"}));
  EXPECT_EQ(Expression::Names("sqrt(rod^2 - (offset - pin_y)^2)"),
            (std::vector<std::string>{"rod", "offset", "pin_y"}));
  EXPECT_TRUE(Expression::Names("1e5 + .5e-2 * 3").empty());
  EXPECT_EQ(Expression::Names("2ea"), (std::vector<std::string>{"ea"}));  // "2e" has no exponent digits
}

// The composite functions agree with 5-point finite differences of the value.
TEST(Expression, CompositesAgreeWithFiniteDifferences) {
  for (const char* text : {"tan(t/3)", "asin(t/2)", "acos(t/3)", "atan2(sin(t), 2+cos(t))", "exp(sin(t))*t^3"}) {
    const Expression e = Expression::Parse(text);
    const double t = 0.4, h = 1e-3;
    const double fd1 = (e.Eval(t - 2 * h).c[0] - 8 * e.Eval(t - h).c[0] + 8 * e.Eval(t + h).c[0] - e.Eval(t + 2 * h).c[0]) / (12 * h);
    const double fd2 = (-e.Eval(t - 2 * h).c[0] + 16 * e.Eval(t - h).c[0] - 30 * e.Eval(t).c[0] + 16 * e.Eval(t + h).c[0] -
                        e.Eval(t + 2 * h).c[0]) / (12 * h * h);
    const double fd4 = (e.Eval(t - 2 * h).Derivative(2) - 2 * e.Eval(t).Derivative(2) + e.Eval(t + 2 * h).Derivative(2)) / (4 * h * h);
    EXPECT_NEAR(e.Eval(t).Derivative(1), fd1, 1e-9) << text;
    EXPECT_NEAR(e.Eval(t).Derivative(2), fd2, 1e-6) << text;
    EXPECT_NEAR(e.Eval(t).Derivative(4), fd4, 1e-4 * (1 + std::abs(fd4))) << text;
  }
}

TEST(Expression, ErrorsNameTheColumn) {
  struct Bad { const char* text; int column; };
  for (const Bad& b : {Bad{"360*t +* 2", 8}, Bad{"sinh(t)", 1}, Bad{"2*(t+1", 7}, Bad{"t $ 2", 3}, Bad{"", 1},
                       Bad{"atan2(t)", 8}, Bad{"1.2.3", 1}}) {
    try {
      Expression::Parse(b.text);
      ADD_FAILURE() << b.text << " parsed";
    } catch (const ExpressionError& e) {
      EXPECT_EQ(e.column, b.column) << b.text << ": " << e.what();
    }
  }
  EXPECT_THROW(Expression::Parse(std::string(500, '(') + "t" + std::string(500, ')')), ExpressionError);
}

TEST(Expression, DomainErrorsAreReportedNotNaN) {
  EXPECT_THROW(Expression::Parse("log(t)").Eval(-1), JetDomainError);
  EXPECT_THROW(Expression::Parse("sqrt(t-2)").Eval(1), JetDomainError);
  EXPECT_THROW(Expression::Parse("1/(t-1)").Eval(1), JetDomainError);
}

// Tables: a quintic spline reproduces the data, is C4 across knots, and its
// derivatives agree with finite differences of its values; outside the range it throws.
TEST(TableSpline, InterpolatesSmoothly) {
  std::vector<double> t, v;
  for (int k = 0; k <= 20; ++k) { t.push_back(0.05 * k); v.push_back(std::sin(3 * t.back())); }
  const TableSpline s(t, v);
  for (size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(s.Eval(t[k]).c[0], v[k], 1e-13);
  for (int d = 1; d <= 4; ++d) {
    const double knot = t[7], eps = 1e-9;
    EXPECT_NEAR(s.Eval(knot - eps).Derivative(d), s.Eval(knot + eps).Derivative(d),
                1e-5 * (1 + std::abs(s.Eval(knot).Derivative(d))))
        << "order " << d;
  }
  const double x = 0.33, h = 1e-4;
  const double fd1 = (s.Eval(x + h).c[0] - s.Eval(x - h).c[0]) / (2 * h);
  const double fd3 = (s.Eval(x + h).Derivative(2) - s.Eval(x - h).Derivative(2)) / (2 * h);
  EXPECT_NEAR(s.Eval(x).Derivative(1), fd1, 1e-7);
  EXPECT_NEAR(s.Eval(x).Derivative(3), fd3, 1e-5);
  // Interior accuracy against the function the table samples.
  EXPECT_NEAR(s.Eval(x).Derivative(1), 3 * std::cos(3 * x), 1e-4);
  EXPECT_THROW(s.Eval(1.5), std::out_of_range);
  EXPECT_THROW(TableSpline({0, 0}, {1, 2}), std::invalid_argument);
}

}  // namespace
}  // namespace mechkin
