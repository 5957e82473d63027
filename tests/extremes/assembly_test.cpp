// Rough design poses and nearly singular positions (issue: numerical stability).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "analysis/kinematic_analysis.hpp"
#include "analysis/load.hpp"
#include "../test_files.hpp"
#include "analysis/motion.hpp"

namespace mechkin {
namespace assembly_test {

using testing_files::ReadTestData;
using testing_files::ReadJson;

struct Rows { AnalysisReport rep; std::vector<std::string> header; std::vector<std::vector<double>> rows; };

Rows RunSi(const nlohmann::json& j, AnalysisOptions o = {}) {
  const LoadResult r = LoadMechanismText(j.dump(), "inline");
  EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  TableOptions topt;
  topt.order = o.order;
  topt.si = true;
  MotionRecorder table(*r.model, topt);
  Rows out;
  out.rep = RunKinematicAnalysis(*r.model, o, [&](const SystemState& s, const StepDiagnostics& d) {
    return table.Record(s, d);
  });
  out.header = testing_files::HeaderOf(table.motion());
  out.rows = testing_files::RowsOf(table.motion());
  return out;
}

size_t Col(const Rows& r, const std::string& name) {
  for (size_t k = 0; k < r.header.size(); ++k)
    if (r.header[k] == name || r.header[k].rfind(name + " [", 0) == 0) return k;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

// R-SS-R with its coupler length given explicitly (105 mm) while the rocker is drawn
// rotated by δ, so that the drawn coupler is 10 % or 30 % too long. The run must
// assemble the branch connected to the drawing: the rocker turns back by −δ.
TEST(RoughStart, AssemblesTheBranchConnectedToTheDesign) {
  const double a = 30, c = 80, b = 105;
  const double D[3] = {40, 20, 40};
  const double th = 40 * M_PI / 180;
  const double B[3] = {a * std::cos(th), a * std::sin(th), 0};
  auto rocker = [&](double phi) {
    return std::array<double, 3>{D[0], D[1] + c * std::cos(phi), D[2] + c * std::sin(phi)};
  };
  auto dist = [&](double phi) {
    const auto C = rocker(phi);
    return std::sqrt(std::pow(C[0] - B[0], 2) + std::pow(C[1] - B[1], 2) + std::pow(C[2] - B[2], 2));
  };
  // The two closures |C − B| = b and the one the bundled file draws.
  const double K1 = 2 * c * (D[1] - B[1]), K2 = 2 * c * (D[2] - B[2]);
  const double K0 = b * b - (std::pow(D[0] - B[0], 2) + std::pow(D[1] - B[1], 2) + std::pow(D[2] - B[2], 2)) - c * c;
  const double phi_true = std::atan2(K2, K1) + std::acos(K0 / std::hypot(K1, K2));
  const double phi_other = std::atan2(K2, K1) - std::acos(K0 / std::hypot(K1, K2));
  for (double off : {0.10, 0.30}) {
    // δ > 0 (away from the other branch) with |C(φ+δ) − B| = (1 + off) b.
    double lo = 0, hi = 0.5 * std::remainder(phi_true - phi_other, 2 * M_PI) > 0 ? 2.5 : -2.5;
    const double sgn = hi > 0 ? 1 : -1;
    hi = sgn * 2.5;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (std::abs(dist(phi_true + mid) - b) < off * b ? lo : hi) = mid;
    }
    const double delta = lo;
    ASSERT_NEAR(std::abs(dist(phi_true + delta) - b), off * b, 1e-6);
    nlohmann::json j = ReadJson("r-ss-r-distance-link.json");
    const auto C = rocker(phi_true + delta);
    j["joints"][1]["point2"] = {C[0], C[1], C[2]};
    j["joints"][1]["length"] = b;
    j["bodies"][1]["position"] = {(C[0] + D[0]) / 2, (C[1] + D[1]) / 2, (C[2] + D[2]) / 2};
    j.erase("expect");
    j["analysis"] = {{"start", 0}, {"end", 0.1}, {"steps", 10}};
    const Rows r = RunSi(j);
    ASSERT_TRUE(r.rep.complete) << r.rep.message;
    // output_angle is measured from the drawn rocker: the assembled one is at −δ.
    EXPECT_NEAR(r.rows[0][Col(r, "output_angle")], -delta, 1e-9) << "off " << off;
  }
}

// A design that cannot close (coupler 10 mm, far too short) is rejected, naming
// the joints that cannot close and by how much.
TEST(RoughStart, ImpossibleDesignIsRejectedWithTheMisfit) {
  nlohmann::json j = ReadJson("r-ss-r-distance-link.json");
  j["joints"][1]["length"] = 10;
  const Rows r = RunSi(j);
  EXPECT_FALSE(r.rep.complete);
  EXPECT_TRUE(r.rows.empty());
  EXPECT_NE(r.rep.message.find("cannot be assembled"), std::string::npos) << r.rep.message;
  EXPECT_NE(r.rep.message.find("joint `coupler` (distance)"), std::string::npos) << r.rep.message;
  EXPECT_NE(r.rep.message.find("misses by"), std::string::npos) << r.rep.message;
}

// Slider-crank with crank = rod (20 mm), approaching its dead centre at 90° to within
// δ = 1e-3, 1e-6 and 1e-9 rad. The closed form on this branch is x = 2a cos θ. The
// condition number κ grows like 1/δ; the reported bound e_k = 8u·κ^k + κ·e_0 grows
// like κ^k (κ² through the position error), and the actual error must stay below it. Far enough from the
// singular position (δ = 1e-3) the results are also accurate in absolute terms.
TEST(NearSingular, DeadCentreApproachStaysWithinTheBound) {
  const double a = 0.020;
  for (double delta : {1e-3, 1e-6, 1e-9}) {
    const double theta_end = M_PI / 2 - delta, w = 2 * M_PI;
    nlohmann::json j = ReadTestData("slider-crank-equal-links.json");
    j["analysis"] = {{"start", 0}, {"end", theta_end / w}, {"steps", 45}};
    AnalysisOptions o;
    o.order = 2;
    o.tolerance = 1e-13;
    const Rows r = RunSi(j, o);
    ASSERT_TRUE(r.rep.complete) << "delta " << delta << ": " << r.rep.message;
    const auto& last = r.rows.back();
    const double th = theta_end;
    const double want[3] = {2 * a * std::cos(th), -2 * a * w * std::sin(th), -2 * a * w * w * std::cos(th)};
    const double scale[3] = {2 * a, 2 * a * w, 2 * a * w * w};  // magnitudes of x, ẋ, ẍ over the motion
    const char* names[3] = {"slider.x", "slider.x_t", "slider.x_tt"};
    const char* bounds[3] = {"error_bound", "error_bound_t", "error_bound_tt"};
    const double kappa = last[Col(r, "condition")];
    EXPECT_GT(kappa, 0.01 / delta) << "the condition estimate must see the singularity coming";
    for (int k = 0; k < 3; ++k) {
      const double err = std::abs(last[Col(r, names[k])] - want[k]) / scale[k];
      EXPECT_LE(err, last[Col(r, bounds[k])] + 1e-15) << "delta " << delta << " order " << k;
      // Far enough away the results are accurate in absolute terms: at κ ≈ 1e4 the
      // round-off floor of order k is 8u·κ^k (9e-8 for the acceleration).
      if (delta == 1e-3) {
        EXPECT_LT(err, k < 2 ? 1e-10 : 5e-8) << "order " << k;
      }
    }
  }
}

}  // namespace
}  // namespace mechkin
