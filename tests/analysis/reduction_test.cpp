// Reductions (issue 29): min, max, rms, mean and at over a run against closed forms,
// where a min/max occurs against the closed-form time, and their gradients against
// central differences of whole runs (the variants compiled from the model's spec with
// the parameter overridden, WithParameters, never re-parsed).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

#include "analysis/load.hpp"
#include "analysis/motion.hpp"
#include "analysis/reduction.hpp"
#include "analysis/run_request.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace reduction_test {

// The bundled parametric four-bar (crank a 40, coupler b 120, rocker c 80, frame d 100
// mm; the crank at θ = 60° + 360° t, t ∈ [0, 1]) with 50 steps (h = 0.02 s: neither
// extremum falls on a row), the distance BD from the crank pin to the rocker pivot,
// the transmission angle μ from the cosine rule and the crank's joint angle, and
// reductions of them.
nlohmann::json FourBar() {
  std::ifstream f(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json");
  nlohmann::json j = nlohmann::json::parse(f);
  j["analysis"]["steps"] = 50;
  auto& o = j["outputs"];
  o.push_back({{"name", "BD"}, {"type", "distance"}, {"body1", "crank"}, {"point1", {"xb", "yb", 0}},
               {"body2", "ground"}, {"point2", {"d", 0, 0}}});
  o.push_back({{"name", "mu"}, {"type", "expression"}, {"value", "acos((b^2 + c^2 - BD^2)/(2*b*c))*180/pi"}});
  o.push_back({{"name", "crank_angle"}, {"type", "joint"}, {"joint", "A"}});
  auto red = [&](const char* name, const char* of, const char* how) {
    o.push_back({{"name", name}, {"type", "reduction"}, {"of", of}, {"reduce", how}});
  };
  red("mu_min", "mu", "min");
  red("mu_max", "mu", "max");
  red("BD_rms", "BD", "rms");
  red("crank_mean", "crank_angle", "mean");
  red("crank_rms", "crank_angle", "rms");
  red("x_max", "coupler_point.x", "max");
  o.push_back({{"name", "mu_at"}, {"type", "reduction"}, {"of", "mu"}, {"reduce", "at"}, {"t", 0.25}});
  return j;
}

const double a = 40, b = 120, c = 80, d = 100, h = 0.02;

// μ at crank angle θ (rad): BD² = a² + d² − 2ad cos θ, cos μ = (b² + c² − BD²)/(2bc).
double Mu(double theta) {
  const double bd2 = a * a + d * d - 2 * a * d * std::cos(theta);
  return std::acos((b * b + c * c - bd2) / (2 * b * c)) * 180 / M_PI;
}

std::map<std::string, ReductionResult> Reduce(const Model& m, std::vector<std::string> sensitivity = {}) {
  RunRequest req;
  req.order = 3;
  req.tolerance = 1e-13;  // round-off level, so the differences of whole runs measure the slope
  req.sensitivity = std::move(sensitivity);
  const Motion motion = RunMotion(m, req);
  EXPECT_TRUE(motion.complete) << motion.stop.message;
  std::map<std::string, ReductionResult> out;
  for (const ReductionResult& r : motion.reductions) {
    EXPECT_EQ(r.problem, "") << r.name;
    out[r.name] = r;
  }
  return out;
}

// μ grows with BD (cos μ falls as BD² rises), and BD = |A + a e^{iθ} − D| runs from
// d − a (θ = 0) to d + a (θ = 180°). So the minimum transmission angle is
// cos μ_min = (b² + c² − (d − a)²)/(2bc) at θ = 360° (t = 300/360 = 5/6 s), the
// maximum cos μ_max = (b² + c² − (d + a)²)/(2bc) at θ = 180° (t = 1/3 s): 26.38° and
// 86.42°, neither on a row (t/h = 41.67, 16.67).
TEST(Reduction, TransmissionAngleExtremaAndWhereTheyOccur) {
  const auto r = Reduce(testing_files::FromJson(FourBar()));
  const double mu_min = std::acos((b * b + c * c - (d - a) * (d - a)) / (2 * b * c)) * 180 / M_PI;
  const double mu_max = std::acos((b * b + c * c - (d + a) * (d + a)) / (2 * b * c)) * 180 / M_PI;
  // Degree-7 Hermite of the rows' jets (the table's order 3): 2.9e-9° and 4e-10 s.
  EXPECT_NEAR(r.at("mu_min").value, mu_min, 1e-8);
  EXPECT_NEAR(r.at("mu_min").t, 5.0 / 6.0, 1e-8);
  EXPECT_TRUE(r.at("mu_min").located);
  EXPECT_EQ(r.at("mu_min").unit, "");  // an expression has no unit
  EXPECT_NEAR(r.at("mu_max").value, mu_max, 1e-8);
  EXPECT_NEAR(r.at("mu_max").t, 1.0 / 3.0, 1e-8);
  // The rows alone miss the minimum by far more: the location between rows is what counts.
  EXPECT_GT(std::abs(Mu(2 * M_PI * (41 * h) + M_PI / 3) - mu_min), 1e-3);
  // "at" 0.25 s (θ = 150°), between rows 12 and 13: the Hermite of the jets to the jerk.
  EXPECT_NEAR(r.at("mu_at").value, Mu(150 * M_PI / 180), 1e-7);
  EXPECT_EQ(r.at("mu_at").t, 0.25);
}

// rms of BD over a full turn: ∫ BD² dθ/2π = a² + d² (the cosine averages out), and the
// trapezoid rule is exact for a trigonometric polynomial of degree < steps over its
// period: sqrt(a² + d²) to round-off.
TEST(Reduction, RmsOfTheCrankPinDistanceOverATurn) {
  const auto r = Reduce(testing_files::FromJson(FourBar()));
  EXPECT_NEAR(r.at("BD_rms").value, std::sqrt(a * a + d * d), 1e-9);
  EXPECT_EQ(r.at("BD_rms").unit, "mm");
}

// The crank's joint angle reads 360 t (degrees from the design pose): mean 180 exactly
// (the trapezoid rule is exact for a line); rms over [0, 1] is 360/√3 analytically,
// and the trapezoid rule on the rows gives 360 sqrt(1/3 + h²/6) (its error for t² is
// h²/6 exactly) — the docs say it is the trapezoid rule.
TEST(Reduction, MeanAndRmsOfTheCrankAngle) {
  const auto r = Reduce(testing_files::FromJson(FourBar()));
  EXPECT_NEAR(r.at("crank_mean").value, 180, 1e-9);
  EXPECT_NEAR(r.at("crank_rms").value, 360 * std::sqrt(1.0 / 3 + h * h / 6), 1e-9);
  EXPECT_NEAR(r.at("crank_rms").value, 360 / std::sqrt(3.0), 360 * h * h / 2);
  EXPECT_EQ(r.at("crank_mean").unit, "deg");
}

// Every reduction's gradient with respect to b (coupler) and d (frame) against the
// central difference of two whole runs at p ± δ, relative to the gradient's scale.
TEST(Reduction, GradientsMatchCentralDifferencesOfWholeRuns) {
  const Model m = testing_files::FromJson(FourBar());
  const auto base = Reduce(m, {"b", "d"});
  const std::vector<std::string> names = {"mu_min", "mu_max", "BD_rms", "crank_mean", "crank_rms", "x_max", "mu_at"};
  for (int p = 0; p < 2; ++p) {
    const std::string param = p ? "d" : "b";
    const double value = p ? d : b, delta = 1e-3;
    LoadResult plus = WithParameters(m, {{param, value + delta}});
    LoadResult minus = WithParameters(m, {{param, value - delta}});
    ASSERT_TRUE(plus.ok() && minus.ok());
    const auto rp = Reduce(*plus.model), rm = Reduce(*minus.model);
    for (const std::string& n : names) {
      const double fd = (rp.at(n).value - rm.at(n).value) / (2 * delta);
      const double got = base.at(n).gradient.at(p);
      // The scale of a slope: the larger of the two and the reduction over the parameter.
      const double scale = std::max({std::abs(fd), std::abs(got), std::abs(base.at(n).value) / value});
      EXPECT_NEAR(got, fd, 1e-6 * scale) << n << " d/d(" << param << ")";
    }
  }
  // Not vacuous: μ_min depends on b (dμ/db from the closed form, degrees per mm).
  const double x = (b * b + c * c - (d - a) * (d - a)) / (2 * b * c);
  const double dx_db = 1 / c - x / b;  // d/db of (b² + c² − e²)/(2bc) = 1/c − x/b
  const double dmu_db = -dx_db / std::sqrt(1 - x * x) * 180 / M_PI;
  EXPECT_NEAR(base.at("mu_min").gradient[0], dmu_db, 1e-6 * std::abs(dmu_db));
}

TEST(Reduction, HermiteReproducesAQuinticFromItsJets) {
  // p(t) = 1 − 2t + 3t² + t³ − t⁴ + 0.5 t⁵ on [0.3, 0.8]: the quintic through the jets is p.
  auto p = [](double t, int k) {
    const double c[6] = {1, -2, 3, 1, -1, 0.5};
    double v = 0;
    for (int j = k; j < 6; ++j) {
      double f = 1;
      for (int i = 0; i < k; ++i) f *= j - i;
      v += f * c[j] * std::pow(t, j - k);
    }
    return v;
  };
  const double t0 = 0.3, t1 = 0.8, d0[3] = {p(t0, 0), p(t0, 1), p(t0, 2)}, d1[3] = {p(t1, 0), p(t1, 1), p(t1, 2)};
  const std::vector<double> coef = HermiteCoefficients(d0, d1, 2, t1 - t0);
  for (double s : {0.0, 0.25, 0.6, 1.0}) EXPECT_NEAR(HermiteEval(coef, s), p(t0 + s * (t1 - t0), 0), 1e-13);
}

}  // namespace reduction_test
}  // namespace mechkin
