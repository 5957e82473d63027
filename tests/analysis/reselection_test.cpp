// Redundancy that follows the motion: a Bennett linkage whose redundant equations
// change along the turn runs the whole turn, and its output matches Bennett's
// closed form; mechanisms without that need never re-select.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/motion.hpp"
#include "../bennett.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace reselection_test {

using nlohmann::json;
using Eigen::Matrix3d;
using Eigen::Vector3d;

using testing_files::Bennett;
using testing_files::BennettTheta2;

Motion RunBennett(const json& doc, double tol, AnalysisReport* report) {
  TableOptions table;
  table.si = true;
  table.order = 2;
  table.all_bodies = false;
  AnalysisOptions options;
  options.tolerance = tol;
  Motion m = RunMotion(testing_files::FromJson(doc), options, table);
  *report = m.report;
  return m;
}

// Twists 40°/65°: with the equations set aside at assembly the reduced Jacobian
// turns singular at t ≈ 0.31 s although the mechanism is regular all the way round.
TEST(Reselection, BennettFortySixtyFiveRunsAFullTurnOnItsClosedForm) {
  const double alpha = 40 * M_PI / 180, beta = 65 * M_PI / 180, theta1 = 70 * M_PI / 180;
  const json doc = Bennett(alpha, beta, theta1, 360);
  // The tolerance is on the residual; 1e-12 puts the angles within 1e-9 rad at the
  // condition numbers met here (≤ 100, dimensionless).
  AnalysisReport report;
  const Motion m = RunBennett(doc, 1e-12, &report);
  ASSERT_TRUE(m.complete) << report.message;
  ASSERT_EQ(m.rows(), 361);
  EXPECT_GE(report.reselections.size(), 1u);
  EXPECT_LT(report.reselections.front().t, 0.32);
  const int c1 = m.layout().Find("theta1"), c2 = m.layout().Find("theta2");
  const double theta2_design = BennettTheta2(theta1, alpha, beta);
  for (int r = 0; r < m.rows(); ++r) {
    const double t1 = theta1 + m.at(r, c1), t2 = theta2_design + m.at(r, c2);
    EXPECT_NEAR(m.at(r, c1), 2 * M_PI * r / 360, 1e-12);
    EXPECT_NEAR(std::remainder(t2 - BennettTheta2(t1, alpha, beta), 2 * M_PI), 0, 1e-9) << "row " << r;
  }
  // The same run at the default tolerance also completes, within 1e-9 rad (4.9e-11
  // measured: the solve meets the tolerance on the answer).
  AnalysisReport coarse;
  const Motion d = RunBennett(doc, 1e-10, &coarse);
  ASSERT_TRUE(d.complete) << coarse.message;
  for (int r = 0; r < d.rows(); ++r)
    EXPECT_NEAR(std::remainder(theta2_design + d.at(r, c2) - BennettTheta2(theta1 + d.at(r, c1), alpha, beta), 2 * M_PI), 0, 1e-9);
}

TEST(Reselection, NotNeededWhereTheFirstChoiceStaysGood) {
  for (const char* file : {"bennett-linkage.json", "planar-four-bar.json", "screw-jack.json", "spatial-slider-crank.json"}) {
    TableOptions table;
    const Motion m = RunMotion(testing_files::FromJson(testing_files::ReadJson(file)), {}, table);
    ASSERT_TRUE(m.complete) << file;
    EXPECT_TRUE(m.report.reselections.empty()) << file;
  }
}

}  // namespace
}  // namespace mechkin
