// Range of motion (issue "Say what engineers measure"): limits against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/range.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace range_test {

// Non-Grashof (a, b, c, d) = (60, 60, 50, 90): the crank rocks between the two
// toggles where coupler and rocker stretch out, |BD| = b + c:
// cos θ = (a² + d² − (b + c)²) / (2ad), θ = ±92.12°; from the design at 60°.
TEST(Range, NonGrashofInputLimitsMatchTheClosedForm) {
  const Model m = testing_files::FromJson(testing_files::PlanarFourBar(60, 60, 50, 90, 60, 10));
  const RangeReport r = CalcRange(m, RangeOptions{});
  ASSERT_TRUE(r.ok) << r.message;
  ASSERT_EQ(r.drivers.size(), 1u);
  const double toggle = std::acos((60.0 * 60 + 90.0 * 90 - 110.0 * 110) / (2 * 60.0 * 90)) * 180 / M_PI;
  EXPECT_EQ(r.drivers[0].upper.kind, "limit");
  EXPECT_EQ(r.drivers[0].lower.kind, "limit");
  const double tol = 1e-9 * 180 / M_PI;  // 1e-9 rad
  EXPECT_NEAR(r.drivers[0].upper.value, toggle - 60, tol);
  EXPECT_NEAR(r.drivers[0].lower.value, -toggle - 60, tol);
  EXPECT_EQ(r.drivers[0].unit, "deg");
}

TEST(Range, GrashofCrankTurnsFully) {
  const Model m = testing_files::FromJson(testing_files::PlanarFourBar(40, 120, 80, 100, 60, 10));
  const RangeReport r = CalcRange(m, RangeOptions{});
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.drivers[0].upper.kind, "full turn");
  EXPECT_GT(r.drivers[0].max_condition, 1);
}

// Crank 20, rod 50: the slider travels between the dead centres x = 30 and 70 mm;
// the design puts it at 56.904... (driver value 0 there).
TEST(Range, PistonDrivenSliderFindsBothDeadCentres) {
  const Model m = testing_files::FromJson(testing_files::ReadTestData("piston-driven-slider-crank.json"));
  const RangeReport r = CalcRange(m, RangeOptions{});
  ASSERT_TRUE(r.ok);
  const double x0 = 20 * std::cos(M_PI / 3) + std::sqrt(2500 - 400 * std::sin(M_PI / 3) * std::sin(M_PI / 3));
  EXPECT_EQ(r.drivers[0].lower.kind, "limit");
  EXPECT_EQ(r.drivers[0].upper.kind, "limit");
  EXPECT_NEAR(r.drivers[0].lower.value, 30 - x0, 1e-9 * 40);  // 1e-9 of the stroke
  EXPECT_NEAR(r.drivers[0].upper.value, 70 - x0, 1e-9 * 40);
}

// Bricard's trihedral linkage (IFToMM A04, mechanisms/bricard-mechanism.json): five
// unit rods on the skew hexagon of a unit cube, one redundant equation. Its joint
// angles obey (1 + sin φ)(1 + sin β) = 1 (φ the driven R1, β = −R2), so φ ranges over
// sin φ ≥ −1/2: the folds φ = −π/6 and 7π/6, where β = π/2 is a double root. Whatever
// the steps — folds on a row (360, 3600, 36, 12 per turn), off them (37, 1000) — both
// ends are located to 1e-9 rad and read `limit` (issue 23 item 3: before, `failed` on a
// row, and an end past 7π/6 where the solved rows close but the set-aside one does not).
TEST(Range, BricardFoldsAreLimitsAtEveryStepCount) {
  const Model m = testing_files::FromJson(testing_files::ReadJson("bricard-mechanism.json"));
  for (int steps : {360, 3600, 36, 37, 1000, 12}) {
    RangeOptions o;
    o.steps = steps;
    const RangeReport r = CalcRange(m, o);
    ASSERT_TRUE(r.ok) << r.message;
    const DriverRange& d = r.drivers.at(0);
    EXPECT_EQ(d.lower.kind, "limit") << steps << " steps: " << d.lower.message;
    EXPECT_EQ(d.upper.kind, "limit") << steps << " steps: " << d.upper.message;
    EXPECT_NEAR(d.lower.value * M_PI / 180, -M_PI / 6, 1e-9) << steps << " steps";
    EXPECT_NEAR(d.upper.value * M_PI / 180, 7 * M_PI / 6, 1e-9) << steps << " steps";
  }
}

TEST(Range, UnknownDriverIsNamed) {
  const Model m = testing_files::FromJson(testing_files::PlanarFourBar(40, 120, 80, 100, 60, 10));
  RangeOptions o;
  o.driver = "motr";
  const RangeReport r = CalcRange(m, o);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("drivers: motor"), std::string::npos);
}

}  // namespace
}  // namespace mechkin
