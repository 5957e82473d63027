// Angle outputs (issue "Say what engineers measure"): the angle between two
// body-fixed vectors, unsigned and signed about an axis, with derivatives, against
// a four-bar's transmission angle in closed form and against the joint output.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/motion.hpp"
#include "analysis/load.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace angle_output_test {

using nlohmann::json;

// Grashof crank-rocker: ground g = 100, crank a = 40, coupler b = 90, rocker c = 80 mm;
// crank angle θ = 30° + 360°·t. Transmission angle μ between coupler and rocker at C:
//   cos μ = (b² + c² − f²) / (2bc),  f² = a² + g² − 2ag cos θ.
double Transmission(double theta) {
  const double g = 100, a = 40, b = 90, c = 80;
  const double f2 = a * a + g * g - 2 * a * g * std::cos(theta);
  return std::acos((b * b + c * c - f2) / (2 * b * c));
}

TEST(AngleOutput, FourBarTransmissionAngleMatchesTheClosedForm) {
  const double g = 100, a = 40, b = 90, c = 80, th0 = M_PI / 6;
  // The joint points, as the file places them: B on the crank, C where coupler and rocker meet.
  json j = testing_files::PlanarFourBar(a, b, c, g, 30, 72);
  const auto& B = j["joints"][1]["origin"];
  const auto& C = j["joints"][2]["origin"];
  const double bx = B[0], by = B[1], cx = C[0], cy = C[1];
  j["outputs"] = {{{"name", "mu"}, {"type", "angle"}, {"body1", "coupler"}, {"vector1", {bx - cx, by - cy, 0}},
                   {"body2", "rocker"}, {"vector2", {g - cx, -cy, 0}}}};
  TableOptions table;
  table.si = true;
  table.order = 2;
  table.all_bodies = false;
  const Motion m = RunMotion(testing_files::FromJson(j), AnalysisOptions{}, table);
  ASSERT_TRUE(m.complete) << m.report.message;
  const int c0 = m.layout().Find("mu"), c1 = m.layout().Find("mu_t"), c2 = m.layout().Find("mu_tt");
  ASSERT_GE(c2, 0);
  const double w = 2 * M_PI, e = 1e-4;
  for (int r = 0; r < m.rows(); ++r) {
    const double th = th0 + w * m.at(r, 0);
    // Derivatives of the closed form by central differences in θ (error ~ e²).
    const double d1 = (Transmission(th + e) - Transmission(th - e)) / (2 * e) * w;
    const double d2 = (Transmission(th + e) - 2 * Transmission(th) + Transmission(th - e)) / (e * e) * w * w;
    EXPECT_NEAR(m.at(r, c0), Transmission(th), 1e-9) << "row " << r;
    EXPECT_NEAR(m.at(r, c1), d1, 1e-6 * w) << "row " << r;
    EXPECT_NEAR(m.at(r, c2), d2, 1e-4 * w * w) << "row " << r;
  }
}

// The crank's arm measured from the ground x axis about the bearing axis equals the
// joint output plus its design angle (0 here), over a whole turn, with derivatives.
TEST(AngleOutput, SignedAngleAboutAnAxisEqualsTheJointAngle) {
  json j = testing_files::ReadJson("spatial-slider-crank.json");
  j["outputs"].push_back({{"name", "arm"}, {"type", "angle"}, {"body1", "ground"}, {"vector1", {1, 0, 0}},
                          {"body2", "crank"}, {"vector2", {1, 0, 0}}, {"about", {0, 0, 1}}});
  TableOptions table;
  table.order = 3;
  table.all_bodies = false;
  const Motion m = RunMotion(testing_files::FromJson(j), AnalysisOptions{}, table);
  ASSERT_TRUE(m.complete);
  for (const char* s : {"", "_t", "_tt", "_ttt"}) {
    const int ca = m.layout().Find(std::string("arm") + s), cj = m.layout().Find(std::string("crank_angle") + s);
    ASSERT_GE(ca, 0);
    for (int r = 0; r < m.rows(); ++r) EXPECT_NEAR(m.at(r, ca), m.at(r, cj), 1e-9) << s << " row " << r;
  }
  EXPECT_NEAR(m.at(m.rows() - 1, m.layout().Find("arm")), 360, 1e-9);  // continuous: a whole turn, not 0
}

TEST(AngleOutput, BadAnglesNameTheirPlace) {
  json j = testing_files::ReadJson("spatial-slider-crank.json");
  j["outputs"] = {{{"name", "a"}, {"type", "angle"}, {"body1", "ground"}, {"vector1", {0, 0, 0}}, {"body2", "crank"}, {"vector2", {1, 0, 0}}},
                  {{"name", "b"}, {"type", "angle"}, {"body1", "ground"}, {"vector1", {1, 0, 0}}, {"body2", "crank"},
                   {"vector2", {0, 1, 0}}, {"about", {2, 0, 0}}},
                  {{"name", "c"}, {"type", "angel"}}};
  const LoadResult r = LoadMechanismText(j.dump(), "inline");
  ASSERT_FALSE(r.ok());
  std::vector<std::string> pointers;
  for (const auto& e : r.errors) pointers.push_back(e.pointer);
  EXPECT_NE(std::find(pointers.begin(), pointers.end(), "/outputs/0/vector1"), pointers.end());
  EXPECT_NE(std::find(pointers.begin(), pointers.end(), "/outputs/1/about"), pointers.end());
  EXPECT_NE(std::find(pointers.begin(), pointers.end(), "/outputs/2/type"), pointers.end());
}

}  // namespace
}  // namespace mechkin
