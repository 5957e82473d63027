// Expression outputs (issue "Design by objective", derived quantities): values and
// exact time derivatives against closed forms differentiated with the test-only jets
// (tests/constraints/test_jet.hpp), against the chain rule written out by hand over
// the other columns, the same numbers whatever the table's units or selection, and
// the parameter sensitivity against a central difference of two whole runs.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <optional>

#include "../constraints/test_jet.hpp"
#include "analysis/kinematic_analysis.hpp"
#include "analysis/load.hpp"
#include "analysis/motion.hpp"
#include "analysis/run_request.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace expression_output_test {

using testing::TJet;

// The bundled parametric four-bar (a 40, b 120, c 80, d 100 mm, crank from 60° at
// 360°/s) with the distance from the crank pin B to the rocker pivot D, the
// transmission angle from it (cosine rule), a product of two columns plus t², and an
// expression of expressions.
nlohmann::json FourBarWithExpressions() {
  std::ifstream f(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json");
  nlohmann::json j = nlohmann::json::parse(f);
  j["outputs"].push_back({{"name", "BD"}, {"type", "distance"}, {"body1", "crank"}, {"point1", {"xb", "yb", 0}},
                          {"body2", "ground"}, {"point2", {"d", 0, 0}}});
  j["outputs"].push_back({{"name", "transmission"}, {"type", "expression"},
                          {"value", "acos((b^2 + c^2 - BD^2)/(2*b*c))*180/pi"}});
  j["outputs"].push_back({{"name", "product"}, {"type", "expression"},
                          {"value", "coupler_point.x*rocker_angle/100 + t^2"}});
  j["outputs"].push_back({{"name", "nested"}, {"type", "expression"}, {"value", "2*product - transmission"}});
  return j;
}

struct Table {
  std::map<std::string, std::vector<double>> col;
  const std::vector<double>& operator[](const std::string& name) const { return col.at(name); }
};

Table RunTable(const Model& m, const TableOptions& topt) {
  MotionRecorder rec(m, topt);
  AnalysisOptions opt;
  opt.order = topt.order;
  RunKinematicAnalysis(m, opt, [&](const SystemState& s, const StepDiagnostics& d) { return rec.Record(s, d); });
  Table t;
  const Motion& motion = rec.motion();
  for (int c = 0; c < motion.cols(); ++c) t.col[motion.columns()[c].name] = motion.Column(c);
  return t;
}

TableOptions Order(int order, bool si = false) {
  TableOptions o;
  o.order = order;
  o.si = si;
  return o;
}

const char* kSuffix[] = {"", "_t", "_tt", "_ttt", "_tttt"};

TEST(ExpressionOutput, TransmissionAngleMatchesTheCosineRuleToTheSnap) {
  const Model m = testing_files::FromJson(FourBarWithExpressions());
  const Table t = RunTable(m, Order(4));
  const double a = 40, b = 120, c = 80, d = 100;
  const size_t rows = t["t"].size();
  ASSERT_EQ(rows, 73u);
  double worst[5] = {0, 0, 0, 0, 0}, scale[5] = {0, 0, 0, 0, 0};
  for (size_t r = 0; r < rows; ++r) {
    TJet th;  // the crank angle (rad) as a series in time about this row
    th.c[0] = (60 + 360 * t["t"][r]) * M_PI / 180;
    th.c[1] = 2 * M_PI;
    const TJet bd2 = TJet(a * a + d * d) - (2 * a * d) * testing::Cos(th);
    const TJet x = (TJet(b * b + c * c) - bd2) / TJet(2 * b * c);
    const TJet mu = (180 / M_PI) * testing::Angle(testing::Sqrt(TJet(1) - x * x), x);
    for (int k = 0; k <= 4; ++k) {
      worst[k] = std::max(worst[k], std::abs(t[std::string("transmission") + kSuffix[k]][r] - mu.D(k)));
      scale[k] = std::max(scale[k], std::abs(mu.D(k)));
    }
  }
  for (int k = 0; k <= 4; ++k) EXPECT_LT(worst[k], 1e-9 * scale[k]) << "order " << k;
}

TEST(ExpressionOutput, ProductFollowsLeibnizOverTheOtherColumns) {
  const Model m = testing_files::FromJson(FourBarWithExpressions());
  const Table t = RunTable(m, Order(3));
  auto x = [&](int k, size_t r) { return t[std::string("coupler_point.x") + kSuffix[k]][r]; };
  auto q = [&](int k, size_t r) { return t[std::string("rocker_angle") + kSuffix[k]][r]; };
  for (size_t r = 0; r < t["t"].size(); ++r) {
    const double tt = t["t"][r];
    const double want[4] = {
        x(0, r) * q(0, r) / 100 + tt * tt,
        (x(1, r) * q(0, r) + x(0, r) * q(1, r)) / 100 + 2 * tt,
        (x(2, r) * q(0, r) + 2 * x(1, r) * q(1, r) + x(0, r) * q(2, r)) / 100 + 2,
        (x(3, r) * q(0, r) + 3 * x(2, r) * q(1, r) + 3 * x(1, r) * q(2, r) + x(0, r) * q(3, r)) / 100};
    for (int k = 0; k <= 3; ++k) {
      const double got = t[std::string("product") + kSuffix[k]][r];
      EXPECT_NEAR(got, want[k], 1e-12 * (1 + std::abs(want[k]))) << "row " << r << " order " << k;
      const double nested = t[std::string("nested") + kSuffix[k]][r];
      EXPECT_NEAR(nested, 2 * got - t[std::string("transmission") + kSuffix[k]][r], 1e-9 * (1 + std::abs(got)));
    }
  }
}

// Through RunMotion, as the CLI and Python run: with only the expression selected the
// run solves just the bodies its inputs need (RunPlan's block selection), and reads the
// same numbers.
Table RunRequested(const Model& m, bool si, std::optional<std::vector<std::string>> outputs) {
  RunRequest req;
  req.order = 3;
  req.si = si;
  if (outputs) req.bodies = std::vector<std::string>{};
  req.outputs = outputs;
  const Motion motion = RunMotion(m, req);
  EXPECT_TRUE(motion.complete);
  Table t;
  for (int c = 0; c < motion.cols(); ++c) t.col[motion.columns()[c].name] = motion.Column(c);
  return t;
}

TEST(ExpressionOutput, SameNumbersInSiAndWithOnlyTheExpressionSelected) {
  const Model m = testing_files::FromJson(FourBarWithExpressions());
  const Table file = RunRequested(m, false, std::nullopt);
  const Table si = RunRequested(m, true, std::nullopt);
  const Table alone = RunRequested(m, false, std::vector<std::string>{"nested"});
  EXPECT_EQ(alone.col.count("transmission"), 0u);
  EXPECT_EQ(alone.col.count("crank.x"), 0u);
  for (const char* name : {"transmission", "product", "nested"})
    for (int k = 0; k <= 3; ++k) {
      const std::string col = std::string(name) + kSuffix[k];
      EXPECT_EQ(si[col], file[col]) << col;
      if (std::string(name) == "nested") {
        EXPECT_EQ(alone[col], file[col]) << col;
      }
    }
  // The SI table's own angle column is in radians, the expression read degrees.
  EXPECT_NEAR(si["rocker_angle"][5] * 180 / M_PI, file["rocker_angle"][5], 1e-9);
}

// d(transmission)/d(a) from the run's sensitivity column against (μ(a + h) − μ(a − h))/2h
// of two whole runs with the parameter set: the expression's own parameters (a, b, c
// in its text and the geometry) enter through the model compiled at a ± h.
Table RunSensitivity(const Model& m) {
  TableOptions topt = Order(2);
  topt.sensitivity = {"a"};
  MotionRecorder rec(m, topt);
  AnalysisOptions opt;
  opt.order = 2;
  opt.sensitivity_parameters = {"a"};
  RunKinematicAnalysis(m, opt, [&](const SystemState& s, const StepDiagnostics& d) { return rec.Record(s, d); });
  Table t;
  const Motion& motion = rec.motion();
  const int col = motion.layout().SensitivityOf("transmission", "a");
  EXPECT_GE(col, 0);
  if (col >= 0) t.col["d"] = motion.Column(col);
  return t;
}

TEST(ExpressionOutput, SensitivityMatchesACentralDifferenceOfTwoRuns) {
  const std::string text = FourBarWithExpressions().dump();
  const double h = 1e-3;
  LoadResult base = LoadMechanismText(text, "inline"), plus = LoadMechanismText(text, "inline", {{"a", 40 + h}}),
             minus = LoadMechanismText(text, "inline", {{"a", 40 - h}});
  ASSERT_TRUE(base.ok() && plus.ok() && minus.ok());
  const Table sens = RunSensitivity(*base.model);
  const Table p = RunTable(*plus.model, Order(2)), mi = RunTable(*minus.model, Order(2));
  ASSERT_EQ(sens["d"].size(), p["transmission"].size());
  double worst = 0, scale = 0;
  for (size_t r = 0; r < p["transmission"].size(); ++r) {
    const double fd = (p["transmission"][r] - mi["transmission"][r]) / (2 * h);
    worst = std::max(worst, std::abs(sens["d"][r] - fd));
    scale = std::max(scale, std::abs(fd));
  }
  EXPECT_GT(scale, 0.1);  // degrees per mm: the crank length moves the transmission angle
  EXPECT_LT(worst, 1e-5 * scale);
}

struct BadCase {
  const char* value;
  const char* message;
};

TEST(ExpressionOutput, BadNamesAreReportedAtTheValue) {
  const BadCase cases[] = {
      {"coupler_point*2", "output 'coupler_point' has several coordinates"},
      {"coupler_point.w", "unknown name 'coupler_point.w'"},
      {"rocker_angel + 1", "did you mean 'rocker_angle'?"},
      {"later + 1", "output 'later' comes after this expression"},
      {"rocker_angle +", "bad expression at column"},
  };
  for (const BadCase& c : cases) {
    nlohmann::json j = FourBarWithExpressions();
    j["outputs"].push_back({{"name", "bad"}, {"type", "expression"}, {"value", c.value}});
    j["outputs"].push_back({{"name", "later"}, {"type", "distance"}, {"body1", "crank"}, {"point1", {0, 0, 0}},
                            {"body2", "ground"}, {"point2", {0, 0, 0}}});
    const LoadResult r = LoadMechanismText(j.dump(), "inline");
    ASSERT_FALSE(r.ok()) << c.value;
    const std::string text = r.errors[0].ToString();
    EXPECT_NE(text.find("/outputs/6/value"), std::string::npos) << text;
    EXPECT_NE(text.find(c.message), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace mechkin
