// The tolerance is on the answer, not only on the residual (issue "Right at every
// order", item 2): a piston-driven slider-crank approaching its dead centre, run
// with the default settings, against the closed form. Before, the predictor met the
// residual tolerance and the jerk was 2.5e-5 off by t = 0.995 and 6.5e-4 at 0.998.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/motion.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace {

using nlohmann::json;

// Crank a = 20 mm, rod b = 50 mm, no offset; the piston is driven so that the crank
// angle is θ(t) = θ0·cos(πt/2) exactly: the dead centre θ = 0 at t = 1.
//   x(θ) = a cos θ + sqrt(b² − a² sin² θ)
json PistonDrivenSliderCrank(double end, int steps) {
  const double a = 20, b = 50, th0 = M_PI / 3;
  const double bx = a * std::cos(th0), by = a * std::sin(th0), cx = bx + std::sqrt(b * b - by * by);
  char fn[256];
  std::snprintf(fn, sizeof fn, "%.17g*cos(%.17g*cos(pi*t/2)) + sqrt(%.17g - %.17g*sin(%.17g*cos(pi*t/2))^2) - %.17g", a, th0,
                b * b, a * a, th0, cx);
  return {{"mechkin", 1}, {"units", {{"length", "mm"}, {"angle", "deg"}}},
          {"bodies", {{{"name", "crank"}, {"position", {bx / 2, by / 2, 0}}},
                      {{"name", "rod"}, {"position", {(bx + cx) / 2, by / 2, 0}}},
                      {{"name", "slider"}, {"position", {cx, 0, 0}}}}},
          {"joints", {{{"name", "A"}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "crank"}, {"origin", {0, 0, 0}}, {"axis", {0, 0, 1}}},
                      {{"name", "B"}, {"type", "revolute"}, {"body1", "crank"}, {"body2", "rod"}, {"origin", {bx, by, 0}}, {"axis", {0, 0, 1}}},
                      {{"name", "C"}, {"type", "revolute"}, {"body1", "rod"}, {"body2", "slider"}, {"origin", {cx, 0, 0}}, {"axis", {0, 0, 1}}},
                      {{"name", "P"}, {"type", "prismatic"}, {"body1", "ground"}, {"body2", "slider"}, {"origin", {cx, 0, 0}}, {"axis", {1, 0, 0}}}}},
          {"drivers", {{{"name", "piston"}, {"type", "translation"}, {"joint", "P"}, {"function", fn}}}},
          {"outputs", {{{"name", "crank_angle"}, {"type", "joint"}, {"joint", "A"}}}},
          {"analysis", {{"start", 0}, {"end", end}, {"steps", steps}}}};
}

TEST(AccuracyTarget, PistonDrivenSliderCrankNearItsDeadCentre) {
  const double th0 = M_PI / 3, w = M_PI / 2;
  TableOptions table;
  table.si = true;
  table.order = 3;
  table.all_bodies = false;
  const Motion m = RunMotion(testing_files::FromJson(PistonDrivenSliderCrank(0.998, 499)), AnalysisOptions{}, table);
  ASSERT_TRUE(m.complete) << m.report.message;
  ASSERT_EQ(m.rows(), 500);
  const char* names[4] = {"crank_angle", "crank_angle_t", "crank_angle_tt", "crank_angle_ttt"};
  // θ − θ0 and its derivatives; scale of order k: θ0·w^k (the largest magnitude over the motion).
  for (int r = 0; r < m.rows(); ++r) {
    const double t = m.at(r, m.layout().Find("t")), c = std::cos(w * t), s = std::sin(w * t);
    const double want[4] = {th0 * (c - 1), -th0 * w * s, -th0 * w * w * c, th0 * w * w * w * s};
    for (int k = 0; k < 4; ++k) {
      // Every order within 1e-6 of its scale to t = 0.995; in the last rows the jerk
      // meets the round-off floor 8u·κ³ (κ ≈ 2e3 at t = 0.998), which no double-
      // precision solve beats, and the row says so (below).
      const double allowed = k == 3 && t > 0.995 ? 1e-4 : 1e-6;
      const double scale = th0 * std::pow(w, k);
      EXPECT_NEAR(m.at(r, m.layout().Find(names[k])), want[k], allowed * scale) << names[k] << " at t = " << t;
    }
  }
  const int last = m.rows() - 1;
  EXPECT_GT(m.at(last, m.layout().Find("error_bound_ttt")), 1e-6);
  EXPECT_LT(m.at(last, m.layout().Find("error_bound_t")), 1e-6);
  // It is ill-conditioned there: the accuracy came from solving to what the
  // derivatives need, not from a benign geometry.
  EXPECT_GT(m.at(m.rows() - 1, m.layout().Find("condition")), 100);
}

}  // namespace
}  // namespace mechkin
