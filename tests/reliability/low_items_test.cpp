// The low findings of issue 24, each at its root: the argument or the report that
// let the wrong thing through, checked from the command line.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"

namespace low_items_test {

using mechkin_test::CliResult;
using mechkin_test::RunCli;
using nlohmann::json;

std::string Dir() {
  static std::string d = [] {
    std::string t = ::testing::TempDir() + "/mechkin-low-XXXXXX";
    return std::string(::mkdtemp(t.data()));
  }();
  return d;
}

const std::string kFourBar = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json";

TEST(LowItems, ShardWithTrailingTextIsRefused) {
  for (const std::string shard : {"1/2/3", "1/2x", "1x/2", "1/"}) {
    const CliResult r = RunCli("sweep " + kFourBar + " --samples 4 --shard " + shard);
    EXPECT_EQ(r.code, 2) << shard << ": " << r.out;
    EXPECT_NE(r.out.find("--shard '" + shard + "': expected i/N with 1 <= i <= N"), std::string::npos) << r.out;
  }
  EXPECT_EQ(RunCli("sweep " + kFourBar + " --samples 4 --shard 2/2").code, 0);
}

TEST(LowItems, SensitivityParameterNamedTwiceIsRefused) {
  const CliResult r = RunCli("run " + kFourBar + " --sensitivity a,a -o " + Dir() + "/s.csv");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("sensitivity: parameter 'a' is given twice: name each parameter once"), std::string::npos)
      << r.out;
  EXPECT_EQ(RunCli("run " + kFourBar + " --sensitivity a,b -o " + Dir() + "/s2.csv").code, 0);
}

TEST(LowItems, MonteCarloWhereEverySampleFailsIsAFailureNotADeviationOfZero) {
  std::ifstream in(kFourBar);
  json j = json::parse(in);
  j["parameters"]["a"]["tolerance"] = 1e6;  // every sample's crank is far beyond what the loop closes
  const std::string file = Dir() + "/wild.json";
  std::ofstream(file) << j.dump();
  const CliResult r = RunCli("tolerance " + file + " --monte-carlo 20 --threads 2");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("every one of the 20 Monte-Carlo samples failed"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("largest deviation"), std::string::npos) << r.out;
  const CliResult ok = RunCli("tolerance " + kFourBar + " --monte-carlo 20 --threads 2");
  EXPECT_EQ(ok.code, 0) << ok.out;  // the file's own tolerances: samples run
}

std::string WriteJson(const std::string& name, const json& j) {
  const std::string p = Dir() + "/" + name;
  std::ofstream(p) << j.dump();
  return p;
}

json Steering() {
  std::ifstream in(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/rack-and-pinion-steering.json");
  return json::parse(in);
}

TEST(LowItems, ALoadUndefinedInsideTheSpanIsRefusedByCheckWithItsPlaceAndTime) {
  json j = Steering();  // analysis 0..2 s in 200 steps: t = 0.5 s is a row
  j["loads"][0]["components"] = {"1/(t-0.5)", 0, 0};
  const std::string file = WriteJson("load.json", j);
  const CliResult check = RunCli("check " + file);
  EXPECT_EQ(check.code, 1) << check.out;
  EXPECT_NE(check.out.find("/loads/0/components/0: load 'road' cannot be evaluated at t = 0.5 s of the analysis span: "
                           "division by zero"),
            std::string::npos)
      << check.out;
  const CliResult run = RunCli("run " + file + " -o " + Dir() + "/load.csv");
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find("/loads/0/components/0"), std::string::npos) << run.out;
  j["loads"][0]["components"] = {"1/(t+0.5)", 0, 0};  // defined over the span
  EXPECT_EQ(RunCli("check " + WriteJson("load-ok.json", j)).code, 0);
}

TEST(LowItems, AMassBeyondTheDoublesRangeOfTheDynamicsIsRefused) {
  json j = Steering();
  j["bodies"][1]["inertia"] = {{"mass", 1e308}, {"center", {0, 0, 0}}, {"moments", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}};
  const CliResult r = RunCli("check " + WriteJson("mass.json", j));
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("/bodies/1/inertia/mass: mass 1e+308 kg is beyond 1e15 kg"), std::string::npos) << r.out;
  j["bodies"][1]["inertia"]["mass"] = 2.5;
  EXPECT_EQ(RunCli("check " + WriteJson("mass-ok.json", j)).code, 0);
}

TEST(LowItems, ABranchHintBeyondOneTurnIsRefusedNotIgnored) {
  std::ifstream in(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/four-bar-by-lengths.json");
  json j = json::parse(in);
  j["analysis"]["branch"]["joints"]["D"] = 1e308;
  const CliResult r = RunCli("check " + WriteJson("hint.json", j));
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("/analysis/branch/joints/D: branch hint 1e+308 deg is more than one turn from the design pose"),
            std::string::npos)
      << r.out;
  j["analysis"]["branch"]["joints"]["D"] = -300;
  EXPECT_EQ(RunCli("check " + WriteJson("hint-ok.json", j)).code, 0);
}

}  // namespace
