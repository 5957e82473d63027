// Assembly branch hints (issue "Say what engineers measure"): a four-bar drawn
// open, run on its crossed branch from an approximate rocker angle.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace branch_test {

// Rocker angle atan2(Cy, Cx − d) of the open (sign = +1) or crossed (−1) assembly.
double Rocker(double a, double b, double c, double d, double th, double sign) {
  const double Bx = a * std::cos(th), By = a * std::sin(th);
  const double dx = d - Bx, dy = -By, dist = std::hypot(dx, dy);
  const double al = (b * b - c * c + dist * dist) / (2 * dist), h = sign * std::sqrt(b * b - al * al);
  const double Cx = Bx + (al * dx - h * dy) / dist, Cy = By + (al * dy + h * dx) / dist;
  return std::atan2(Cy, Cx - d);
}

TEST(Branch, CrossedFourBarFromAHint) {
  const double a = 40, b = 120, c = 80, d = 100, th0 = 60 * M_PI / 180;
  nlohmann::json doc = testing_files::PlanarFourBar(a, b, c, d, 60, 72);
  const double open0 = Rocker(a, b, c, d, th0, 1);
  const double hint = (Rocker(a, b, c, d, th0, -1) - open0) * 180 / M_PI + 4;  // 4° off: a sketch
  doc["analysis"]["branch"] = {{"joints", {{"D", hint}}}};
  TableOptions table;
  table.order = 1;
  const Motion m = RunMotion(testing_files::FromJson(doc), AnalysisOptions{}, table);
  ASSERT_TRUE(m.complete) << m.stop.message;
  const int col = m.layout().Find("rocker_angle");
  for (int r = 0; r < m.rows(); ++r) {
    const double th = th0 + 2 * M_PI * m.at(r, 0);
    const double expect = Rocker(a, b, c, d, th, -1) - open0;  // from the (open) design pose
    EXPECT_NEAR(std::remainder(m.at(r, col) * M_PI / 180 - expect, 2 * M_PI), 0, 1e-9) << r;
    // and not the open branch
    EXPECT_GT(std::abs(std::remainder(m.at(r, col) * M_PI / 180 - (Rocker(a, b, c, d, th, 1) - open0), 2 * M_PI)), 0.1);
  }
}

TEST(Branch, HintOnAnUnknownJointIsAnError) {
  nlohmann::json doc = testing_files::PlanarFourBar(40, 120, 80, 100, 60, 72);
  doc["analysis"]["branch"] = {{"joints", {{"E", 10}}}};
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors[0].pointer, "/analysis/branch/joints/E");
}

}  // namespace
}  // namespace mechkin

#include "analysis/branches.hpp"

namespace mechkin {
namespace branch_test {

// A four-bar at a given crank angle closes in two ways (open and crossed); so does
// a slider-crank (the rod on either side of the crank pin). Joints mounted
// backwards (a body flipped over) are not counted.
TEST(Branch, CountsTheAssemblies) {
  const Model four_bar = testing_files::FromJson(testing_files::PlanarFourBar(40, 120, 80, 100, 60, 10));
  const BranchCount fb = CountBranches(four_bar, 200, 3);
  EXPECT_EQ(fb.branches, 2);
  EXPECT_GT(fb.converged, 100);
  EXPECT_NEAR(fb.distances[0], 0, 1e-9);  // the design pose itself first
  const Model slider = testing_files::FromJson(testing_files::ReadJson("offset-slider-crank.json"));
  EXPECT_EQ(CountBranches(slider, 200, 3).branches, 2);
}

}  // namespace
}  // namespace mechkin
