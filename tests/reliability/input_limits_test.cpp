// Limits on accepted inputs (issue 24, "Memory limits on accepted inputs"): the JSON
// nesting limit that docs/format.md states (100 levels) is the one the reader
// enforces, and it is checked before the parse allocates anything (a 20 MB file of
// '[' took 4.3 GB and 17 s to report a syntax error).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <string>

#include "analysis/load.hpp"

namespace {

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

}  // namespace
