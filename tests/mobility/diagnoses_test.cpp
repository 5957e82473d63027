// Diagnoses that send the user the right way (issue "Right at every order", item 6):
// joints that lock the mechanism are named before any talk of conflicting drivers,
// and a design pose that is itself singular is called that, with the direction lost.
#include <gtest/gtest.h>

#include <glob.h>
#include <nlohmann/json.hpp>

#include "analysis/kinematic_analysis.hpp"
#include "mobility/mobility.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace diagnoses_test {

AnalysisReport RunQuietly(const Model& m) {
  return RunKinematicAnalysis(m, AnalysisOptions{}, [](const SystemState&, const StepDiagnostics&) { return true; });
}

// The planar four-bar with one axis mistyped (B about y instead of z): a spatial 4R
// loop that cannot move at all.
TEST(Diagnoses, JointsThatLockTheMechanismAreNamed) {
  nlohmann::json j = testing_files::ReadJson("planar-four-bar.json");
  j["joints"][1]["axis"] = {0, 1, 0};
  j.erase("expect");
  const Model m = testing_files::FromJson(j);
  const MobilityReport r = CalcMobility(m);
  EXPECT_EQ(r.mobility, 0);
  EXPECT_TRUE(r.locked);
  EXPECT_EQ(r.locking_joints, (std::vector<std::string>{"A", "B", "C", "D"}));
  EXPECT_NE(r.verdict.find("locked by the joints"), std::string::npos) << r.verdict;
  const AnalysisReport run = RunQuietly(m);
  EXPECT_EQ(run.stop, StopKind::Refused);
  EXPECT_NE(run.message.find("locked by the joints"), std::string::npos) << run.message;
  EXPECT_NE(run.message.find("`B`"), std::string::npos) << run.message;
  EXPECT_EQ(run.message.find("over-driven"), std::string::npos) << run.message;
}

// The same verdict from the sparse path (more than 200 bodies): 201 bodies, each held
// to ground by two revolutes at one point with crossed axes, cannot move at all.
TEST(Diagnoses, LockedLargeModelsAreCalledLockedToo) {
  nlohmann::json j = {{"mechkin", 1}, {"bodies", nlohmann::json::array()}, {"joints", nlohmann::json::array()}};
  for (int k = 0; k < 201; ++k) {
    const std::string b = "b" + std::to_string(k);
    j["bodies"].push_back({{"name", b}, {"position", {k, 1, 0}}});
    for (int axis = 0; axis < 2; ++axis)
      j["joints"].push_back({{"name", b + (axis ? "x" : "z")}, {"type", "revolute"}, {"body1", "ground"}, {"body2", b},
                             {"origin", {k, 0, 0}}, {"axis", axis ? nlohmann::json{1, 0, 0} : nlohmann::json{0, 0, 1}}});
  }
  const MobilityReport r = CalcMobility(testing_files::FromJson(j));
  EXPECT_EQ(r.rank_method, "sparse-qr");
  EXPECT_EQ(r.mobility, 0);
  EXPECT_EQ(r.redundant, 201 * 4);
  EXPECT_TRUE(r.locked);
  EXPECT_NE(r.verdict.find("locked by the joints"), std::string::npos) << r.verdict;
}

// Every leg in a radial plane: the legs cannot resist a turn about the centre line
// at the design pose; a little away they drive the platform fully.
TEST(Diagnoses, ASingularDesignPoseIsCalledThat) {
  const Model m = testing_files::FromJson(testing_files::ReadTestData("stewart-singular-design-pose.json"));
  const MobilityReport r = CalcMobility(m);
  EXPECT_EQ(r.singular_lost, 1);
  ASSERT_EQ(r.singular_directions.size(), 1u);
  EXPECT_NE(r.singular_directions[0].find("turning about [0, 0, 1]"), std::string::npos) << r.singular_directions[0];
  EXPECT_TRUE(r.conflicting_drivers.empty());
  EXPECT_EQ(r.driving_status, DrivingStatus::Full);
  const AnalysisReport run = RunQuietly(m);
  EXPECT_EQ(run.stop, StopKind::Refused);
  EXPECT_NE(run.message.find("the design pose is a singular position"), std::string::npos) << run.message;
  EXPECT_EQ(run.message.find("conflict"), std::string::npos) << run.message;
}

TEST(Diagnoses, RegularMechanismsGetNeither) {
  glob_t g;
  ASSERT_EQ(glob((std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/*.json").c_str(), 0, nullptr, &g), 0);
  for (size_t k = 0; k < g.gl_pathc; ++k) {
    const MobilityReport r = CalcMobility(*LoadMechanismFile(g.gl_pathv[k]).model);
    EXPECT_FALSE(r.locked) << g.gl_pathv[k];
    EXPECT_EQ(r.singular_lost, 0) << g.gl_pathv[k];
  }
  globfree(&g);
}

// Issue 23 item 8: `check`'s `driven` and `run`'s refusal come from one rule
// (JudgeDriving). The S–S RSSR: Grübler 6·3 − (5 + 3 + 3 + 5) = 2 freedoms, one
// driver, so one freedom (the coupler's spin) is left: under, and the run refuses.
TEST(Diagnoses, TheSpinningRssrCouplerIsUnderDrivenInCheckAndRun) {
  const Model m = testing_files::FromJson(testing_files::ReadJson("rssr-function-generator.json"));
  const MobilityReport r = CalcMobility(m);
  EXPECT_EQ(r.mobility, 2);
  EXPECT_EQ(r.dof_after_drivers, 1);
  ASSERT_EQ(r.idle.size(), 1u);
  EXPECT_EQ(r.driving_status, DrivingStatus::Under);
  ASSERT_EQ(r.remaining_freedoms.size(), 1u);
  EXPECT_NE(r.remaining_freedoms[0].find("idle, not driven: body `coupler`"), std::string::npos)
      << r.remaining_freedoms[0];
  const AnalysisReport run = RunQuietly(m);
  EXPECT_EQ(run.stop, StopKind::Refused);
  EXPECT_EQ(run.message.rfind("under-driven: 1 freedom(s)", 0), 0u) << run.message;
}

TEST(Diagnoses, CheckAndRunAgreeOnEveryBundledMechanism) {
  glob_t g;
  ASSERT_EQ(glob((std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/*.json").c_str(), 0, nullptr, &g), 0);
  int refused = 0;
  for (size_t k = 0; k < g.gl_pathc; ++k) {
    const std::string path = g.gl_pathv[k];
    nlohmann::json j = testing_files::ReadJson(path.substr(path.rfind('/') + 1));
    if (!j.contains("analysis")) j["analysis"] = {{"start", 0}, {"end", 1}, {"steps", 10}};
    const Model m = testing_files::FromJson(j);
    const bool full = CalcMobility(m).driving_status == DrivingStatus::Full;
    AnalysisOptions options;
    options.order = 0;
    const AnalysisReport run =
        RunKinematicAnalysis(m, options, [](const SystemState&, const StepDiagnostics&) { return false; });
    EXPECT_EQ(full, run.stop != StopKind::Refused) << g.gl_pathv[k] << ": " << run.message;
    refused += run.stop == StopKind::Refused;
  }
  globfree(&g);
  EXPECT_EQ(refused, 2);  // the RSSR and the Stewart platform with S-P-S leg bodies
}

// Issue 23 item 5: the Watt II six-bar (tests/data/watt-ii-six-bar.json: loop 1 =
// A, B, C, D and loop 2 = D, E, F, G, sharing the ternary link and its pivot D)
// with one revolute axis turned 90°. The turned joint locks its loop, and the
// locked loop the whole linkage; the joints named are those whose removal frees
// the loops, not every joint whose removal lets a crank dangle: the turned joint's
// loop (both loops share only D, so D alone when D is turned), and the turned axis
// is called out by name.
struct TurnedAxis {
  int joint;
  std::vector<std::string> locking;
};

class LockedWattII : public ::testing::TestWithParam<TurnedAxis> {};

TEST_P(LockedWattII, IsLockedByTheJointsNamingTheTurnedOne) {
  const TurnedAxis c = GetParam();
  nlohmann::json j = testing_files::ReadTestData("watt-ii-six-bar.json");
  const std::string turned = j["joints"][c.joint]["name"];
  j["joints"][c.joint]["axis"] = {1, 0, 0};
  const Model m = testing_files::FromJson(j);
  const MobilityReport r = CalcMobility(m);
  EXPECT_EQ(r.mobility, 0);
  EXPECT_TRUE(r.locked);
  EXPECT_EQ(r.locking_joints, c.locking) << r.verdict;
  EXPECT_EQ(r.verdict.rfind("locked by the joints", 0), 0u) << r.verdict;
  if (c.locking.size() > 1) {
    EXPECT_NE(r.verdict.find("the axis of `" + turned + "` is 90° off"), std::string::npos) << r.verdict;
  }
  const AnalysisReport run = RunQuietly(m);
  EXPECT_EQ(run.stop, StopKind::Refused);
  EXPECT_NE(run.message.find("locked by the joints"), std::string::npos) << run.message;
  EXPECT_NE(run.message.find("`" + turned + "`"), std::string::npos) << run.message;
  EXPECT_EQ(run.message.find("over-driven"), std::string::npos) << run.message;
}

const std::vector<std::string> kLoop1{"A", "B", "C", "D"}, kLoop2{"D", "E", "F", "G"};
INSTANTIATE_TEST_SUITE_P(EachJoint, LockedWattII,
                         ::testing::Values(TurnedAxis{0, kLoop1}, TurnedAxis{1, kLoop1}, TurnedAxis{2, kLoop1},
                                           TurnedAxis{3, {"D"}}, TurnedAxis{4, kLoop2}, TurnedAxis{5, kLoop2},
                                           TurnedAxis{6, kLoop2}));

TEST(Diagnoses, TheWattIIWithItsAxesRightMoves) {
  const Model m = testing_files::FromJson(testing_files::ReadTestData("watt-ii-six-bar.json"));
  const MobilityReport r = CalcMobility(m);
  EXPECT_EQ(r.mobility, 1);  // planar count 3·5 − 2·7
  EXPECT_FALSE(r.locked);
  EXPECT_EQ(r.driving_status, DrivingStatus::Full);
  EXPECT_TRUE(RunQuietly(m).complete);
}

}  // namespace
}  // namespace mechkin
