// The low findings of issue 24, each at its root: the argument or the report that
// let the wrong thing through, checked from the command line.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"

namespace {

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

}  // namespace
