// The `angle` driver (the general rotation driver, §3.9, between body vectors):
// on a revolute it equals the joint driver; off the joint manifold — a pointer on a
// universal joint steered by two angle drivers — its accelerations, jerks and the
// driver efforts' rates are checked against central differences in time of
// independent runs (velocities come from ν = f_t alone, so they check γ; the
// accelerations check η; the efforts check κ).
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace angle_driver_test {

using nlohmann::json;

Motion RunShifted(json doc, int order, double shift = 0, bool forces = false) {
  doc["analysis"]["start"] = doc["analysis"]["start"].get<double>() + shift;
  doc["analysis"]["end"] = doc["analysis"]["end"].get<double>() + shift;
  TableOptions table;
  table.order = order;
  table.forces = forces;
  AnalysisOptions options;
  options.tolerance = 1e-13;
  options.forces = forces;
  Motion m = RunMotion(testing_files::FromJson(doc), options, table);
  EXPECT_TRUE(m.complete) << m.stop.message;
  return m;
}

TEST(AngleDriver, OnARevoluteItIsTheJointDriver) {
  json joint = testing_files::PlanarFourBar(40, 120, 80, 100, 60, 72);
  json angle = joint;
  angle["drivers"][0] = {{"name", "motor"}, {"type", "angle"}, {"body1", "ground"}, {"body2", "crank"},
                         {"about", {0, 0, 1}}, {"function", "360*t"}};
  const Motion a = RunShifted(joint, 3), b = RunShifted(angle, 3);
  const int c = a.layout().Find("rocker_angle");
  for (int r = 0; r < a.rows(); ++r)
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(a.at(r, c + k), b.at(r, c + k), 1e-8 * (1 + std::abs(a.at(r, c + k))));
}

json Pointer() {
  return {{"mechkin", 1}, {"units", {{"length", "mm"}, {"angle", "deg"}}},
          {"bodies", {{{"name", "pointer"}, {"position", {0, 0, 50}},
                       {"inertia", {{"mass", 2}, {"center", {0, 0, 50}},
                                    {"moments", {{300, 0, 0}, {0, 400, 0}, {0, 0, 100}}}}}}}},
          {"gravity", {0, 0, -9810}},
          {"joints", {{{"name", "cross"}, {"type", "universal"}, {"body1", "ground"}, {"body2", "pointer"},
                       {"origin", {0, 0, 0}}, {"axis1", {1, 0, 0}}, {"axis2", {0, 1, 0}}}}},
          {"drivers", {{{"name", "tilt"}, {"type", "angle"}, {"body1", "ground"}, {"body2", "pointer"},
                        {"about", {1, 0, 0}}, {"vector", {0, 1, 0}}, {"function", "30*sin(2*pi*t)"}},
                       {{"name", "swing"}, {"type", "angle"}, {"body1", "ground"}, {"body2", "pointer"},
                        {"about", {0, 1, 0}}, {"vector", {0, 0, 1}}, {"function", "25*sin(2*pi*t + 1)"}}}},
          {"analysis", {{"start", 0}, {"end", 1}, {"steps", 20}}},
          {"outputs", {{{"name", "tip"}, {"type", "point"}, {"body", "pointer"}, {"point", {0, 0, 100}}}}}};
}

TEST(AngleDriver, OffTheJointManifoldDerivativesMatchDifferences) {
  const json doc = Pointer();
  const double h = 1e-4;
  const Motion m = RunShifted(doc, 3, 0, true), plus = RunShifted(doc, 3, h, true), minus = RunShifted(doc, 3, -h, true);
  const int x = m.layout().Find("tip.x");
  const int effort = m.layout().Find("swing.effort");
  ASSERT_GE(effort, 0);
  double scale[3] = {0, 0, 0}, effort_scale = 0;
  for (int r = 0; r < m.rows(); ++r) {
    for (int a = 0; a < 3; ++a)
      for (int k = 1; k <= 3; ++k) scale[k - 1] = std::max(scale[k - 1], std::abs(m.at(r, x + 4 * a + k)));
    effort_scale = std::max(effort_scale, std::abs(m.at(r, effort + 1)));
  }
  for (int r = 0; r < m.rows(); ++r) {
    for (int a = 0; a < 3; ++a)
      for (int k = 2; k <= 3; ++k) {  // acceleration and jerk from the order below
        const int col = x + 4 * a + k;
        const double fd = (plus.at(r, col - 1) - minus.at(r, col - 1)) / (2 * h);
        EXPECT_NEAR(m.at(r, col), fd, 1e-6 * scale[k - 1]) << "row " << r << " axis " << a << " order " << k;
      }
    const double fd = (plus.at(r, effort) - minus.at(r, effort)) / (2 * h);
    EXPECT_NEAR(m.at(r, effort + 1), fd, 1e-6 * effort_scale) << "effort rate, row " << r;
  }
  EXPECT_GT(scale[1], 1.0);  // it moves
}

TEST(AngleDriver, BadDefinitionsAreNamed) {
  json doc = Pointer();
  doc["drivers"][0]["vector"] = {1, 0, 0};
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors[0].pointer, "/drivers/0/vector");
}

}  // namespace
}  // namespace mechkin
