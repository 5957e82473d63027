// `mechkin run` at every --order stops at the change point of a slider-crank with
// crank = rod (issue 23, item 9): exit 1, a partial table of the 25 rows before
// t = 0.25 s, "singular position" on stderr and in the table's note.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands/run_command.hpp"
#include "../n_four_bar.hpp"

namespace mechkin {
namespace singular_run_test {

TEST(SingularRun, CrankEqualsRodStopsAtTheChangePointAtEveryOrder) {
  std::ifstream in(std::string(MECHKIN_SOURCE_DIR) + "/tests/data/slider-crank-equal-links.json");
  nlohmann::json j = nlohmann::json::parse(in);
  j["analysis"] = {{"start", 0}, {"end", 1}, {"steps", 100}};
  const std::string path = ::testing::TempDir() + "/crank-equals-rod-100.json";
  std::ofstream(path) << j.dump();
  for (int order = 0; order <= 4; ++order) {
    RunOptions o;
    o.file = path;
    o.request.order = order;
    std::ostringstream out, err;
    EXPECT_EQ(RunRun(o, out, err), 1) << order;
    EXPECT_NE(err.str().find("singular position at t = 0.25"), std::string::npos) << order << err.str();
    const std::string text = out.str();
    EXPECT_EQ(text.rfind("# PARTIAL TABLE: singular position at t = 0.25", 0), 0u) << order;
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1 + 1 + 25) << order;  // note, header, t = 0 … 0.24
  }
}

// The N-four-bar (IFToMM A02) with N = 2 windows, drawn at −40° and driven at
// −97°/s through the singular position at −90° (a unique passage, t = 50/97 s,
// between rows): the run completes and says so on stderr.
TEST(SingularRun, UniquePassageIsNotedOnStderr) {
  const nlohmann::json j = testing_files::NFourBar(2, -40, -97, 100);
  const std::string path = ::testing::TempDir() + "/n-four-bar-2.json";
  std::ofstream(path) << j.dump();
  RunOptions o;
  o.file = path;
  std::ostringstream out, err;
  EXPECT_EQ(RunRun(o, out, err), 0) << err.str();
  const std::string e = err.str();
  EXPECT_NE(e.find("mechkin run: note: "), std::string::npos) << e;
  EXPECT_NE(e.find("unique passage through a singular position at t = 0.51546"), std::string::npos) << e;
  const std::string table = out.str();
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 1 + 101);  // header and every row
}

}  // namespace
}  // namespace mechkin
