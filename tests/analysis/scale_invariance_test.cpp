// The conditioning diagnostics are properties of the mechanism's shape, not of its
// size or unit (issue "Right at every order", item 3): the same mechanism drawn at
// 1e-6, 1e-3, 1, 1e3 and 1e6 times its size, or written in another length unit,
// gives the same `condition` and `error_bound` columns, and a well-conditioned
// design stays below the run's warning level (1e-4) at every order.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "analysis/motion.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace scale_invariance_test {

using nlohmann::json;

void ScaleVector(json* v, double s) {
  for (auto& x : *v) x = x.get<double>() * s;
}

// Every length of the file times s (these mechanisms have rotation drivers only).
json Scaled(json doc, double s) {
  for (auto& b : doc["bodies"]) ScaleVector(&b["position"], s);
  for (auto& j : doc["joints"]) {
    if (j.contains("origin")) ScaleVector(&j["origin"], s);
    if (j.contains("length")) j["length"] = j["length"].get<double>() * s;
  }
  for (auto& o : doc["outputs"])
    if (o.contains("point")) ScaleVector(&o["point"], s);
  return doc;
}

Motion RunDoc(const json& doc) {
  TableOptions table;
  table.order = 3;
  table.all_bodies = false;
  table.all_outputs = false;
  return RunMotion(testing_files::FromJson(doc), {}, table);
}

std::vector<double> Diagnostic(const Motion& m, const std::string& name) {
  const int c = m.layout().Find(name);
  EXPECT_GE(c, 0) << name;
  return c >= 0 ? m.Column(c) : std::vector<double>{};
}

void ExpectSameDiagnostics(const Motion& a, const Motion& b, const std::string& what) {
  ASSERT_TRUE(a.complete && b.complete) << what;
  ASSERT_EQ(a.rows(), b.rows()) << what;
  for (const char* name : {"condition", "error_bound", "error_bound_t", "error_bound_tt", "error_bound_ttt"}) {
    const std::vector<double> x = Diagnostic(a, name), y = Diagnostic(b, name);
    for (size_t r = 0; r < x.size(); ++r) EXPECT_NEAR(y[r], x[r], 1e-9 * std::abs(x[r])) << what << " " << name << " row " << r;
  }
}

TEST(ScaleInvariance, ConditionAndErrorBoundsDoNotDependOnSize) {
  for (const char* file : {"planar-four-bar.json", "spatial-slider-crank.json", "offset-slider-crank.json", "five-bar.json",
                           "bennett-linkage.json"}) {
    const json doc = testing_files::ReadJson(file);
    const Motion reference = RunDoc(doc);
    ASSERT_TRUE(reference.complete) << file;
    for (double s : {1e-6, 1e-3, 1e3, 1e6}) ExpectSameDiagnostics(reference, RunDoc(Scaled(doc, s)), file + std::string(" ×") + std::to_string(s));
    // Well conditioned: no order's bound reaches the warning level.
    for (const char* name : {"error_bound", "error_bound_t", "error_bound_tt", "error_bound_ttt"})
      for (double v : Diagnostic(reference, name)) EXPECT_LT(v, 1e-4) << file << " " << name;
  }
}

TEST(ScaleInvariance, TheLengthUnitDoesNotChangeTheDiagnostics) {
  // The planar four-bar's numbers read as m, mm, cm and in: four sizes of one shape.
  json doc = testing_files::ReadJson("planar-four-bar.json");
  const Motion reference = RunDoc(doc);
  for (const char* unit : {"m", "cm", "in"}) {
    doc["units"]["length"] = unit;
    ExpectSameDiagnostics(reference, RunDoc(doc), std::string("unit ") + unit);
  }
}

}  // namespace
}  // namespace mechkin
