// Planar mechanisms said as such (issue "Describe mechanisms as designers do"): a
// file whose revolute axes are parallel and prismatic axes across them is planar,
// with the planar count 3n − 2j₁ − j₂ next to the spatial Grübler–Kutzbach count.
#include <gtest/gtest.h>

#include <sstream>

#include "analysis/check_report.hpp"
#include "io/check_report_writer.hpp"
#include "mobility/grubler.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace planar_test {

using nlohmann::json;
using testing_files::FromJson;
using testing_files::ReadJson;

std::optional<PlanarStructure> PlanarOf(const std::string& file) { return FindPlanarStructure(FromJson(ReadJson(file))); }

TEST(Planar, BundledPlanarFilesAndTheirCounts) {
  const auto four_bar = PlanarOf("planar-four-bar.json");
  ASSERT_TRUE(four_bar);
  EXPECT_EQ(four_bar->count, 1);  // 3·3 − 2·4
  EXPECT_EQ(four_bar->lower_pairs, 4);
  EXPECT_LT(four_bar->normal.cross(Vec3::UnitZ()).norm(), 1e-15);
  const auto slider_crank = PlanarOf("offset-slider-crank.json");  // R R R P
  ASSERT_TRUE(slider_crank);
  EXPECT_EQ(slider_crank->count, 1);
  const auto five_bar = PlanarOf("five-bar.json");
  ASSERT_TRUE(five_bar);
  EXPECT_EQ(five_bar->count, 2);  // 3·4 − 2·5
  const auto table = PlanarOf("planar-xy-table.json");  // one planar joint: nothing removed in the plane
  ASSERT_TRUE(table);
  EXPECT_EQ(table->count, 3);
  EXPECT_EQ(table->planar_joints, 1);
}

TEST(Planar, SpatialFilesAreNot) {
  for (const char* file : {"rssr-function-generator.json", "spatial-four-bar-rusr.json", "r-ss-r-distance-link.json",
                           "cylindrical-spindle.json", "bennett-linkage.json", "screw-jack.json", "spatial-slider-crank.json", "stewart-platform.json",
                           "hooke-joint-30deg.json"})
    EXPECT_FALSE(PlanarOf(file)) << file;
}

// One revolute axis tilted by 1e-6 rad makes the four-bar spatial; the same four-bar
// turned as a whole into the plane normal to (1, 2, 2)/3 stays planar with that normal.
TEST(Planar, AxesDecideAndThePlaneMayBeAnyPlane) {
  json tilted = ReadJson("planar-four-bar.json");
  tilted["joints"][2]["axis"] = {0, 1e-6, 1};
  EXPECT_FALSE(FindPlanarStructure(FromJson(tilted)));

  const Vec3 n = Vec3(1, 2, 2) / 3;
  const Mat3 R = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), n).toRotationMatrix();
  json turned = ReadJson("planar-four-bar.json");
  auto turn = [&](json& v) {
    const Vec3 x = R * Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    v = {x.x(), x.y(), x.z()};
  };
  for (auto& b : turned["bodies"]) turn(b["position"]);
  for (auto& j : turned["joints"]) turn(j["origin"]), turn(j["axis"]);
  for (auto& o : turned["outputs"])
    if (o.contains("point")) turn(o["point"]);
  const auto p = FindPlanarStructure(FromJson(turned));
  ASSERT_TRUE(p);
  EXPECT_LT(p->normal.cross(n).norm(), 1e-12);
  EXPECT_EQ(p->count, 1);
}

// A distance link is one equation in the plane (j₂): crank and rocker joined by a
// 120 mm link, 3·2 − 2·2 − 1 = 1. A cylindrical joint (even along the normal: its
// slide leaves the plane) or a spherical one makes the four-bar spatial.
TEST(Planar, DistanceLinksCountAndCylindricalOrSphericalJointsDoNot) {
  json doc = ReadJson("planar-four-bar.json");
  doc["joints"][0]["type"] = "cylindrical";
  EXPECT_FALSE(FindPlanarStructure(FromJson(doc)));
  doc["joints"][0]["type"] = "revolute";
  ASSERT_TRUE(FindPlanarStructure(FromJson(doc)));

  json link = ReadJson("planar-four-bar.json");
  link["bodies"].erase(1);
  link["joints"] = {link["joints"][0], link["joints"][3],
                    {{"name", "link"}, {"type", "distance"}, {"body1", "crank"}, {"body2", "rocker"},
                     {"point1", link["joints"][1]["origin"]}, {"point2", link["joints"][2]["origin"]}}};
  link["outputs"] = json::array();
  link.erase("expect");
  const auto with_link = FindPlanarStructure(FromJson(link));
  ASSERT_TRUE(with_link);
  EXPECT_EQ(with_link->higher_pairs, 1);
  EXPECT_EQ(with_link->count, 1);

  doc["joints"][1]["type"] = "spherical";
  doc["joints"][1].erase("axis");
  EXPECT_FALSE(FindPlanarStructure(FromJson(doc)));
}

// The check report: "planar" with the planar count next to the spatial one (text and
// JSON); a spatial file's report has neither.
TEST(Planar, CheckReportSaysPlanarOnlyForPlanarFiles) {
  const std::string dir = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/";
  const CheckReport planar = CheckFile(dir + "planar-four-bar.json");
  ASSERT_TRUE(planar.planar);
  const json pj = CheckReportJson(planar);
  EXPECT_EQ(pj["grubler"], -2);
  EXPECT_EQ(pj["planar"]["grubler"], 1);
  EXPECT_EQ(pj["planar"]["dof_after_drivers_count"], 0);
  EXPECT_EQ(pj["planar"]["lower_pairs"], 4);
  EXPECT_EQ(pj["planar"]["higher_pairs"], 0);
  EXPECT_EQ(pj["planar"]["normal"], json({0.0, 0.0, 1.0}));
  std::ostringstream text;
  PrintCheckReport(planar, text);
  EXPECT_NE(text.str().find("  Grübler–Kutzbach count: -2 (after drivers: -3)\n  planar: every body moves parallel to "
                            "the plane normal to [0, 0, 1]; planar count 3n − 2j₁ − j₂ = 1 (after drivers: 0)\n"),
            std::string::npos)
      << text.str();

  const CheckReport spatial = CheckFile(dir + "rssr-function-generator.json");
  EXPECT_FALSE(spatial.planar);
  EXPECT_FALSE(CheckReportJson(spatial).contains("planar"));
  std::ostringstream spatial_text;
  PrintCheckReport(spatial, spatial_text);
  EXPECT_EQ(spatial_text.str().find("planar"), std::string::npos);
}

}  // namespace
}  // namespace mechkin
