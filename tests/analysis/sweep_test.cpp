// Sweeps (issue "Parametric designs", item 6): the grid's order, variants that do
// not assemble reported as such, summaries against the four-bar's closed form,
// and shards that merge into exactly the unsharded result.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "analysis/sweep.hpp"
#include "io/sweep_writer.hpp"

namespace mechkin {
namespace sweep_test {

Model FourBar() {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json");
  EXPECT_TRUE(r.ok());
  return std::move(*r.model);
}

TEST(Sweep, GridIsRowMajorLastAxisFastest) {
  GridAxis a, b;
  std::string why;
  ASSERT_TRUE(ParseGridAxis("a=30:50:3", &a, &why));
  ASSERT_TRUE(ParseGridAxis("b=100:140:2", &b, &why));
  const auto v = GridVariants({a, b});
  ASSERT_EQ(v.size(), 6u);
  EXPECT_EQ(v[0].at("a"), 30);
  EXPECT_EQ(v[1].at("b"), 140);
  EXPECT_EQ(v[2].at("a"), 40);
  EXPECT_EQ(v[5].at("a"), 50);
  EXPECT_FALSE(ParseGridAxis("a=30:50", &a, &why));
  EXPECT_NE(why.find("NAME=FROM:TO:COUNT"), std::string::npos);
}

// Rocker angle of the open four-bar (a, b, c, d) at crank angle θ (closed form).
double RockerAngle(double a, double b, double c, double d, double th) {
  const double xb = a * std::cos(th), yb = a * std::sin(th);
  const double e = std::hypot(xb - d, yb), beta = std::atan2(yb, xb - d);
  return beta - std::acos((c * c + e * e - b * b) / (2 * c * e));
}

TEST(Sweep, SummariesMatchTheClosedFormAndFailuresAreReported) {
  const Model model = FourBar();
  // b = 5: the coupler cannot reach (b + c < |BD|): no design pose.
  const std::vector<ParameterOverrides> variants = {{{"a", 40}, {"b", 120}}, {{"a", 40}, {"b", 5}}};
  SweepOptions options;
  options.request.order = 0;
  const SweepResult r = RunSweep(model, variants, options);
  ASSERT_EQ(r.variants.size(), 2u);
  EXPECT_EQ(r.variants[0].status, "complete");
  EXPECT_EQ(r.variants[1].status, "invalid");
  EXPECT_NE(r.variants[1].message.find("/parameters/psi"), std::string::npos) << r.variants[1].message;
  // min/max of the rocker angle over the 73 rows: joint D turns ground (body2) relative to
  // the rocker (body1), so the column is −(φ − φ0) in degrees.
  const double start = 60 * M_PI / 180, phi0 = RockerAngle(40, 120, 80, 100, start);
  double lo = 1e9, hi = -1e9;
  for (int k = 0; k <= 72; ++k) {
    const double phi =
        -std::remainder(RockerAngle(40, 120, 80, 100, start + 2 * M_PI * k / 72) - phi0, 2 * M_PI) * 180 / M_PI;
    lo = std::min(lo, phi), hi = std::max(hi, phi);
  }
  ASSERT_EQ(r.columns.front(), "rocker_angle [deg]");
  EXPECT_NEAR(r.variants[0].min[0], lo, 1e-8);
  EXPECT_NEAR(r.variants[0].max[0], hi, 1e-8);
}

TEST(Sweep, FourShardsMergeIntoTheUnshardedResultExactly) {
  const Model model = FourBar();
  std::string why;
  const auto variants = SampleVariants(model, 40, 3, &why);
  ASSERT_EQ(variants.size(), 40u);
  SweepOptions options;
  options.threads = 2;
  const std::string whole = SweepJson(RunSweep(model, variants, options)).dump();
  std::vector<std::string> files;
  for (int s = 1; s <= 4; ++s) {
    options.shard = s, options.shards = 4;
    files.push_back(::testing::TempDir() + "/shard" + std::to_string(s) + ".json");
    std::ofstream(files.back()) << SweepJson(RunSweep(model, variants, options)).dump();
  }
  SweepResult merged;
  ASSERT_TRUE(MergeSweepFiles(files, &merged, &why)) << why;
  EXPECT_EQ(SweepJson(merged).dump(), whole);
  int statuses_not_complete = 0;
  for (const auto& v : merged.variants) statuses_not_complete += v.status != "complete";
  EXPECT_GT(statuses_not_complete, 0);  // the sampled ranges include failing designs
  files.erase(files.begin() + 1);
  EXPECT_FALSE(MergeSweepFiles(files, &merged, &why));
  EXPECT_NE(why.find("missing shards: 2/4"), std::string::npos) << why;
}

// Issue 31, flat memory: a shard's samples and grid variants are made as they are
// asked for, not listed. They must equal the listed ones (SampleVariants /
// GridVariants at the shard's indices) in any order of asking: ascending as the
// threads ask, descending and far behind (the stream restarts), and repeated.
TEST(Sweep, ShardVariantsMadeOnDemandEqualTheListedOnes) {
  const Model model = FourBar();
  std::string why;
  const int count = 3000, shard = 2, shards = 3;
  const auto listed = SampleVariants(model, count, 7, &why);
  const ShardVariants samples = SampleShard(model, count, 7, shard, shards, &why);
  ASSERT_EQ(samples.size(), 1000u) << why;
  std::vector<size_t> order;
  for (size_t k = 0; k < samples.size(); ++k) order.push_back(k);
  for (size_t k = samples.size(); k-- > 0;) order.push_back(k);
  order.insert(order.end(), {5, 999, 0, 5, 500, 499, 998});
  for (size_t k : order) {
    ASSERT_EQ(samples.Index(k), shard - 1 + static_cast<int>(k) * shards);
    EXPECT_EQ(samples.Variant(k), listed[samples.Index(k)]) << "sample " << k;
  }
  const std::vector<GridAxis> axes = {{"a", 30, 50, 7}, {"b", 100, 140, 11}};
  const auto grid_listed = GridVariants(axes);
  const ShardVariants grid = GridShard(axes, 3, 4);
  ASSERT_EQ(grid.size(), 19u);  // indices 2, 6, ..., 74 of 77
  for (size_t k = 0; k < grid.size(); ++k) EXPECT_EQ(grid.Variant(k), grid_listed[grid.Index(k)]) << "grid " << k;
  ShardVariants added;
  added.parameters = {"a"};
  added.Add(4, {{"a", 1.0}});
  added.Add(7, {{"a", 2.0}});
  EXPECT_THROW(added.Add(9, {{"a", 3.0}}), std::invalid_argument);  // not 4 + 2·3
  EXPECT_EQ(added.Variant(1).at("a"), 2.0);
}

// Issue 23 item 9, the sweep: the crank = rod slider-crank (L = 19, 20, 21 mm, no
// offset, 100 steps; the change point at t = 0.25 s on a row) stops there as
// `singular` at every order 0–4 — never `complete` — with the 25 rows before it
// on the closed form x = 2L·cos 2πt (its minimum at the last row, t = 0.24 s).
class SweepCrankEqualsRod : public ::testing::TestWithParam<int> {};

TEST_P(SweepCrankEqualsRod, IsSingularAtTheChangePointAtEveryOrder) {
  LoadResult loaded = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/tests/data/parametric-crank-equals-rod.json");
  ASSERT_TRUE(loaded.ok());
  SweepOptions options;
  options.request.order = GetParam();
  options.threads = 1;
  const SweepResult r = RunSweep(*loaded.model, {{{"L", 19}}, {{"L", 20}}, {{"L", 21}}}, options);
  ASSERT_EQ(r.variants.size(), 3u);
  ASSERT_EQ(r.columns.front(), "piston.x [mm]");
  for (const VariantSummary& v : r.variants) {
    const double L = v.values[0];
    EXPECT_EQ(v.status, "singular") << L << ": " << v.message;
    EXPECT_EQ(v.message.rfind("singular position at t = 0.25 s", 0), 0u) << v.message;
    EXPECT_EQ(v.rows, 25) << L;
    EXPECT_NEAR(v.t_stop, 0.24, 1e-12) << L;
    EXPECT_NEAR(v.min[0], 2 * L * std::cos(2 * M_PI * 0.24), 1e-9) << L;
    EXPECT_NEAR(v.max[0], 2 * L, 1e-9) << L;
  }
  // The unit of work the Python binding calls says the same.
  const VariantSummary one = RunVariant(*loaded.model, {{"L", 20}}, options);
  EXPECT_EQ(one.status, "singular") << one.message;
  EXPECT_EQ(one.rows, 25);
}

INSTANTIATE_TEST_SUITE_P(Orders, SweepCrankEqualsRod, ::testing::Values(0, 1, 2, 3, 4));

}  // namespace
}  // namespace mechkin
