// Issue 24, `sweep --merge` under damaged shards: every field read is validated
// (a `min` list longer than `max` read past a heap buffer), and a variant
// missing, duplicated or out of range is named. Run against the real executable.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"

namespace sweep_merge_test {

using nlohmann::json;
const std::string kSlider = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-slider-crank.json";

using Result = mechkin_test::CliResult;
Result Mechkin(const std::string& args) { return mechkin_test::RunCli(args); }

std::string Dir() {
  static std::string d = [] {
    std::string t = ::testing::TempDir() + "/mechkin-merge-XXXXXX";
    return std::string(::mkdtemp(t.data()));
  }();
  return d;
}

std::string Read(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Shards 1/2 and 2/2 of a 6-variant grid (written once), their paths.
const std::pair<std::string, std::string>& Shards() {
  static const std::pair<std::string, std::string> shards = [] {
    const std::string a = Dir() + "/a.json", b = Dir() + "/b.json";
    const std::string grid = " --grid crank=30:50:3 --grid rod=110:130:2 --format json -o ";
    EXPECT_EQ(Mechkin("sweep " + kSlider + grid + a + " --shard 1/2").code, 0);
    EXPECT_EQ(Mechkin("sweep " + kSlider + grid + b + " --shard 2/2").code, 0);
    return std::make_pair(a, b);
  }();
  return shards;
}

// Shard 2/2 changed by `edit`, merged with shard 1/2: the result.
Result MergeEdited(const std::string& name, const std::function<void(json&)>& edit) {
  json doc = json::parse(Read(Shards().second));
  edit(doc);
  const std::string edited = Dir() + "/" + name + ".json";
  std::ofstream(edited) << doc.dump(1);
  return Mechkin("sweep --merge " + Shards().first + " " + edited + " -o " + Dir() + "/" + name + ".csv");
}

TEST(SweepMerge, IntactShardsMergeIntoTheUnshardedSweep) {
  const Result r = Mechkin("sweep --merge " + Shards().first + " " + Shards().second + " -o " + Dir() + "/merged.csv");
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_EQ(Mechkin("sweep " + kSlider + " --grid crank=30:50:3 --grid rod=110:130:2 -o " + Dir() + "/whole.csv").code, 0);
  EXPECT_EQ(Read(Dir() + "/merged.csv"), Read(Dir() + "/whole.csv"));
}

TEST(SweepMerge, AMinListLongerThanMaxIsAnErrorNamingTheFileAndField) {
  const Result r = MergeEdited("long-min", [](json& d) { d["variants"][1]["min"].push_back(1.5); });
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("long-min.json"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("/variants/1/min: has "), std::string::npos) << r.out;
  EXPECT_FALSE(std::ifstream(Dir() + "/long-min.csv").good()) << "nothing written";
  const Result shorter = MergeEdited("short-max", [](json& d) { d["variants"][0]["max"].erase(0); });
  EXPECT_EQ(shorter.code, 1) << shorter.out;
  EXPECT_NE(shorter.out.find("/variants/0/max: has "), std::string::npos) << shorter.out;
}

TEST(SweepMerge, EveryFieldIsValidated) {
  const std::vector<std::pair<std::function<void(json&)>, std::string>> cases = {
      {[](json& d) { d["variants"][0]["values"].erase(0); }, "/variants/0/values: has 1 entries"},
      {[](json& d) { d["variants"][0]["rows"] = "many"; }, "/variants/0/rows: expected an integer"},
      {[](json& d) { d["variants"][0]["rows"] = 1e300; }, "/variants/0/rows: expected an integer"},
      {[](json& d) { d["variants"][0]["status"] = 3; }, "/variants/0/status: expected a string"},
      {[](json& d) { d["variants"][0].erase("t_stop"); }, "/variants/0/t_stop: missing"},
      {[](json& d) { d["variants"][0]["min"][0] = "x"; }, "/variants/0/min/0: expected a number or null"},
      {[](json& d) { d["columns"] = 7; }, "/columns: expected a list of names"},
      {[](json& d) { d["shard"] = 3; }, "/shard: 3 is outside 1..2"},
      {[](json& d) { d["variants"][0]["variant"] = 99; }, "/variants/0/variant: 99 is outside 0..5"},
      {[](json& d) { d["variants"][0]["variant"] = 2; }, "/variants/0/variant: 2 does not belong to shard 2/2"},
  };
  for (size_t k = 0; k < cases.size(); ++k) {
    const Result r = MergeEdited("field-" + std::to_string(k), cases[k].first);
    EXPECT_EQ(r.code, 1) << cases[k].second << "\n" << r.out;
    EXPECT_NE(r.out.find("field-" + std::to_string(k) + ".json"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(cases[k].second), std::string::npos) << r.out;
  }
}

TEST(SweepMerge, MissingAndDuplicatedVariantsAreNamed) {
  // Shard 2/2 holds variants 1, 3, 5.
  const Result deleted = MergeEdited("deleted", [](json& d) { d["variants"].erase(1); });
  EXPECT_EQ(deleted.code, 1) << deleted.out;
  EXPECT_NE(deleted.out.find("missing variants: 3 (of 0..5)"), std::string::npos) << deleted.out;
  const Result twice = MergeEdited("twice", [](json& d) { d["variants"][1] = d["variants"][0]; });
  EXPECT_EQ(twice.code, 1) << twice.out;
  EXPECT_NE(twice.out.find("variants given twice: 1; missing variants: 3"), std::string::npos) << twice.out;
}

}  // namespace

namespace sweep_merge_test {

// Issue 24, limits up front: a count beyond a stated limit is an argument error
// (exit 2) naming the limit, before any variant, sample or step is made.
TEST(SweepLimits, AGridBeyondTheVariantLimitIsAnArgumentError) {
  for (const char* grid : {" --grid crank=30:50:1000000 --grid rod=100:140:1000000",  // 1e12
                           " --grid crank=30:50:10001 --grid rod=100:140:10000"}) {  // 1e8 + 1e4
    const Result r = Mechkin("sweep " + kSlider + grid + " --shard 1/10000");
    EXPECT_EQ(r.code, 2) << grid << "\n" << r.out;
    EXPECT_NE(r.out.find("limit of 100000000 variants"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("internal error"), std::string::npos) << r.out;
  }
}

TEST(SweepLimits, SamplesMonteCarloAndStepsBeyondTheirLimitsAreArgumentErrors) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"sweep " + kSlider + " --samples 100000001", "--samples: the sweep's sample count must be a whole number from 1 to 100000000"},
      {"sweep " + kSlider + " --samples 1e12", "--samples"},
      {"tolerance " + kSlider + " --monte-carlo 100000001", "--monte-carlo: the Monte-Carlo sample count must be a whole number from 0 to 100000000"},
      {"range " + kSlider + " --steps 10000001", "--steps: the range's steps per direction must be a whole number from 4 to 10000000"},
  };
  for (const auto& [args, limit] : cases) {
    const Result r = Mechkin(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.out;
    EXPECT_NE(r.out.find(limit), std::string::npos) << args << "\n" << r.out;
  }
}

}  // namespace

namespace sweep_merge_test {

// A shard makes its own variants only: the 1e8-variant grid's 1/100000 share runs
// in a few MB (it took 4.5 GB when every variant was made first). RUSAGE_CHILDREN
// is the largest child of this test process (ctest runs each test alone).
TEST(SweepLimits, AShardOfAHugeGridMakesOnlyItsOwnVariants) {
  const std::string out = Dir() + "/huge-shard.csv";
  const Result r = Mechkin("sweep " + kSlider + " --grid crank=30:50:10000 --grid rod=110:130:10000 --shard 3/100000 -o " + out);
  ASSERT_EQ(r.code, 0) << r.out;
  rusage usage {};
  ASSERT_EQ(::getrusage(RUSAGE_CHILDREN, &usage), 0);
  EXPECT_LT(usage.ru_maxrss, 200 * 1024) << "peak KB of the sweep";
  std::istringstream rows(Read(out));
  std::string header, first;
  std::getline(rows, header);
  std::getline(rows, first);
  // Variant 2 of the row-major grid: crank = 30 (first axis, digit 0), rod = 110 + 20*2/9999.
  char expected[128];
  std::snprintf(expected, sizeof expected, "2,30,%.17g,", 110 + (130.0 - 110) * 2 / 9999);
  EXPECT_EQ(first.rfind(expected, 0), 0u) << first << " vs " << expected;
}

TEST(SweepLimits, ShardedSamplesMergeIntoTheUnshardedSweep) {
  std::string files;
  for (int s = 1; s <= 3; ++s) {
    const std::string f = Dir() + "/samples-" + std::to_string(s) + ".json";
    ASSERT_EQ(Mechkin("sweep " + kSlider + " --samples 11 --seed 5 --format json --shard " + std::to_string(s) + "/3 -o " + f).code, 0);
    files += " " + f;
  }
  ASSERT_EQ(Mechkin("sweep --merge" + files + " -o " + Dir() + "/samples-merged.csv").code, 0);
  ASSERT_EQ(Mechkin("sweep " + kSlider + " --samples 11 --seed 5 -o " + Dir() + "/samples-whole.csv").code, 0);
  EXPECT_EQ(Read(Dir() + "/samples-merged.csv"), Read(Dir() + "/samples-whole.csv"));
}

}  // namespace

namespace sweep_merge_test {

// Shards carry their sweep's identity: merging shards of different sweeps (another
// grid of the same size, another version of the file, other --set or --tol) is refused.
TEST(SweepMerge, ShardsOfDifferentSweepsAreRefused) {
  const std::string copy = Dir() + "/copy.json", edited = Dir() + "/edited.json";
  std::ofstream(copy) << Read(kSlider);
  std::ofstream(edited) << Read(kSlider) << "\n";  // another version: one more byte
  const std::string grid = " --grid crank=30:50:3 --grid rod=110:130:2 --format json --shard 2/2 -o ";
  const std::vector<std::pair<std::string, std::string>> others = {
      {copy + " --grid crank=30:50:3 --grid rod=110:131:2 --format json --shard 2/2", "grid"},
      {edited + grid.substr(0, grid.size() - 4), "file_fnv1a"},
      {copy + grid.substr(0, grid.size() - 4) + " --set offset=12", "set"},
      {copy + grid.substr(0, grid.size() - 4) + " --tol 1e-9", "tolerance"},
  };
  for (size_t k = 0; k < others.size(); ++k) {
    const std::string shard = Dir() + "/other-" + std::to_string(k) + ".json";
    ASSERT_EQ(Mechkin("sweep " + others[k].first + " -o " + shard).code, 0) << others[k].first;
    const Result r = Mechkin("sweep --merge " + Shards().first + " " + shard);
    EXPECT_EQ(r.code, 1) << others[k].first << "\n" << r.out;
    EXPECT_NE(r.out.find("is a shard of another sweep"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("they differ in: " + others[k].second), std::string::npos) << r.out;
  }
}

}  // namespace
