// Rank-based mobility (constraints.md §6) on mechanisms with known answers.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "analysis/kinematic_analysis.hpp"
#include "mobility/grubler.hpp"
#include "io/check_report_writer.hpp"
#include "mobility/mobility.hpp"
#include "analysis/load.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace mobility_test {

using testing_files::ReadTestData;
using testing_files::ReadJson;
using testing_files::FromJson;

Model Load(const std::string& name) {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/" + name);
  EXPECT_TRUE(r.ok()) << name;
  return std::move(*r.model);
}

struct Expected { const char* file; int grubler, mobility, redundant, idle; };

TEST(Mobility, KnownMechanisms) {
  for (const Expected& e : {Expected{"bennett-linkage.json", -2, 1, 3, 0}, Expected{"planar-four-bar.json", -2, 1, 3, 0},
                            Expected{"bricard-mechanism.json", 0, 1, 1, 0}, Expected{"rssr-function-generator.json", 2, 2, 0, 1},
                            Expected{"r-ss-r-distance-link.json", 1, 1, 0, 0}, Expected{"spatial-slider-crank.json", 1, 1, 0, 0},
                            Expected{"stewart-platform-sps-legs.json", 12, 12, 0, 6}, Expected{"screw-jack.json", -3, 1, 4, 0}}) {
    const Model m = Load(e.file);
    const MobilityReport r = CalcMobility(m);
    ASSERT_TRUE(r.assembled) << e.file;
    EXPECT_EQ(CalcGrublerCount(m), e.grubler) << e.file;
    EXPECT_EQ(r.mobility, e.mobility) << e.file;
    EXPECT_EQ(r.redundant, e.redundant) << e.file;
    EXPECT_EQ(static_cast<int>(r.idle.size()), e.idle) << e.file;
    EXPECT_EQ(r.mobility, CalcGrublerCount(m) + r.redundant) << e.file;  // M = M_G + r (§6)
    // The margin separates the kept from the discarded singular values by far.
    if (r.redundant > 0) {
      EXPECT_LT(r.sigma_max_dropped, 1e-10 * r.sigma_min_kept) << e.file;
    }
  }
}

TEST(Mobility, RedundantEquationsAreNamedAndTheSuggestionHolds) {
  const MobilityReport r = CalcMobility(Load("planar-four-bar.json"));
  ASSERT_EQ(r.redundant_equations.size(), 3u);
  for (const auto& e : r.redundant_equations) {
    EXPECT_NE(e.description.find("joint `D` (revolute)"), std::string::npos) << e.description;
    EXPECT_EQ(e.fixed_by, (std::vector<std::string>{"A", "B", "C"}));
  }
  ASSERT_EQ(r.suggestions.size(), 1u);
  EXPECT_NE(r.suggestions[0].find("(verified)"), std::string::npos);
  // Apply the suggestion by hand: A cylindrical, B spherical → no redundancy, still 1.
  auto j = ReadJson("planar-four-bar.json");
  j["joints"][0]["type"] = "cylindrical";
  j["joints"][1]["type"] = "spherical";
  j["joints"][1].erase("axis");
  const MobilityReport fixed = CalcMobility(FromJson(j));
  EXPECT_EQ(fixed.redundant, 0);
  EXPECT_EQ(fixed.mobility, 1);
}

TEST(Mobility, StewartLegSpinsAreNamed) {
  const MobilityReport r = CalcMobility(Load("stewart-platform-sps-legs.json"));
  ASSERT_EQ(r.idle.size(), 6u);
  for (int k = 1; k <= 6; ++k) {
    const std::string pair = "cylinder" + std::to_string(k) + "+piston" + std::to_string(k);
    EXPECT_TRUE(std::any_of(r.idle.begin(), r.idle.end(), [&](const IdleFreedom& f) { return f.body == pair; })) << pair;
  }
  // Idle spins are freedoms a run cannot leave free (JudgeDriving): under, each named.
  EXPECT_EQ(r.driving_status, DrivingStatus::Under);
  EXPECT_EQ(r.remaining_freedoms.size(), 6u);
}

TEST(Mobility, FiveBarWithOneDriverIsUnderDriven) {
  auto j = ReadJson("five-bar.json");
  j["drivers"].erase(1);
  j.erase("expect");
  const MobilityReport r = CalcMobility(FromJson(j));
  EXPECT_EQ(r.mobility, 2);
  EXPECT_EQ(r.driving_status, DrivingStatus::Under);
  EXPECT_EQ(r.dof_after_drivers, 1);
  ASSERT_EQ(r.remaining_freedoms.size(), 1u);
  EXPECT_NE(r.remaining_freedoms[0].find("is not driven"), std::string::npos);
}

TEST(Mobility, TwoDriversOnOneJointConflict) {
  auto j = ReadJson("planar-four-bar.json");
  j["drivers"].push_back({{"name", "second"}, {"type", "rotation"}, {"joint", "A"}, {"function", "10*t"}});
  j.erase("expect");
  const MobilityReport r = CalcMobility(FromJson(j));
  EXPECT_EQ(r.driving_status, DrivingStatus::Over);
  EXPECT_EQ(r.conflicting_drivers, (std::vector<std::string>{"second"}));
  // format-v1: DOF after drivers = mobility − drivers = 1 − 2, negative when over-driven.
  const CheckReport cr = CheckLoaded("inline", LoadMechanismText(j.dump(), "inline"));
  EXPECT_EQ(CheckReportJson(cr)["mobility"]["dof_after_drivers"].get<int>(), -1);
}

// Slider-crank with crank = rod: the dead centre, where the slider reaches the
// crank pivot, is at crank angle 90° (cos θ* = 0 for zero offset). The run stops
// there and reports it to better than 1e-6 rad, with the higher mobility.
TEST(Mobility, DeadCentreIsLocatedAtTheClosedFormAngle) {
  const nlohmann::json j = ReadTestData("slider-crank-equal-links.json");
  const Model m = FromJson(j);
  int rows = 0;
  const AnalysisReport rep = RunKinematicAnalysis(m, AnalysisOptions{}, [&](const SystemState&, const StepDiagnostics&) { ++rows; return true; });
  ASSERT_FALSE(rep.complete);
  ASSERT_TRUE(rep.singular.has_value()) << rep.message;
  EXPECT_NEAR(rep.singular->driver_values[0], M_PI / 2, 1e-6);
  EXPECT_EQ(rep.singular->joint_mobility, 2);
  EXPECT_EQ(rows, 19);  // rows before the singular position are kept
  EXPECT_NE(rep.message.find("singular position"), std::string::npos);
}

}  // namespace
}  // namespace mechkin
