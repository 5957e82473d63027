// Branch continuity and singular positions (issue: numerical stability).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/kinematic_analysis.hpp"
#include "analysis/load.hpp"
#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace branches_test {

// A planar 4R four-bar (mm) with the crank at theta0_deg at the design pose, upper branch.
// Closed form (upper assembly branch): rocker angle relative to its design value.
double RockerAngle(double a, double b, double c, double d, double theta) {
  const double Bx = a * std::cos(theta), By = a * std::sin(theta);
  const double dx = d - Bx, dy = -By, dist = std::hypot(dx, dy);
  const double al = (b * b - c * c + dist * dist) / (2 * dist), h = std::sqrt(b * b - al * al);
  const double Cx = Bx + (al * dx - h * dy) / dist, Cy = By + (al * dy + h * dx) / dist;
  return std::atan2(Cy, Cx - d);
}

struct RunOut { AnalysisReport rep; std::vector<double> t, rocker; };

RunOut RunRocker(const nlohmann::json& j, const AnalysisOptions& o) {
  const LoadResult r = LoadMechanismText(j.dump(), "inline");
  EXPECT_TRUE(r.ok());
  TableOptions topt;
  topt.order = o.order;
  topt.si = true;
  topt.all_bodies = false;
  MotionRecorder table(*r.model, topt);
  RunOut out;
  out.rep = RunKinematicAnalysis(*r.model, o, [&](const SystemState& s, const StepDiagnostics& d) {
    return table.Record(s, d);
  });
  for (const auto& row : testing_files::RowsOf(table.motion())) {
    out.t.push_back(row[0]);
    out.rocker.push_back(row[1]);
  }
  return out;
}

// A Grashof crank-rocker close to its change point (40/120/80/81 mm, s + l = 160 vs
// p + q = 161) driven through a revolution in 8 coarse steps. Plain Newton from the
// previous step (no predictor, no guard) lands on the other assembly branch; mechkin
// detects the jump (det Φ_q changes sign / the pose is far from the prediction),
// refines that interval into sub-steps and stays on the design branch.
TEST(Branches, CoarseStepsDoNotJumpBranch) {
  const double a = 40, b = 120, c = 80, d = 81, th0 = 60;
  const nlohmann::json j = testing_files::PlanarFourBar(a, b, c, d, th0, 8);
  auto closed = [&](double t) {
    const double phi0 = RockerAngle(a, b, c, d, th0 * M_PI / 180);
    return std::remainder(RockerAngle(a, b, c, d, (th0 + 360 * t) * M_PI / 180) - phi0, 2 * M_PI);
  };
  AnalysisOptions plain;
  plain.order = 1;
  plain.predictor_order = 0;
  plain.branch_guard = false;
  const RunOut jumped = RunRocker(j, plain);
  ASSERT_TRUE(jumped.rep.complete);
  double worst_plain = 0;
  for (size_t k = 0; k < jumped.t.size(); ++k) worst_plain = std::max(worst_plain, std::abs(jumped.rocker[k] - closed(jumped.t[k])));
  EXPECT_GT(worst_plain, 0.1) << "plain Newton was expected to jump branch here";

  for (int predictor : {0, 3}) {
    AnalysisOptions guarded;
    guarded.order = 1;
    guarded.predictor_order = predictor;
    const RunOut ok = RunRocker(j, guarded);
    ASSERT_TRUE(ok.rep.complete) << ok.rep.message;
    int refined = 0;
    for (const auto& s : ok.rep.steps) refined += s.substeps_refinements;
    EXPECT_GT(refined, 0);
    for (size_t k = 0; k < ok.t.size(); ++k) EXPECT_NEAR(ok.rocker[k], closed(ok.t[k]), 1e-9) << "t = " << ok.t[k];
  }
}

// Solver settings of one derivative order (named fields, not positional).
AnalysisOptions OrderOptions(int order) {
  AnalysisOptions o;
  o.order = order;
  return o;
}

// Grashof sum equal (40 + 100 = 80 + 60): at crank angle 0 all links are collinear,
// a change point where the branches meet. Starting at 60°, the crank reaches it
// after 300° of driver motion; the run stops there and says so.
TEST(Branches, ChangePointOfAnEqualGrashofSum) {
  const nlohmann::json j = testing_files::PlanarFourBar(40, 100, 80, 60, 60, 90);
  const RunOut out = RunRocker(j, OrderOptions(1));
  ASSERT_FALSE(out.rep.complete);
  ASSERT_TRUE(out.rep.singular.has_value()) << out.rep.message;
  EXPECT_NEAR(out.rep.singular->driver_values[0], 300 * M_PI / 180, 1e-6);
  EXPECT_GE(out.rep.singular->joint_mobility, 2);
}

}  // namespace
}  // namespace mechkin
