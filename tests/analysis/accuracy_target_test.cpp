// The tolerance is on the answer, not only on the residual (issue "Right at every
// order", item 2): a piston-driven slider-crank approaching its dead centre, run
// with the default settings, against the closed form. Before, the predictor met the
// residual tolerance and the jerk was 2.5e-5 off by t = 0.995 and 6.5e-4 at 0.998;
// solved in double to round-off it was still 1.6e-5 off at 0.998. Where the
// derivatives need a residual below double round-off the position solve now ends in
// extended precision (NewtonSolver::RefineExtended).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "analysis/error_bounds.hpp"
#include "analysis/motion.hpp"
#include "../piston_toggle.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace accuracy_target_test {

using nlohmann::json;

using testing_files::Geometry;
using testing_files::kExact;
using testing_files::kRounded;
using testing_files::PistonDrivenSliderCrank;

struct Worst {
  double error[4] = {0, 0, 0, 0};  // per order, relative to the order's scale θ0·w^k
  double at[4] = {0, 0, 0, 0};
};

// θ − θ0 and its derivatives against the closed form at every row.
Worst CompareWithClosedForm(const Motion& m, double th0) {
  const double w = M_PI / 2;
  const char* names[4] = {"crank_angle", "crank_angle_t", "crank_angle_tt", "crank_angle_ttt"};
  Worst worst;
  for (int r = 0; r < m.rows(); ++r) {
    const double t = m.at(r, m.layout().Find("t")), c = std::cos(w * t), s = std::sin(w * t);
    const double want[4] = {th0 * (c - 1), -th0 * w * s, -th0 * w * w * c, th0 * w * w * w * s};
    for (int k = 0; k < 4; ++k) {
      const double e = std::abs(m.at(r, m.layout().Find(names[k])) - want[k]) / (th0 * std::pow(w, k));
      if (!(e <= worst.error[k])) worst.error[k] = e, worst.at[k] = t;
    }
  }
  return worst;
}

Motion RunToNearTheDeadCentre(const Geometry& g) {
  TableOptions table;
  table.si = true;
  table.order = 3;
  table.all_bodies = false;
  return RunMotion(testing_files::FromJson(PistonDrivenSliderCrank(g, 0.998, 499)), AnalysisOptions{}, table);
}

TEST(AccuracyTarget, PistonDrivenSliderCrankNearItsDeadCentre) {
  const Motion m = RunToNearTheDeadCentre(kExact);
  ASSERT_TRUE(m.complete) << m.report.message;
  ASSERT_EQ(m.rows(), 500);
  const Worst worst = CompareWithClosedForm(m, std::atan2(kExact.by, kExact.bx));
  for (int k = 0; k < 4; ++k) {
    std::printf("order %d: worst %.3g of its scale at t = %.3f\n", k, worst.error[k], worst.at[k]);
    RecordProperty("worst_order_" + std::to_string(k), std::to_string(worst.error[k]));
    // Every order within 1e-6 of its scale at every row, to t = 0.998.
    EXPECT_LT(worst.error[k], 1e-6) << "order " << k << " at t = " << worst.at[k];
  }
  // It is ill-conditioned there: the accuracy came from solving to what the
  // derivatives need, not from a benign geometry.
  EXPECT_GT(m.at(m.rows() - 1, m.layout().Find("condition")), 100);
}

// The same motion with the 20/50 mm crank at 60°: the solve is as accurate, but the
// file's rounded numbers describe a slightly different mechanism, and so near the dead
// centre the closed form of the intended one is only met to what that difference
// allows (tools/piston_conditioning.py: one double spacing of a 70 mm coordinate moves
// the exact jerk by 2.8e-5 of its scale there). Position and velocity are unaffected.
TEST(AccuracyTarget, RoundedGeometryMovesTheExactJerkNotTheSolve) {
  const Motion m = RunToNearTheDeadCentre(kRounded);
  ASSERT_TRUE(m.complete) << m.report.message;
  const Worst worst = CompareWithClosedForm(m, M_PI / 3);
  for (int k = 0; k < 4; ++k) std::printf("order %d: worst %.3g of its scale at t = %.3f\n", k, worst.error[k], worst.at[k]);
  EXPECT_LT(worst.error[0], 1e-10);
  EXPECT_LT(worst.error[1], 1e-9);
  EXPECT_LT(worst.error[3], 1e-5);  // 4.3e-5 when solved in double
}

// The extended phase runs only where a double residual cannot give the derivatives
// the tolerance and the row approaches a singular position (error_bounds.hpp).
TEST(AccuracyTarget, ExtendedPrecisionOnlyWhereASingularPositionIsNear) {
  EXPECT_TRUE(NeedsExtendedResidual(1e-10, 2000, 5.4, 3));    // the piston at t = 0.998
  EXPECT_FALSE(NeedsExtendedResidual(1e-10, 74, 5.4, 3));     // the piston at t = 0.95: double suffices
  EXPECT_FALSE(NeedsExtendedResidual(1e-10, 6500, 5450, 3));  // a geared chain: κ high all along
  EXPECT_FALSE(NeedsExtendedResidual(1e-14, 30, 5, 3));       // tight tolerance on a regular row
  EXPECT_FALSE(NeedsExtendedResidual(1e-6, 2000, 5, 3));      // loose tolerance: tol/κ² above the floor
}

}  // namespace
}  // namespace mechkin
