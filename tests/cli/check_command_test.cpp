#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands/check_command.hpp"

namespace mechkin {
namespace check_command_test {

const std::string kSrc = MECHKIN_SOURCE_DIR;

nlohmann::json CheckJson(const std::vector<std::string>& files, int* rc) {
  CheckOptions o;
  o.files = files;
  o.format = "json";
  std::ostringstream out, err;
  *rc = RunCheck(o, out, err);
  return nlohmann::json::parse(out.str());
}

// Every file of the invalid corpus is rejected with exit 1 and an error at the
// JSON pointer listed in tests/invalid/expected.tsv.
TEST(CheckCommand, InvalidCorpusNamesTheRightPointer) {
  std::ifstream tsv(kSrc + "/tests/invalid/expected.tsv");
  std::string line;
  int cases = 0;
  while (std::getline(tsv, line)) {
    const auto tab = line.find('\t');
    const std::string file = line.substr(0, tab), pointer = line.substr(tab + 1);
    int rc = 0;
    const auto report = CheckJson({kSrc + "/tests/invalid/" + file}, &rc);
    EXPECT_EQ(rc, 1) << file;
    const auto& f = report["files"][0];
    EXPECT_FALSE(f["valid"].get<bool>()) << file;
    bool found = false;
    for (const auto& e : f["errors"]) found = found || e["pointer"] == pointer;
    EXPECT_TRUE(found) << file << " should name " << pointer << "; got " << f["errors"].dump();
    ++cases;
  }
  EXPECT_GE(cases, 30);
}

// The JSON report of each bundled file gives the Grübler count its expect states.
TEST(CheckCommand, BundledMechanismsHoldTheirExpectations) {
  const std::vector<std::pair<std::string, int>> grubler = {
      {"planar-four-bar", -2}, {"bennett-linkage", -2}, {"spatial-slider-crank", 1}, {"screw-jack", -3},
      {"stewart-platform", 6}, {"five-bar", -1}, {"rssr-function-generator", 2}, {"hooke-joint-30deg", -2}};
  for (const auto& [name, g] : grubler) {
    int rc = 0;
    const auto report = CheckJson({kSrc + "/mechanisms/" + name + ".json"}, &rc);
    EXPECT_EQ(rc, 0) << name;
    EXPECT_EQ(report["files"][0]["grubler"].get<int>(), g) << name;
  }
}

TEST(CheckCommand, OneBadFileDoesNotStopTheOthers) {
  int rc = 0;
  const auto report = CheckJson({kSrc + "/tests/invalid/empty-file.json", kSrc + "/mechanisms/planar-four-bar.json"}, &rc);
  EXPECT_EQ(rc, 1);
  ASSERT_EQ(report["files"].size(), 2u);
  EXPECT_FALSE(report["files"][0]["valid"].get<bool>());
  EXPECT_TRUE(report["files"][1]["valid"].get<bool>());
  EXPECT_EQ(report["files"][1]["mobility"]["mobility"].get<int>(), 1);
}

TEST(CheckCommand, FailedExpectationExitsOne) {
  const std::string path = ::testing::TempDir() + "/wrong_expect.json";
  std::ofstream(path) << R"({"mechkin": 1, "bodies": [{"name": "b", "position": [0, 0, 0]}],
    "joints": [{"name": "j", "type": "spherical", "body1": "ground", "body2": "b", "origin": [0, 0, 0]}],
    "expect": {"grubler": 4}})";
  int rc = 0;
  const auto report = CheckJson({path}, &rc);
  EXPECT_EQ(rc, 1);
  EXPECT_EQ(report["files"][0]["grubler"].get<int>(), 3);
  EXPECT_FALSE(report["files"][0]["expect"][0]["held"].get<bool>());
}

int RunBinary(const std::string& args) {
  const int status = std::system((std::string(MECHKIN_BINARY) + " " + args + " >/dev/null 2>&1").c_str());
  return WEXITSTATUS(status);
}

TEST(CheckCommand, ExitCodes) {
  EXPECT_EQ(RunBinary("check " + kSrc + "/mechanisms/planar-four-bar.json"), 0);
  EXPECT_EQ(RunBinary("check " + kSrc + "/tests/invalid/zero-axis.json"), 1);
  EXPECT_EQ(RunBinary("check --format xml " + kSrc + "/mechanisms/planar-four-bar.json"), 2);
  EXPECT_EQ(RunBinary("check"), 2);
  EXPECT_EQ(RunBinary("frobnicate"), 2);
  EXPECT_EQ(RunBinary("--help"), 0);
}

}  // namespace
}  // namespace mechkin
