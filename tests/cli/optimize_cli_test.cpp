// `mechkin optimize` as a user meets it (issue 29): the worked Freudenstein example
// (mechanisms/synthesis/freudenstein-three-points.json) recovers the closed-form link
// lengths (tests/analysis/optimize_test.cpp derives them: a = 0.539363, b = 0.776453,
// c = 1.029196), writes the optimised file (which loads and runs, its parameters
// replaced, its other keys kept) and the JSON report; bad arguments exit 2 with why.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace mechkin {
namespace optimize_cli_test {

using mechkin_test::RunCli;
using mechkin_test::RunCliWithStderr;
using nlohmann::json;

const std::string kFile = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/synthesis/freudenstein-three-points.json";

json ReadFile(const std::string& path) {
  std::ifstream f(path);
  return json::parse(f);
}

TEST(OptimizeCli, FreudensteinWritesTheFileAndTheReport) {
  const std::string out = ::testing::TempDir() + "/freudenstein-optimised.json";
  const std::string report = ::testing::TempDir() + "/freudenstein-report.json";
  const auto r = RunCli("optimize " + kFile + " --vary a,b,c --minimize fit -o " + out + " --report " + report);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("minimize fit:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(converged)"), std::string::npos) << r.out;
  const json rep = ReadFile(report);
  EXPECT_EQ(rep["converged"], true);
  EXPECT_LT(rep["objective_after"].get<double>(), 1e-18);
  ASSERT_EQ(rep["parameters"].size(), 3u);
  EXPECT_EQ(rep["parameters"][0]["name"], "a");
  EXPECT_NEAR(rep["parameters"][0]["before"].get<double>(), 0.62, 1e-15);
  EXPECT_NEAR(rep["parameters"][0]["after"].get<double>(), 0.5393634715, 1e-9);
  const json file = ReadFile(out);
  EXPECT_NEAR(file["parameters"]["b"]["value"].get<double>(), 0.7764527979, 1e-9);
  EXPECT_EQ(file["parameters"]["b"]["min"], 0.4);  // the object's other keys kept
  EXPECT_EQ(file["parameters"]["xb"], "a*cos(start*pi/180)");
  EXPECT_EQ(file["description"], ReadFile(kFile)["description"]);
  const auto check = RunCli("run " + out + " -o /dev/null");
  EXPECT_EQ(check.code, 0) << check.out;
  EXPECT_NE(check.out.find("fit = sse of theta4"), std::string::npos) << check.out;
}

TEST(OptimizeCli, JsonReportOnStdoutAndProgressLines) {
  const auto r = RunCliWithStderr("optimize " + kFile + " --vary a,b,c --minimize fit --format json --progress",
                                  "/dev/null");
  ASSERT_EQ(r.code, 0) << r.out;
  const json rep = json::parse(r.out);
  EXPECT_EQ(rep["starts"].size(), 1u);
  EXPECT_GT(rep["iterations"].get<int>(), 0);
  const auto progress = RunCli("optimize " + kFile + " --vary a,b,c --minimize fit --progress -o /dev/null");
  EXPECT_NE(progress.out.find("mechkin optimize: start 1/1 iteration 1: objective "), std::string::npos)
      << progress.out;
}

TEST(OptimizeCli, UnusableArgumentsExit2WithWhy) {
  auto r = RunCli("optimize " + kFile + " --vary a,zz --minimize fit");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("no parameter 'zz'"), std::string::npos) << r.out;
  r = RunCli("optimize " + kFile + " --vary a --minimize fitt");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("'fitt' is not a reduction (the file's: fit)"), std::string::npos) << r.out;
  r = RunCli("optimize " + kFile + " --vary a --minimize fit --subject-to 'fit > 1'");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("write REDUCTION >= NUMBER"), std::string::npos) << r.out;
}

}  // namespace optimize_cli_test
}  // namespace mechkin
