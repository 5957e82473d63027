// Joint coordinates from the markers (issue "Describe mechanisms as designers do"):
// a joint on markers measures its coordinate from the markers' coincidence, so the
// crank's 0 of a marker four-bar is "crank along the frame line" for every crank
// length of a sweep, and the rocker's angle there is the closed form's — where a
// file written in global coordinates reads 0 at its design pose for every variant.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "analysis/assembly.hpp"
#include "analysis/range.hpp"
#include "analysis/sweep.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace marker_coordinates_test {

constexpr double kDeg = M_PI / 180;
constexpr double kCoupler = 120, kRocker = 80, kFrame = 100;

Model MarkerFourBar(const ParameterOverrides& overrides) {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/tests/data/marker-four-bar.json", overrides);
  EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  return r.ok() ? std::move(*r.model) : Model{};
}

// The rocker's angle θ4 from the frame line at crank angle θ2 (open branch, C above
// the frame line): C is b from B = a(cos θ2, sin θ2) and c from D = (d, 0).
double RockerAngle(double a, double b, double c, double d, double th2) {
  const double xb = a * std::cos(th2), yb = a * std::sin(th2);
  const double e = std::hypot(xb - d, yb), beta = std::atan2(yb, xb - d);
  return beta - std::acos((c * c + e * e - b * b) / (2 * c * e));
}

// The closed form above satisfies Freudenstein's equation
// K1 cos θ4 − K2 cos θ2 + K3 = cos(θ2 − θ4), K1 = d/a, K2 = d/c, K3 = (a² − b² + c² + d²)/(2ac).
TEST(MarkerCoordinates, TheClosedFormSatisfiesFreudenstein) {
  for (double a : {30.0, 35.0, 40.0, 45.0, 50.0})
    for (double th2 : {0.0, 1.0, 2.5}) {
      const double th4 = RockerAngle(a, kCoupler, kRocker, kFrame, th2);
      const double k1 = kFrame / a, k2 = kFrame / kRocker;
      const double k3 = (a * a - kCoupler * kCoupler + kRocker * kRocker + kFrame * kFrame) / (2 * a * kRocker);
      EXPECT_NEAR(k1 * std::cos(th4) - k2 * std::cos(th2) + k3, std::cos(th2 - th4), 1e-12) << a << " " << th2;
    }
}

// Acceptance: a sweep of the marker four-bar over its crank length with the crank held
// at 0 (speed = 0): every variant's rocker angle is the closed form's at θ2 = 0 (62.7°
// for the nominal crank, not 0), though the bodies are drawn at 60° and close only
// for crank = 40.
TEST(MarkerCoordinates, SweepOverTheCrankReadsTheClosedFormAtTheCranksZero) {
  const Model model = MarkerFourBar({{"speed", 0}});
  GridAxis axis;
  std::string why;
  ASSERT_TRUE(ParseGridAxis("crank=30:50:5", &axis, &why));
  SweepOptions options;
  options.request.order = 0;
  const SweepResult r = RunSweep(model, GridVariants({axis}), options);
  ASSERT_EQ(r.variants.size(), 5u);
  const auto col = [&](const std::string& header) {
    const auto it = std::find(r.columns.begin(), r.columns.end(), header);
    EXPECT_NE(it, r.columns.end()) << header;
    return static_cast<size_t>(it - r.columns.begin());
  };
  const size_t crank = col("crank_angle [deg]"), rocker = col("rocker_angle [deg]");
  for (const VariantSummary& v : r.variants) {
    ASSERT_EQ(v.status, "complete") << v.message;
    const double a = v.values[0];
    const double expected = RockerAngle(a, kCoupler, kRocker, kFrame, 0) / kDeg;
    EXPECT_NEAR(v.min[crank], 0, 1e-9);
    EXPECT_NEAR(v.max[crank], 0, 1e-9);
    EXPECT_NEAR(v.min[rocker], expected, 1e-8) << "crank " << a;
    EXPECT_NEAR(v.max[rocker], expected, 1e-8) << "crank " << a;
    EXPECT_GT(expected, 40);  // 73.9° at 30 down to 46.6° at 50: far from 0
  }
}

// The contrast, unchanged: the global-form parametric four-bar measures from its
// design pose, so its rocker reads 0 at the start (the design pose) for every variant.
TEST(MarkerCoordinates, GlobalJointsStillMeasureFromTheDesignPose) {
  LoadResult loaded = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json");
  ASSERT_TRUE(loaded.ok());
  for (double a : {30.0, 50.0}) {
    const LoadResult variant = WithParameters(*loaded.model, {{"a", a}});
    ASSERT_TRUE(variant.ok());
    EXPECT_EQ(DesignDriverValue(*variant.model, variant.model->drivers[0]), 0.0);
    TableOptions table;
    table.order = 0;
    const Motion m = RunMotion(*variant.model, AnalysisOptions{}, table);
    ASSERT_TRUE(m.complete);
    EXPECT_NEAR(m.at(0, m.layout().Find("rocker_angle")), 0, 1e-9);
  }
}

// The whole motion of a variant (crank 50, drawn for 40 at 60°) against the closed
// form, row by row; the crank's pin marker lies on the frame line at t = 0.
TEST(MarkerCoordinates, AVariantsMotionMatchesTheClosedFormFromTheMarkersZero) {
  const Model m = MarkerFourBar({{"crank", 50}});
  // drawn at 60°, assembled with the driver at 0: the design pose has the markers together
  EXPECT_NEAR(DesignDriverValue(m, m.drivers[0]), 0, 1e-12);
  TableOptions table;
  table.order = 1;
  const Motion motion = RunMotion(m, AnalysisOptions{}, table);
  ASSERT_TRUE(motion.complete) << motion.stop.message;
  const int t = motion.layout().Find("t"), crank = motion.layout().Find("crank_angle");
  const int rocker = motion.layout().Find("rocker_angle"), e3 = motion.layout().Find("crank.e3");
  ASSERT_GE(rocker, 0);
  ASSERT_GE(e3, 0);
  for (int row = 0; row < motion.rows(); ++row) {
    const double th2 = 360 * motion.at(row, t) * kDeg;
    EXPECT_NEAR(motion.at(row, crank), th2 / kDeg, 1e-9) << row;
    // continuous over the turn: unwrap the closed form towards the column
    const double th4 = RockerAngle(50, kCoupler, kRocker, kFrame, th2) / kDeg;
    EXPECT_NEAR(std::remainder(motion.at(row, rocker) - th4, 360), 0, 1e-8) << row;
  }
  EXPECT_NEAR(motion.at(0, e3), 0, 1e-12);  // the crank along ground's x: its markers' x axes coincide
}

// `range` starts from the design value — the assembly held the driver at its markers'
// coincidence, 0, although the file draws the crank at 60° — and the crank turns fully.
TEST(MarkerCoordinates, RangeStartsFromTheMarkersCoincidence) {
  const Model m = MarkerFourBar({});
  RangeOptions options;
  options.steps = 72;
  const RangeReport r = CalcRange(m, options);
  ASSERT_TRUE(r.ok) << r.message;
  ASSERT_EQ(r.drivers.size(), 1u);
  EXPECT_NEAR(r.drivers[0].design_value, 0, 1e-9);
  EXPECT_EQ(r.drivers[0].upper.kind, "full turn");
}

// A prismatic joint on markers: its slide is marker2's origin along marker1's axis
// from marker1's origin; a slider drawn 30 mm along the guide is assembled with the
// driver at 0, its markers together, and slides 5 mm from there.
TEST(MarkerCoordinates, APrismaticOnMarkersSlidesFromTheirCoincidence) {
  const nlohmann::json doc = {
      {"mechkin", 1},
      {"units", {{"length", "mm"}}},
      {"ground", {{"markers", {{"rail", {{"point", {10, 0, 0}}, {"axis", {1, 0, 0}}}}}}}},
      {"bodies",
       {{{"name", "slider"}, {"position", {40, 0, 0}}, {"markers", {{"shoe", {{"point", {0, 0, 0}}, {"axis", {1, 0, 0}}}}}}}}},
      {"joints",
       {{{"name", "guide"}, {"type", "prismatic"}, {"body1", "ground"}, {"body2", "slider"}, {"marker1", "rail"}, {"marker2", "shoe"}}}},
      {"drivers", {{{"name", "push"}, {"type", "translation"}, {"joint", "guide"}, {"function", "5*t"}}}},
      {"analysis", {{"start", 0}, {"end", 1}, {"steps", 2}}},
      {"outputs", {{{"name", "slide"}, {"type", "joint"}, {"joint", "guide"}}}}};
  const Model m = testing_files::FromJson(doc);
  ASSERT_EQ(m.drivers.size(), 1u);
  EXPECT_NEAR(DesignDriverValue(m, m.drivers[0]), 0, 1e-15);
  TableOptions table;
  table.order = 0;
  const Motion motion = RunMotion(m, AnalysisOptions{}, table);
  ASSERT_TRUE(motion.complete) << motion.stop.message;
  for (int row = 0; row < motion.rows(); ++row) {
    const double slide = 5 * motion.at(row, motion.layout().Find("t"));
    EXPECT_NEAR(motion.at(row, motion.layout().Find("slide")), slide, 1e-9);
    EXPECT_NEAR(motion.at(row, motion.layout().Find("slider.x")), 10 + slide, 1e-9);
  }
}

}  // namespace
}  // namespace mechkin
