// `mechkin run` at every --order stops at the change point of a slider-crank with
// crank = rod (issue 23, item 9): exit 1, a partial table of the 25 rows before
// t = 0.25 s, "singular position" on stderr and in the table's note.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands/run_command.hpp"

namespace mechkin {
namespace {

TEST(SingularRun, CrankEqualsRodStopsAtTheChangePointAtEveryOrder) {
  std::ifstream in(std::string(MECHKIN_SOURCE_DIR) + "/tests/data/slider-crank-equal-links.json");
  nlohmann::json j = nlohmann::json::parse(in);
  j["analysis"] = {{"start", 0}, {"end", 1}, {"steps", 100}};
  const std::string path = ::testing::TempDir() + "/crank-equals-rod-100.json";
  std::ofstream(path) << j.dump();
  for (int order = 0; order <= 4; ++order) {
    RunOptions o;
    o.file = path;
    o.order = order;
    std::ostringstream out, err;
    EXPECT_EQ(RunRun(o, out, err), 1) << order;
    EXPECT_NE(err.str().find("singular position at t = 0.25"), std::string::npos) << order << err.str();
    const std::string text = out.str();
    EXPECT_EQ(text.rfind("# PARTIAL TABLE: singular position at t = 0.25", 0), 0u) << order;
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1 + 1 + 25) << order;  // note, header, t = 0 … 0.24
  }
}

}  // namespace
}  // namespace mechkin
