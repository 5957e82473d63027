// Numerical behaviour at the extremes: scale, long runs, high rates, orientation
// extremes. Each case asserts numbers against a closed form or an exact invariant.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "analysis/kinematic_analysis.hpp"
#include "analysis/load.hpp"
#include "../test_files.hpp"
#include "analysis/motion.hpp"

namespace mechkin {
namespace extremes_test {

using testing_files::ReadJson;
using testing_files::FromJson;

using Columns = std::map<std::string, std::vector<double>>;

// Solver settings of one derivative order (named fields, not positional).
AnalysisOptions OrderOptions(int order) {
  AnalysisOptions o;
  o.order = order;
  return o;
}

Columns RunColumns(const Model& m, AnalysisReport* rep, int order = 3) {
  TableOptions topt;
  topt.order = order;
  topt.si = true;
  MotionRecorder table(m, topt);
  *rep = RunKinematicAnalysis(m, OrderOptions(order), [&](const SystemState& s, const StepDiagnostics& d) {
    return table.Record(s, d);
  });
  Columns c;
  for (size_t k = 0; k < testing_files::HeaderOf(table.motion()).size(); ++k) {
    const std::string name = testing_files::HeaderOf(table.motion())[k].substr(0, testing_files::HeaderOf(table.motion())[k].find(" ["));
    for (const auto& r : testing_files::RowsOf(table.motion())) c[name].push_back(r[k]);
  }
  return c;
}

// Multiplies every length of a format-v1 document by `s` (units: m).
void ScaleLengths(nlohmann::json& j, double s) {
  auto scale3 = [&](nlohmann::json& v) { for (auto& x : v) x = x.get<double>() * s; };
  j["units"]["length"] = "m";
  for (auto& b : j["bodies"]) scale3(b["position"]);
  for (auto& jt : j["joints"]) {
    for (const char* k : {"origin", "point1", "point2"}) if (jt.contains(k)) scale3(jt[k]);
  }
  for (auto& o : j["outputs"]) for (const char* k : {"point", "point1", "point2"}) if (o.contains(k)) scale3(o[k]);
}

// The four-bar at 1e-6 m, 1 m and 1e6 m: lengths and their derivatives scale
// exactly with the size, angles do not change (relative 1e-9, every order).
TEST(Extremes, ScaleInvariance) {
  const nlohmann::json base = ReadJson("planar-four-bar.json");
  // The file is in mm: 1e-3 turns it into metres, then the factor.
  Columns ref;
  for (double size : {1.0, 1e-6, 1e6}) {
    nlohmann::json j = base;
    ScaleLengths(j, 1e-3 * size);
    AnalysisReport rep;
    const Columns c = RunColumns(FromJson(j), &rep, 4);
    ASSERT_TRUE(rep.complete) << size << ": " << rep.message;
    if (size == 1.0) { ref = c; continue; }
    for (const auto& [name, values] : ref) {
      if (name == "newton_iterations" || name == "residual" || name == "t" || name == "condition" ||
          name.rfind("error_bound", 0) == 0)
        continue;
      const bool angular = name.find(".w") != std::string::npos || name.find(".e") != std::string::npos ||
                           name.find("rocker_angle") != std::string::npos;
      const double f = angular ? 1.0 : size;
      double scale = 0, err = 0;
      for (size_t k = 0; k < values.size(); ++k) {
        scale = std::max(scale, std::abs(values[k]));
        err = std::max(err, std::abs(c.at(name)[k] / f - values[k]));
      }
      if (scale == 0) continue;
      EXPECT_LT(err / scale, 1e-9) << "size " << size << " column " << name;
    }
  }
}

// A crank driven for 10,000 revolutions: no drift. After the last revolution the
// rocker is back at its closed-form start angle (0 from design), the crank angle
// reads 20,000π continuously and the Euler parameters are unit to 1e-14.
TEST(Extremes, TenThousandRevolutions) {
  nlohmann::json j = ReadJson("planar-four-bar.json");
  j["analysis"] = {{"start", 0}, {"end", 10000}, {"steps", 240000}};  // 24 steps per revolution
  j["outputs"].push_back({{"name", "crank_angle"}, {"type", "joint"}, {"joint", "A"}});
  const Model m = FromJson(j);
  TableOptions topt;
  topt.order = 1;
  topt.si = true;
  topt.all_bodies = false;
  topt.bodies = {};
  MotionRecorder table(m, topt);
  double worst_norm = 0;
  std::vector<double> last;
  const AnalysisReport rep = RunKinematicAnalysis(m, OrderOptions(1), [&](const SystemState& s, const StepDiagnostics& d) {
    for (const auto& b : s.bodies) worst_norm = std::max(worst_norm, std::abs(b.p.norm() - 1));
    return table.Record(s, d);
  });
  ASSERT_TRUE(rep.complete) << rep.message;
  const auto& rows = testing_files::RowsOf(table.motion());
  const auto& h = testing_files::HeaderOf(table.motion());
  auto col = [&](const std::string& prefix) {
    for (size_t k = 0; k < h.size(); ++k) if (h[k].rfind(prefix + " [", 0) == 0) return k;
    return h.size();
  };
  EXPECT_NEAR(rows.back()[col("crank_angle")], 20000 * M_PI, 1e-9 * 20000 * M_PI);
  EXPECT_NEAR(rows.back()[col("rocker_angle")], 0.0, 1e-9);
  EXPECT_LT(worst_norm, 1e-14);
}

// A driver at 10,000 rev/s: velocity, acceleration and jerk scale as ω, ω², ω³
// exactly against the same motion at 1 rev/s.
TEST(Extremes, HighRates) {
  nlohmann::json slow = ReadJson("spatial-slider-crank.json");
  slow["analysis"] = {{"start", 0}, {"end", 1}, {"steps", 90}};
  nlohmann::json fast = slow;
  const double w = 10000;
  fast["drivers"][0]["function"] = "3600000*t";
  fast["analysis"] = {{"start", 0}, {"end", 1 / w}, {"steps", 90}};
  AnalysisReport r1, r2;
  const Columns a = RunColumns(FromJson(slow), &r1, 3), b = RunColumns(FromJson(fast), &r2, 3);
  ASSERT_TRUE(r1.complete && r2.complete);
  for (const char* base : {"piston.x", "rod.y", "crank_angle"}) {
    for (int k = 0; k <= 3; ++k) {
      const std::string name = std::string(base) + (k == 0 ? "" : k == 1 ? "_t" : k == 2 ? "_tt" : "_ttt");
      const double f = std::pow(w, k);
      double scale = 0, err = 0;
      for (size_t i = 0; i < a.at(name).size(); ++i) {
        scale = std::max(scale, std::abs(a.at(name)[i]));
        err = std::max(err, std::abs(b.at(name)[i] / f - a.at(name)[i]));
      }
      if (scale == 0) EXPECT_EQ(err, 0.0) << name;  // e.g. the constant-speed crank's jerk
      else EXPECT_LT(err / scale, 1e-9) << name;
    }
  }
}

// A crank designed at exactly 180° (e0 = 0) gives the same motion as the
// identity design; and every full revolution passes e0 = 0 along the run.
TEST(Extremes, HalfTurnDesignOrientation) {
  nlohmann::json a = ReadJson("offset-slider-crank.json");
  nlohmann::json b = a;
  b["bodies"][0]["orientation"] = {{"axis", {0, 0, 1}}, {"angle", 180}};
  b["bodies"][1]["orientation"] = {{"euler_parameters", {0, 1, 0, 0}}};  // 180° about x
  AnalysisReport ra, rb;
  const Columns ca = RunColumns(FromJson(a), &ra, 3), cb = RunColumns(FromJson(b), &rb, 3);
  ASSERT_TRUE(ra.complete && rb.complete) << rb.message;
  for (const char* name : {"piston.x", "piston.x_t", "piston.x_tt", "piston.x_ttt", "stroke"}) {
    double scale = 0, err = 0;
    for (size_t i = 0; i < ca.at(name).size(); ++i) {
      scale = std::max(scale, std::abs(ca.at(name)[i]));
      err = std::max(err, std::abs(cb.at(name)[i] - ca.at(name)[i]));
    }
    EXPECT_LT(err / scale, 1e-10) << name;
  }
  // The crank body passes e0 = 0 (half a turn from the identity) during the run.
  double min_e0 = 1;
  for (double e0 : ca.at("crank.e0")) min_e0 = std::min(min_e0, std::abs(e0));
  EXPECT_LT(min_e0, 0.01);
}

// A universal joint bent to 80°: tan θ2 = cos β tan θ1 and the speed ratio
// cos β / (1 − sin²β sin²θ1) swings between 0.17 and 5.8.
TEST(Extremes, HookeJointBentTo80Degrees) {
  nlohmann::json j = ReadJson("hooke-joint-30deg.json");
  const double beta = 80 * M_PI / 180;
  const double s2[3] = {std::cos(beta), std::sin(beta), 0};
  j["bodies"][1]["position"] = {50 * s2[0], 50 * s2[1], 0};
  j["joints"][1]["axis2"] = {-std::sin(beta), std::cos(beta), 0};
  j["joints"][2]["origin"] = {100 * s2[0], 100 * s2[1], 0};
  j["joints"][2]["axis"] = {s2[0], s2[1], 0};
  j.erase("expect");
  AnalysisReport rep;
  const Columns c = RunColumns(FromJson(j), &rep, 1);
  ASSERT_TRUE(rep.complete) << rep.message;
  double ref = 0, err_angle = 0, err_ratio = 0;
  for (size_t i = 0; i < c.at("t").size(); ++i) {
    const double th1 = 2 * M_PI * c.at("t")[i];
    ref = UnwrapAngle(std::cos(beta) * std::sin(th1), std::cos(th1), ref);
    err_angle = std::max(err_angle, std::abs(c.at("output_angle")[i] - ref));
    const double ratio = std::cos(beta) / (1 - std::pow(std::sin(beta) * std::sin(th1), 2));
    err_ratio = std::max(err_ratio, std::abs(c.at("output_angle_t")[i] / (2 * M_PI) - ratio) / ratio);
  }
  EXPECT_LT(err_angle, 1e-9);
  EXPECT_LT(err_ratio, 1e-9);
}

}  // namespace
}  // namespace mechkin
