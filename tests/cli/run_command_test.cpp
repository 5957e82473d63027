#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands/run_command.hpp"

namespace mechkin {
namespace run_command_test {

const std::string kSrc = MECHKIN_SOURCE_DIR;

std::string ReadFile(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string p = ::testing::TempDir() + "/" + name;
  std::ofstream(p) << text;
  return p;
}

TEST(RunCommand, ColumnsAreNamedAsInFormatV1) {
  RunOptions o;
  o.file = kSrc + "/mechanisms/spatial-slider-crank.json";
  o.request.order = 3;
  std::ostringstream out, err;
  ASSERT_EQ(RunRun(o, out, err), 0) << err.str();
  const std::string header = out.str().substr(0, out.str().find('\n'));
  for (const char* col : {"t [s]", "crank.x [m]", "crank.e0,", "crank.wx [deg/s]", "crank.wx_t [deg/s^2]",
                          "piston.x_tt [m/s^2]", "piston.x_ttt [m/s^3]", "crank_angle [deg]", "crank_angle_ttt [deg/s^3]"})
    EXPECT_NE(header.find(col), std::string::npos) << col;
  EXPECT_EQ(header.find("_tttt"), std::string::npos);  // order 3: no snap columns
  // 360 steps → 361 rows + header.
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 362);
}

TEST(RunCommand, OrderAndSelectionLimitTheColumns) {
  RunOptions o;
  o.file = kSrc + "/mechanisms/spatial-slider-crank.json";
  o.request.order = 1;
  o.bodies_given = true;  // no body columns
  o.outputs = {"piston"};
  o.outputs_given = true;
  std::ostringstream out, err;
  ASSERT_EQ(RunRun(o, out, err), 0);
  EXPECT_EQ(out.str().substr(0, out.str().find('\n')),
            "t [s],piston.x [m],piston.x_t [m/s],piston.y [m],piston.y_t [m/s],piston.z [m],piston.z_t [m/s],"
            "newton_iterations,residual,condition,error_bound,error_bound_t");
}

TEST(RunCommand, JsonTableAndStatsLine) {
  RunOptions o;
  o.file = kSrc + "/mechanisms/planar-four-bar.json";
  o.format = "json";
  o.stats = true;
  std::ostringstream out, err;
  ASSERT_EQ(RunRun(o, out, err), 0);
  const auto j = nlohmann::json::parse(out.str());
  EXPECT_FALSE(j["partial"].get<bool>());
  EXPECT_EQ(j["rows"].size(), 361u);
  EXPECT_EQ(j["columns"][1]["name"], "crank.x");
  EXPECT_EQ(j["columns"][1]["unit"], "mm");
  EXPECT_NE(err.str().find("per step: "), std::string::npos);
  EXPECT_NE(err.str().find(" us solve, "), std::string::npos);
  EXPECT_NE(err.str().find(" Newton iterations"), std::string::npos);
  // Planar (planar count 1 = drivers): the out-of-plane redundancy is not listed, only counted.
  EXPECT_EQ(err.str().find("redundant equation"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("set-aside equations: 3 "), std::string::npos) << err.str();
}

// Planar files do not repeat the out-of-plane redundancy `check` reports; a spatial
// overconstrained file lists its redundant equations unless --quiet.
TEST(RunCommand, RedundancyNotesArePlanarAwareAndQuietSilencesThem) {
  auto stderr_of = [](const std::string& file, bool quiet) {
    RunOptions o;
    o.file = kSrc + "/mechanisms/" + file;
    o.request.order = 0;
    o.quiet = quiet;
    std::ostringstream out, err;
    EXPECT_EQ(RunRun(o, out, err), 0) << err.str();
    return err.str();
  };
  for (const char* planar : {"planar-four-bar.json", "offset-slider-crank.json", "five-bar.json"})
    EXPECT_EQ(stderr_of(planar, false), "") << planar;
  const std::string bennett = stderr_of("bennett-linkage.json", false);
  EXPECT_NE(bennett.find("mechkin run: redundant equation set aside: joint `J4` (revolute)"), std::string::npos);
  EXPECT_EQ(stderr_of("bennett-linkage.json", true), "");
}

// The crank-rocker driven at its rocker past the rocker's range: a toggle. The run
// stops with the time, the residuals and the singular value, keeps the rows so far
// in a table marked partial, and exits 1.
TEST(RunCommand, DriverPushedPastAToggleStopsWithAPartialTable) {
  std::string text = ReadFile(kSrc + "/mechanisms/planar-four-bar.json");
  const auto j0 = nlohmann::json::parse(text);
  nlohmann::json j = j0;
  j["drivers"][0]["joint"] = "D";
  j["drivers"][0]["function"] = "-120*t";  // the rocker swings about 60° in all
  j["analysis"] = {{"start", 0}, {"end", 1}, {"steps", 100}};
  const std::string file = WriteTemp("toggle.json", j.dump());
  RunOptions o;
  o.file = file;
  o.output = ::testing::TempDir() + "/toggle.csv";
  std::ostringstream out, err;
  EXPECT_EQ(RunRun(o, out, err), 1);
  EXPECT_NE(err.str().find("position solve failed at t = "), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("smallest singular value"), std::string::npos);
  EXPECT_NE(err.str().find("Try:"), std::string::npos);
  const std::string table = ReadFile(o.output);
  EXPECT_EQ(table.rfind("# PARTIAL TABLE", 0), 0u);
  const long rows = std::count(table.begin(), table.end(), '\n') - 2;
  EXPECT_GT(rows, 5);
  EXPECT_LT(rows, 101);
}

TEST(RunCommand, RefusesConflictingAndUnderDrivenFiles) {
  auto j = nlohmann::json::parse(ReadFile(kSrc + "/mechanisms/planar-four-bar.json"));
  j["drivers"].push_back({{"name", "second"}, {"type", "rotation"}, {"joint", "A"}, {"function", "10*t"}});
  RunOptions o;
  o.file = WriteTemp("two_drivers.json", j.dump());
  std::ostringstream out, err;
  EXPECT_EQ(RunRun(o, out, err), 1);
  EXPECT_NE(err.str().find("over-driven"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("`second`"), std::string::npos) << err.str();

  auto f = nlohmann::json::parse(ReadFile(kSrc + "/mechanisms/five-bar.json"));
  f["drivers"].erase(1);
  o.file = WriteTemp("five_bar_one_driver.json", f.dump());
  std::ostringstream out2, err2;
  EXPECT_EQ(RunRun(o, out2, err2), 1);
  EXPECT_NE(err2.str().find("under-driven"), std::string::npos) << err2.str();
}

TEST(RunCommand, InvalidFileExitsOneAndWritesNothing) {
  RunOptions o;
  o.file = kSrc + "/tests/invalid/zero-axis.json";
  o.output = ::testing::TempDir() + "/never.csv";
  std::remove(o.output.c_str());
  std::ostringstream out, err;
  EXPECT_EQ(RunRun(o, out, err), 1);
  EXPECT_NE(err.str().find("/joints/0/axis"), std::string::npos);
  EXPECT_FALSE(std::ifstream(o.output).good());
}

// Near a dead centre the step solves to the residual the derivatives need; where the
// conditioning still costs digits, run says which orders and when (once each), and
// the well-conditioned bundled mechanisms say nothing.
TEST(RunCommand, NotesWhereTheBoundExceedsTheTolerance) {
  RunOptions o;
  o.file = kSrc + "/tests/data/piston-driven-slider-crank.json";
  o.request.order = 3;
  std::ostringstream out, err;
  ASSERT_EQ(RunRun(o, out, err), 0) << err.str();
  EXPECT_NE(err.str().find("note: the jerk error bound exceeds 10 x --tol 1e-10 from t = "), std::string::npos) << err.str();
  EXPECT_EQ(err.str().find("note: the position"), std::string::npos) << err.str();
  RunOptions plain;
  plain.file = kSrc + "/mechanisms/planar-four-bar.json";
  plain.request.order = 3;
  std::ostringstream out2, err2;
  ASSERT_EQ(RunRun(plain, out2, err2), 0);
  EXPECT_EQ(err2.str().find("note:"), std::string::npos) << err2.str();
}

}  // namespace
}  // namespace mechkin
