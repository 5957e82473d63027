// The parametric commands from the command line: --set, --sensitivity, tolerance
// and sweep — their exit codes and the messages a slip gets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands/check_command.hpp"
#include "cli/commands/run_command.hpp"
#include "cli/commands/sweep_command.hpp"
#include "cli/commands/tolerance_command.hpp"

namespace mechkin {
namespace parametric_commands_test {

const std::string kSlider = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-slider-crank.json";
const std::string kFourBar = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json";

TEST(ParametricCommands, SetChangesTheRunAndBadSettingsAreRefused) {
  RunOptions o;
  o.file = kSlider;
  o.request.order = 0;
  o.outputs = {"piston"};
  o.outputs_given = o.bodies_given = true;
  o.set = {"crank=45", "offset=0"};
  std::ostringstream out, err;
  ASSERT_EQ(RunRun(o, out, err), 0) << err.str();
  // First row: x = 45 cos 30° + √(120² − (0 − 22.5)²), y = 0.
  std::istringstream rows(out.str());
  std::string header, first;
  std::getline(rows, header);
  std::getline(rows, first);
  EXPECT_NEAR(std::stod(first.substr(first.find(',') + 1)), 45 * std::sqrt(3.0) / 2 + std::sqrt(14400 - 506.25), 1e-9);
  for (const std::vector<std::string>& bad : {std::vector<std::string>{"crank"}, {"crank=abc"}, {"=4"}}) {
    o.set = bad;
    std::ostringstream o2, e2;
    EXPECT_EQ(RunRun(o, o2, e2), 2) << bad[0];
    EXPECT_NE(e2.str().find("expected NAME=NUMBER"), std::string::npos);
  }
  o.set = {"crnk=4"};
  std::ostringstream o3, e3;
  EXPECT_EQ(RunRun(o, o3, e3), 1);
  EXPECT_NE(e3.str().find("did you mean 'crank'?"), std::string::npos) << e3.str();
}

TEST(ParametricCommands, SensitivityColumnsAndUnknownParameter) {
  RunOptions o;
  o.file = kSlider;
  o.request.order = 1;
  o.sensitivity = {"rod"};
  std::ostringstream out, err;
  ASSERT_EQ(RunRun(o, out, err), 0) << err.str();
  EXPECT_NE(out.str().find("piston.x/d(rod) [mm/rod]"), std::string::npos);
  EXPECT_NE(out.str().find("crank.wz/d(rod) [deg/s/rod]"), std::string::npos);
  o.sensitivity = {"length"};
  std::ostringstream o2, e2;
  EXPECT_EQ(RunRun(o, o2, e2), 2);
  EXPECT_NE(e2.str().find("no parameter 'length'"), std::string::npos);
}

TEST(ParametricCommands, CheckShowsParametersAndLinkLengths) {
  CheckOptions o;
  o.files = {kSlider};
  o.set = {"rod=130"};
  std::ostringstream out, err;
  ASSERT_EQ(RunCheck(o, out, err), 0) << out.str() << err.str();
  EXPECT_NE(out.str().find("rod = 130 ±0.05 (set)"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("rod: crankpin-wristpin 130;"), std::string::npos) << out.str();
  o.format = "json";
  std::ostringstream js;
  ASSERT_EQ(RunCheck(o, js, err), 0);
  const auto doc = nlohmann::json::parse(js.str());
  EXPECT_DOUBLE_EQ(doc["files"][0]["parameters"]["rod"]["value"].get<double>(), 130);
  EXPECT_NEAR(doc["files"][0]["geometry"]["bodies"][0]["lengths"][0]["distance"].get<double>(), 40, 1e-12);
}

TEST(ParametricCommands, ToleranceJsonAndAFileWithoutTolerances) {
  ToleranceCommandOptions o;
  o.file = kSlider;
  o.format = "json";
  std::ostringstream out, err;
  ASSERT_EQ(RunToleranceCommand(o, out, err), 0) << err.str();
  const auto doc = nlohmann::json::parse(out.str());
  EXPECT_EQ(doc["columns"][0]["name"], "piston.x");
  EXPECT_EQ(doc["tolerances"].size(), 3u);
  o.file = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/offset-slider-crank.json";
  std::ostringstream o2, e2;
  EXPECT_EQ(RunToleranceCommand(o, o2, e2), 1);
  EXPECT_NE(e2.str().find("no parameter declares a tolerance"), std::string::npos);
}

TEST(ParametricCommands, SweepArgumentsAreChecked) {
  SweepCommandOptions o;
  o.files = {kFourBar};
  std::ostringstream out, err;
  EXPECT_EQ(RunSweepCommand(o, out, err), 2);  // neither --grid nor --samples
  EXPECT_NE(err.str().find("either --grid"), std::string::npos);
  o.grid = {"q=1:2:3"};
  std::ostringstream o2, e2;
  EXPECT_EQ(RunSweepCommand(o, o2, e2), 2);
  EXPECT_NE(e2.str().find("no parameter 'q'"), std::string::npos);
  o.grid = {"a=30:50:3"};
  o.shard = "5/4";
  std::ostringstream o3, e3;
  EXPECT_EQ(RunSweepCommand(o, o3, e3), 2);
  EXPECT_NE(e3.str().find("expected i/N"), std::string::npos);
  o.shard = "";
  std::ostringstream o4, e4;
  ASSERT_EQ(RunSweepCommand(o, o4, e4), 0) << e4.str();
  const std::string table = o4.str();
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 4);  // header + 3 variants
}

// Acceptance (joint coordinates from the markers): `mechkin sweep` of the marker four-bar
// over its crank length with the crank held at 0: each variant's rocker angle is the
// closed form's there (C at 120 from B = (a, 0) and 80 from D = (100, 0)), not 0.
TEST(ParametricCommands, SweepOfAMarkerFourBarReadsTheClosedFormAtTheCranksZero) {
  SweepCommandOptions o;
  o.files = {std::string(MECHKIN_SOURCE_DIR) + "/tests/data/marker-four-bar.json"};
  o.set = {"speed=0"};
  o.grid = {"crank=30:50:3"};
  o.request.order = 0;
  o.format = "json";
  std::ostringstream out, err;
  ASSERT_EQ(RunSweepCommand(o, out, err), 0) << err.str();
  const auto j = nlohmann::json::parse(out.str());
  const auto& columns = j["columns"];
  const auto rocker = std::find(columns.begin(), columns.end(), "rocker_angle [deg]") - columns.begin();
  ASSERT_LT(rocker, static_cast<long>(columns.size())) << columns.dump();
  ASSERT_EQ(j["variants"].size(), 3u);
  for (const auto& v : j["variants"]) {
    ASSERT_EQ(v["status"], "complete") << v.dump();
    const double a = v["values"][0], b = 120, c = 80, d = 100;
    const double cos_psi = (c * c + (d - a) * (d - a) - b * b) / (2 * c * (d - a));
    const double expected = 180 - std::acos(cos_psi) * 180 / M_PI;
    EXPECT_NEAR(v["min"][rocker].get<double>(), expected, 1e-8) << a;
    EXPECT_NEAR(v["max"][rocker].get<double>(), expected, 1e-8) << a;
  }
}

}  // namespace
}  // namespace mechkin
