// Parameter sensitivities (issue "Parametric designs", item 4) against the
// independent reference the acceptance names: central finite differences of
// whole runs with the parameter overridden (WithParameters = `--set`).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "analysis/motion.hpp"
#include "analysis/load.hpp"

namespace mechkin {
namespace sensitivity_test {

Model Load(const std::string& relative, const ParameterOverrides& set = {}) {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/" + relative, set);
  EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  return std::move(*r.model);
}

Motion RunWith(const Model& model, int order, std::vector<std::string> sensitivity = {}) {
  TableOptions table;
  table.order = order;
  table.sensitivity = std::move(sensitivity);
  AnalysisOptions options;
  options.tolerance = 1e-13;  // the reference runs: round-off level, so the differences measure the slope
  Motion m = RunMotion(model, options, table);
  EXPECT_TRUE(m.complete) << m.stop.message;
  return m;
}

// Every sensitivity column at every row vs [run(p + h) − run(p − h)] / 2h,
// relative to the column's largest magnitude over the motion (acceptance: 1e-6).
// Compared: every body and output column to the acceleration.
double WorstMismatch(const std::string& file, const std::string& parameter, double relative_h, int order) {
  const Model model = Load(file);
  const double p = model.FindParameter(parameter)->value;
  const double h = relative_h * std::abs(p);
  const Motion with = RunWith(model, order, {parameter});
  const Motion plus = RunWith(*WithParameters(model, {{parameter, p + h}}).model, order);
  const Motion minus = RunWith(*WithParameters(model, {{parameter, p - h}}).model, order);
  // A column that is zero in exact arithmetic (a planar body's z) is compared at the
  // scale of its kind: 1e-3 of the largest sensitivity of the same unit.
  std::map<std::string, double> unit_scale;
  for (int c = 0; c < with.cols(); ++c)
    for (int r = 0; r < with.rows() && with.columns()[c].wrt >= 0; ++r)
      unit_scale[with.columns()[c].unit] = std::max(unit_scale[with.columns()[c].unit], std::abs(with.at(r, c)));
  double worst = 0;
  int compared = 0;
  for (int c = 0; c < with.cols(); ++c) {
    const ColumnDescriptor& col = with.columns()[c];
    if (col.wrt < 0) continue;
    const int base = plus.layout().Find(with.columns()[col.base].name);
    double scale = 1e-3 * unit_scale[col.unit];
    for (int r = 0; r < with.rows(); ++r) scale = std::max(scale, std::abs(with.at(r, c)));
    for (int r = 0; r < with.rows(); ++r) {
      const double fd = (plus.at(r, base) - minus.at(r, base)) / (2 * h);
      const double mismatch = std::abs(with.at(r, c) - fd) / scale;
      if (mismatch > 1e-6)
        ADD_FAILURE() << col.name << " row " << r << ": " << with.at(r, c) << " vs " << fd << " (scale " << scale << ")";
      worst = std::max(worst, mismatch);
      ++compared;
    }
  }
  EXPECT_GT(compared, 100);
  // The README's figure: --gtest_output=xml shows worst_<parameter> per test.
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", worst);
  ::testing::Test::RecordProperty("worst_" + parameter, text);
  return worst;
}

TEST(Sensitivity, SliderCrankMatchesWholeRunDifferences) {
  for (const char* p : {"crank", "rod", "offset"})
    EXPECT_LT(WorstMismatch("mechanisms/parametric-slider-crank.json", p, 1e-4, 2), 1e-6) << p;
}

TEST(Sensitivity, FourBarMatchesWholeRunDifferences) {
  for (const char* p : {"a", "b", "c", "d"})
    EXPECT_LT(WorstMismatch("mechanisms/parametric-four-bar.json", p, 1e-4, 2), 1e-6) << p;
}

TEST(Sensitivity, SpatialRssrMatchesWholeRunDifferences) {
  for (const char* p : {"crank", "coupler", "pivot_z"})
    EXPECT_LT(WorstMismatch("tests/data/parametric-rssr.json", p, 1e-4, 2), 1e-6) << p;
}

// The closed form of the offset slider-crank's piston, x = c cos θ + √(L² − (e − c sin θ)²):
// ∂x/∂c, ∂x/∂L, ∂x/∂e at every row.
TEST(Sensitivity, SliderCrankPistonClosedForm) {
  const Model model = Load("mechanisms/parametric-slider-crank.json");
  const Motion m = RunWith(model, 1, {"crank", "rod", "offset"});
  const double c = 40, L = 120, e = 10;
  const int t_col = 0;
  const int dc = m.layout().Find("piston.x/d(crank)"), dl = m.layout().Find("piston.x/d(rod)"),
            de = m.layout().Find("piston.x/d(offset)");
  ASSERT_GE(dc, 0);
  for (int r = 0; r < m.rows(); ++r) {
    const double th = (30 + 360 * m.at(r, t_col)) * M_PI / 180;
    const double root = std::sqrt(L * L - (e - c * std::sin(th)) * (e - c * std::sin(th)));
    EXPECT_NEAR(m.at(r, dc), std::cos(th) + (e - c * std::sin(th)) * std::sin(th) / root, 1e-9);
    EXPECT_NEAR(m.at(r, dl), L / root, 1e-9);
    EXPECT_NEAR(m.at(r, de), -(e - c * std::sin(th)) / root, 1e-9);
  }
}

TEST(Sensitivity, UnknownParameterIsRefused) {
  const Model model = Load("mechanisms/parametric-slider-crank.json");
  TableOptions table;
  table.sensitivity = {"crnk"};
  const Motion m = RunMotion(model, AnalysisOptions{}, table);
  EXPECT_FALSE(m.complete);
  EXPECT_NE(m.stop.message.find("no parameter 'crnk'"), std::string::npos) << m.stop.message;
}

}  // namespace
}  // namespace mechkin
