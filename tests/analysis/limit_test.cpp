// Limits of motion located exactly (issue "Right at every order", item 5): a
// slider-crank whose piston is driven past its stroke end stops at the stroke end,
// located to 1e-9 of the stroke, and says it is a limit of motion.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/kinematic_analysis.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace limit_test {

TEST(LimitOfMotion, PistonDrivenPastItsStrokeEnd) {
  // tests/data/piston-driven-slider-crank.json: crank 20 mm, rod 50 mm, no offset,
  // design crank angle 60°; the piston's largest reach is a + b = 70 mm from the crank pivot.
  nlohmann::json j = testing_files::ReadTestData("piston-driven-slider-crank.json");
  const double a = 20, b = 50, th0 = M_PI / 3;
  const double x0 = a * std::cos(th0) + std::sqrt(b * b - a * a * std::sin(th0) * std::sin(th0));
  const double overshoot = 70.5 - x0;  // the driver asks for 0.5 mm past the stroke end at t = 1
  char fn[64];
  std::snprintf(fn, sizeof fn, "%.17g*t", overshoot);
  j["drivers"][0]["function"] = fn;
  j["analysis"] = {{"start", 0}, {"end", 1}, {"steps", 100}};
  const Model m = testing_files::FromJson(j);
  int rows = 0;
  const AnalysisReport rep =
      RunKinematicAnalysis(m, AnalysisOptions{}, [&](const SystemState&, const StepDiagnostics&) { return ++rows > 0; });
  ASSERT_FALSE(rep.complete);
  ASSERT_TRUE(rep.limit.has_value()) << rep.message;
  EXPECT_TRUE(rep.limit->fold);
  const double stroke = 2 * a;
  EXPECT_NEAR(rep.limit->driver_values[0], (70 - x0) * 1e-3, 1e-9 * stroke * 1e-3);  // SI
  EXPECT_NEAR(rep.limit->t, (70 - x0) / overshoot, 1e-9);
  EXPECT_EQ(rows, 97);  // rows up to t = 0.96 are kept
  EXPECT_NE(rep.message.find("limit of motion at t = 0.96322405"), std::string::npos) << rep.message;
  EXPECT_NE(rep.message.find("driver `piston` = 13.09584240"), std::string::npos) << rep.message;
}

// A non-Grashof four-bar (ground 100, input 70, coupler 40, rocker 60 mm) driven at
// its input from 60°: the input cannot pass the angle where coupler and rocker
// line up, cos θ* = (70² + 100² − (40 + 60)²) / (2·70·100). Located to 1e-9 rad,
// also across a re-selection of its redundant equations near the limit.
TEST(LimitOfMotion, NonGrashofInputReachesItsLimit) {
  const double g = 100, a = 70, b = 40, c = 60, th = M_PI / 3;
  nlohmann::json j = testing_files::PlanarFourBar(a, b, c, g, 60, 90);
  j["drivers"][0]["function"] = "90*t";
  const AnalysisReport rep = RunKinematicAnalysis(testing_files::FromJson(j), AnalysisOptions{},
                                                  [](const SystemState&, const StepDiagnostics&) { return true; });
  ASSERT_FALSE(rep.complete);
  ASSERT_TRUE(rep.limit.has_value()) << rep.message;
  EXPECT_TRUE(rep.limit->fold);
  const double limit = std::acos((a * a + g * g - (b + c) * (b + c)) / (2 * a * g));
  EXPECT_NEAR(rep.limit->driver_values[0], limit - th, 1e-9);
  EXPECT_FALSE(rep.singular.has_value());
}

// A spatial RCCC (tests/data/rccc-input-limit-90.json): revolute input on ground about
// z, cylinders crank–coupler, coupler–follower, follower–ground; twists 90°, 45°, 45°,
// 45° between consecutive axes. The axes' directions form a spherical four-bar: the arc
// d24 from the crank's cylinder axis z2 = (cos θ, sin θ, 0) to the ground's z4 =
// (1, 0, 1)/√2 has cos d24 = cos θ/√2, and coupler and follower reach at most 45° + 45°,
// so θ ≤ 90° exactly; the offsets were drawn from the stretched pose (θ = 90°), so the
// slides stay finite up to it (there z2, z3, z4 are coplanar and the cylinders may also
// slide together: Φ_q loses rank 2, one of them the fold). Issue 23 item 4: before,
// "singular position" 0.0018° past 90° (probes that had left the branch counted).
TEST(LimitOfMotion, SpatialRcccInputStopsAt90Degrees) {
  for (const char* function : {"360*t", "97*t"}) {  // 90° on a row (t = 0.25), and off rows
    nlohmann::json j = testing_files::ReadTestData("rccc-input-limit-90.json");
    j["drivers"][0]["function"] = function;
    j["analysis"] = {{"start", 0}, {"end", function[0] == '3' ? 0.5 : 1.0}, {"steps", 100}};
    const AnalysisReport rep = RunKinematicAnalysis(testing_files::FromJson(j), AnalysisOptions{},
                                                    [](const SystemState&, const StepDiagnostics&) { return true; });
    ASSERT_FALSE(rep.complete) << function;
    ASSERT_TRUE(rep.limit.has_value()) << function << ": " << rep.message;
    EXPECT_FALSE(rep.singular.has_value()) << function;
    EXPECT_TRUE(rep.limit->fold) << function;
    EXPECT_TRUE(rep.notes.empty()) << function << ": " << rep.notes.front();  // no passage claimed on the way
    EXPECT_NEAR(rep.limit->driver_values[0], M_PI / 2, 1e-9) << function;
    EXPECT_EQ(rep.message.rfind("limit of motion at t = ", 0), 0u) << rep.message;
    EXPECT_NE(rep.message.find("driver `motor` = 90 deg"), std::string::npos) << rep.message;
    EXPECT_NE(rep.message.find("the branch folds there"), std::string::npos) << rep.message;
  }
}

}  // namespace
}  // namespace mechkin
