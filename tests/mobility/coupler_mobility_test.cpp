// Couplers in the mobility analysis (constraints.md §3.11, §6): one freedom each in
// the Grübler count and the rank; a coupler the linkage already imposes is named as
// redundant, one that contradicts a driver is named next to the conflicting driver.
#include <gtest/gtest.h>

#include "analysis/check_report.hpp"
#include "mobility/grubler.hpp"
#include "mobility/mobility.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace coupler_mobility_test {

using nlohmann::json;
using testing_files::FromJson;
using testing_files::ReadJson;

json Revolute(const std::string& name, const std::string& b1, const std::string& b2, std::vector<double> at) {
  return {{"name", name}, {"type", "revolute"}, {"body1", b1}, {"body2", b2}, {"origin", at}, {"axis", {0, 0, 1}}};
}

// Two cranks on ground (pivots 100 mm apart, both 40 mm, drawn at 60°) tied by a
// coupler rod: a parallelogram, which already turns them alike. Optionally a gear of
// ratio 1 between the two cranks.
json Parallelogram(bool with_gear) {
  const double c = 40 * std::cos(M_PI / 3), s = 40 * std::sin(M_PI / 3);
  json j = {{"mechkin", 1}, {"units", {{"length", "mm"}, {"angle", "deg"}}},
            {"bodies", {{{"name", "left"}, {"position", {0, 0, 0}}}, {{"name", "right"}, {"position", {100, 0, 0}}}}},
            {"joints", {Revolute("A", "ground", "left", {0, 0, 0}), Revolute("D", "ground", "right", {100, 0, 0}),
                        {{"name", "rod"}, {"type", "distance"}, {"body1", "left"}, {"body2", "right"},
                         {"point1", {c, s, 0}}, {"point2", {100 + c, s, 0}}}}},
            {"drivers", {{{"name", "motor"}, {"type", "rotation"}, {"joint", "A"}, {"function", "30*t"}}}}};
  if (with_gear) j["couplers"] = {{{"name", "sync"}, {"type", "gear"}, {"joint1", "A"}, {"joint2", "D"}, {"ratio", 1}}};
  return j;
}

TEST(CouplerMobility, EachCouplerRemovesOneFreedomInTheCount) {
  const Model without = FromJson(Parallelogram(false)), with = FromJson(Parallelogram(true));
  EXPECT_EQ(CalcGrublerCount(without), 12 - 10 - 1);
  EXPECT_EQ(CalcGrublerCount(with), 12 - 10 - 1 - 1);
  const auto planar = FindPlanarStructure(with);
  ASSERT_TRUE(planar.has_value());
  EXPECT_EQ(planar->couplers, 1);
  EXPECT_EQ(planar->count, 6 - 4 - 1 - 1);
}

TEST(CouplerMobility, GearClosingALoopTheLinkageClosesIsRedundant) {
  const MobilityReport rep = CalcMobility(FromJson(Parallelogram(true)));
  ASSERT_TRUE(rep.assembled) << rep.assembly_message;
  EXPECT_EQ(rep.mobility, 1);
  EXPECT_EQ(rep.redundant, 1);
  ASSERT_EQ(rep.redundant_equations.size(), 1u);
  EXPECT_EQ(rep.redundant_equations[0].description, "coupler `sync` (gear): coordinates coupled by the gear");
  EXPECT_EQ(rep.driving_status, DrivingStatus::Full);
  // Without the gear nothing is redundant: the count and the rank agree.
  const MobilityReport plain = CalcMobility(FromJson(Parallelogram(false)));
  EXPECT_EQ(plain.redundant, 0);
  EXPECT_EQ(plain.mobility, 1);
}

// Two gears on ground, meshed (ratio −2), each driven: the second driver contradicts
// the mesh; both are named.
TEST(CouplerMobility, GearContradictingADriverIsNamed) {
  json j = {{"mechkin", 1}, {"units", {{"length", "mm"}, {"angle", "deg"}}},
            {"bodies", {{{"name", "pinion"}, {"position", {0, 0, 0}}}, {{"name", "wheel"}, {"position", {60, 0, 0}}}}},
            {"joints", {Revolute("P", "ground", "pinion", {0, 0, 0}), Revolute("W", "ground", "wheel", {60, 0, 0})}},
            {"couplers", {{{"name", "mesh"}, {"type", "gear"}, {"joint1", "P"}, {"joint2", "W"}, {"ratio", -2}}}},
            {"drivers", {{{"name", "motor"}, {"type", "rotation"}, {"joint", "P"}, {"function", "30*t"}},
                         {{"name", "brake"}, {"type", "rotation"}, {"joint", "W"}, {"function", "10*t"}}}}};
  const MobilityReport rep = CalcMobility(FromJson(j));
  ASSERT_TRUE(rep.assembled);
  EXPECT_EQ(rep.mobility, 1);
  EXPECT_EQ(rep.driving_status, DrivingStatus::Over);
  EXPECT_EQ(rep.conflicting_drivers, std::vector<std::string>{"brake"});
  EXPECT_EQ(rep.conflicting_couplers, std::vector<std::string>{"mesh"});
  // One driver is enough: full, nothing named.
  j["drivers"].erase(1);
  const MobilityReport one = CalcMobility(FromJson(j));
  EXPECT_EQ(one.driving_status, DrivingStatus::Full);
  EXPECT_TRUE(one.conflicting_couplers.empty());
}

// The planetary train: 6 bodies, 6 revolutes, 6 meshes; the second and third
// planets' ring meshes repeat the Willis relation and are the redundant rows.
TEST(CouplerMobility, PlanetaryTrainCountsAndRedundantMeshes) {
  const Model m = FromJson(ReadJson("planetary-gear-train.json"));
  EXPECT_EQ(CalcGrublerCount(m), 36 - 30 - 6);
  const MobilityReport rep = CalcMobility(m);
  EXPECT_EQ(rep.mobility, 2);
  EXPECT_EQ(rep.redundant, 2);
  ASSERT_EQ(rep.redundant_equations.size(), 2u);
  EXPECT_EQ(rep.redundant_equations[0].description, "coupler `ring_mesh2` (coupling): joint coordinates coupled");
  EXPECT_EQ(rep.redundant_equations[1].description, "coupler `ring_mesh3` (coupling): joint coordinates coupled");
  EXPECT_EQ(rep.driving_status, DrivingStatus::Full);
  const CheckReport check = CheckFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/planetary-gear-train.json");
  EXPECT_EQ(check.couplers, 6);
  EXPECT_EQ(check.grubler, 0);
  for (const auto& e : check.expectations) EXPECT_TRUE(e.held) << e.key;
}

}  // namespace
}  // namespace mechkin
