// Limits on accepted inputs (issue 24, "Memory limits on accepted inputs"): the JSON
// nesting limit that docs/format.md states (100 levels) is the one the reader
// enforces, and it is checked before the parse allocates anything (a 20 MB file of
// '[' took 4.3 GB and 17 s to report a syntax error).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "analysis/load.hpp"
#include "cli_runner.hpp"

namespace input_limits_test {

using mechkin::LoadMechanismText;
using mechkin::LoadResult;

std::string Nested(int depth) { return std::string(depth, '[') + std::string(depth, ']'); }

long PeakRssKb() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

TEST(JsonNesting, OneHundredLevelsParseAndTheNextIsRefusedWithItsPlace) {
  const LoadResult ok_depth = LoadMechanismText(Nested(100), "nested.json");
  ASSERT_FALSE(ok_depth.errors.empty());
  EXPECT_EQ(ok_depth.errors.front().message.find("nests deeper"), std::string::npos)
      << "100 levels are within the stated limit: " << ok_depth.errors.front().message;
  const LoadResult deep = LoadMechanismText(Nested(101), "nested.json");
  ASSERT_FALSE(deep.errors.empty());
  EXPECT_EQ(deep.errors.front().message, "the JSON nests deeper than 100 levels of '[' and '{' at line 1, column 101");
  EXPECT_FALSE(deep.errors.front().fix.empty());
}

TEST(JsonNesting, BracketsInsideStringsDoNotCount) {
  const std::string text = "{\"name\": \"" + std::string(500, '[') + "\\\"" + std::string(500, '{') + "\"}";
  const LoadResult r = LoadMechanismText(text, "strings.json");
  ASSERT_FALSE(r.errors.empty());  // not a mechanism, but not too deep either
  for (const auto& e : r.errors) EXPECT_EQ(e.message.find("nests deeper"), std::string::npos) << e.message;
}

TEST(JsonNesting, TwentyMegabytesOfOpenBracketsAreRefusedWithoutAllocating) {
  const std::string text(20 * 1000 * 1000, '[');
  const long before = PeakRssKb();
  const LoadResult r = LoadMechanismText(text, "brackets.json");
  const long grown_mb = (PeakRssKb() - before) / 1024;
  ASSERT_FALSE(r.errors.empty());
  EXPECT_EQ(r.errors.front().message, "the JSON nests deeper than 100 levels of '[' and '{' at line 1, column 101");
  EXPECT_LT(grown_mb, 100) << "peak memory grew by " << grown_mb << " MB";
  std::printf("20 MB of '[': peak memory grew by %ld MB\n", grown_mb);
}

std::string ReadText(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// `view` keeps only the page's rows while the run goes (a 1e7-step view held the whole
// table, > 4 GB); with --gltf the whole motion is kept and the page decimates it. The
// two pages must be the same bytes: the rows kept are the rows the page shows.
TEST(PageRows, TheRowsKeptDuringTheRunAreThePagesFrames) {
  std::ifstream in(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json");
  nlohmann::json j = nlohmann::json::parse(in);
  j["analysis"]["steps"] = 20011;  // not a multiple of the frames
  const std::string dir = ::testing::TempDir();
  const std::string file = dir + "/page-rows.json";
  std::ofstream(file) << j.dump();
  for (const std::string frames : {"300", "2000"}) {
    const auto a = mechkin_test::RunCli("view " + file + " --order 1 --max-frames " + frames + " -o " + dir + "/a.html");
    const auto b = mechkin_test::RunCli("view " + file + " --order 1 --max-frames " + frames + " -o " + dir +
                                        "/b.html --gltf " + dir + "/b.glb");
    ASSERT_EQ(a.code, 0) << a.out;
    ASSERT_EQ(b.code, 0) << b.out;
    const std::string page_a = ReadText(dir + "/a.html"), page_b = ReadText(dir + "/b.html");
    EXPECT_GT(page_a.size(), 100000u);
    EXPECT_TRUE(page_a == page_b) << "--max-frames " << frames << ": the pages differ";
  }
}

// The peak memory of the largest child of this test process (ctest runs each test alone).
long ChildPeakMb() {
  rusage u{};
  ::getrusage(RUSAGE_CHILDREN, &u);
  return u.ru_maxrss / 1024;
}

std::string FourBarWithSteps(int steps) {
  std::ifstream in(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json");
  nlohmann::json j = nlohmann::json::parse(in);
  j["analysis"]["steps"] = steps;
  const std::string file = ::testing::TempDir() + "/four-bar-" + std::to_string(steps) + ".json";
  std::ofstream(file) << j.dump();
  return file;
}

// 300,000 steps held the whole table (about 180 MB here; 1e7 steps: > 4 GB).
TEST(PageRows, AViewKeepsThePagesRowsNotTheTable) {
  const auto r = mechkin_test::RunCli("view " + FourBarWithSteps(300000) + " -o " + ::testing::TempDir() + "/long.html");
  ASSERT_EQ(r.code, 0) << r.out;
  // Flat in the steps: under ASan + UBSan 85 MB at 30,000 and at 300,000 steps
  // (2026-12-04; the sanitizer's own overhead), Release well below.
  EXPECT_LT(ChildPeakMb(), 100) << "peak MB of the view";
  std::printf("view of 300000 steps: peak %ld MB\n", ChildPeakMb());
}

// range kept every step's diagnostics and the whole table (471 MB at --steps 1e6).
TEST(RangeRows, ARangeKeepsNoTable) {
  const std::string four_bar = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json";
  const auto r = mechkin_test::RunCli("range " + four_bar + " --steps 300000");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("full turn"), std::string::npos) << r.out;
  // Flat in the steps: under ASan + UBSan 63 MB at 30,000 and at 300,000 steps (2026-12-04).
  EXPECT_LT(ChildPeakMb(), 75) << "peak MB of the range";
  std::printf("range --steps 300000: peak %ld MB\n", ChildPeakMb());
}

}  // namespace
