// A joint type added at run time (issue 32, docs/joints.md): one descriptor, one
// line to register it, and a file may name it. "test_hinge" is revolute's
// descriptor written out again under another name, so every bundled mechanism
// with its revolutes retyped must read, compile, check and run exactly as it does
// with "revolute": the same check report (but for the type's name) and the same
// table, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "analysis/check_report.hpp"
#include "analysis/run_request.hpp"
#include "constraints/system.hpp"
#include "io/check_report_writer.hpp"
#include "joints/equations.hpp"
#include "joints/registry.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace joint_registry_test {

using nlohmann::json;

// The new joint's one file would hold this (compare src/joints/revolute.cpp).
JointDescriptor TestHinge() {
  JointDescriptor d;
  d.name = "test_hinge";
  d.frames = JointFrameRule::Axis;
  d.equations = Joined({{SphericalEquation()}, ParallelOne()});
  d.coordinates = JointCoordinates::Angle;
  d.turns = true;
  d.limit = JointLimit::Angle;
  d.planar = PlanarRole::Turn;
  d.relaxations = {"cylindrical", "universal", "spherical"};
  d.glyph = "pin";
  return d;
}

const JointDescriptor& Hinge() {
  static const JointDescriptor& hinge = RegisterJointType(TestHinge());  // the one registry line
  return hinge;
}

// The file with every revolute joint retyped; false when it has none.
bool Retyped(json* doc) {
  bool any = false;
  for (json& j : (*doc)["joints"])
    if (j.value("type", "") == "revolute") j["type"] = Hinge().name, any = true;
  return any;
}

// Text with the new type's name put back: what the two files must agree on.
std::string Renamed(std::string text) {
  for (size_t at; (at = text.find("test_hinge")) != std::string::npos;) text.replace(at, 10, "revolute");
  return text;
}

TEST(JointRegistry, ARegisteredCopyOfRevoluteChecksAndRunsLikeIt) {
  int files = 0, ran = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms")) {
    if (entry.path().extension() != ".json") continue;
    const json original = testing_files::ReadJson(entry.path().filename().string());
    json retyped = original;
    if (!Retyped(&retyped)) continue;
    const std::string name = entry.path().filename().string();
    const LoadResult a = LoadMechanismText(original.dump(), name), b = LoadMechanismText(retyped.dump(), name);
    ASSERT_TRUE(a.ok() && b.ok()) << name << (b.errors.empty() ? "" : b.errors[0].ToString());
    // Mobility, the Grübler count, joint equations and their names, expectations.
    const json ca = CheckReportJson(CheckLoaded(name, a));
    const json cb = json::parse(Renamed(CheckReportJson(CheckLoaded(name, b)).dump()));
    EXPECT_EQ(ca, cb) << name;
    EXPECT_NE(CheckReportJson(CheckLoaded(name, b)).dump().find("test_hinge"), std::string::npos) << name;
    RunRequest request;
    const Motion ma = RunMotion(*a.model, request), mb = RunMotion(*b.model, request);
    ASSERT_EQ(ma.cols(), mb.cols()) << name;
    for (int c = 0; c < ma.cols(); ++c) EXPECT_EQ(ma.columns()[c].name, mb.columns()[c].name) << name;
    ASSERT_EQ(ma.values().size(), mb.values().size()) << name;
    EXPECT_EQ(ma.complete, mb.complete) << name;
    EXPECT_EQ(std::memcmp(ma.values().data(), mb.values().data(), ma.values().size() * sizeof(double)), 0) << name;
    ++files;
    ran += ma.rows() > 1;
  }
  EXPECT_GE(files, 15);
  EXPECT_GE(ran, 12);  // tables to compare (an under-driven file is refused by both)
}

TEST(JointRegistry, EquationNamesAndMessagesNameTheNewType) {
  json doc = testing_files::ReadJson("planar-four-bar.json");
  ASSERT_TRUE(Retyped(&doc));
  const LoadResult r = LoadMechanismText(doc.dump(), "four-bar");
  ASSERT_TRUE(r.ok());
  const ConstraintSystem sys(*r.model, false);
  EXPECT_EQ(sys.DescribeRow(3), "joint `" + r.model->joints[0].name + "` (test_hinge): rotation about its frame's g axis");
  EXPECT_EQ(r.model->joints[0].type, &Hinge());
  // The reader takes the new type's keys and refuses what revolute refuses.
  doc["joints"][0].erase("axis");
  doc["joints"][0]["normal"] = {0, 0, 1};
  const LoadResult bad = LoadMechanismText(doc.dump(), "four-bar");
  ASSERT_FALSE(bad.ok());
  const std::string first = bad.errors[0].ToString();
  EXPECT_NE(first.find("a test_hinge joint"), std::string::npos) << first;
  // Unknown types list the registered ones.
  doc["joints"][0]["type"] = "test_hinje";
  const LoadResult typo = LoadMechanismText(doc.dump(), "four-bar");
  ASSERT_FALSE(typo.ok());
  EXPECT_NE(typo.errors[0].ToString().find("did you mean 'test_hinge'?"), std::string::npos) << typo.errors[0].ToString();
}

TEST(JointRegistry, RefusesATakenNameAndAnUnknownRelaxation) {
  Hinge();
  EXPECT_THROW(RegisterJointType(TestHinge()), std::invalid_argument);
  JointDescriptor d = TestHinge();
  d.name = "test_loose_hinge";
  d.relaxations = {"no_such_joint"};
  EXPECT_THROW(RegisterJointType(d), std::invalid_argument);
  d.relaxations.clear();
  d.equations[0].rows.pop_back();  // a spherical primitive has three rows
  EXPECT_THROW(RegisterJointType(d), std::invalid_argument);
  EXPECT_EQ(FindJointType("test_loose_hinge"), nullptr);
  EXPECT_EQ(JointTypeNamed("revolute").Rows(), 5);
}

}  // namespace
}  // namespace mechkin
