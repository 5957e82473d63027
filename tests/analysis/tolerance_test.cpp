// Tolerance stack-up (issue "Parametric designs", item 5): the linear worst-case
// and RSS envelopes from the exact sensitivities against a Monte-Carlo of 10,000
// variants of the offset slider-crank (crank ±0.05, rod ±0.05, offset ±0.1 mm),
// each parameter uniform within its tolerance.
//
// Expected agreement: the linearisation error is second order, (τ/L)·(linear) ≈
// 0.1/40 = 0.25 % of the envelope; the standard deviation of 10,000 samples has a
// relative sampling error 1/√(2N) = 0.7 % (1σ). The bounds: largest deviation within
// [85 %, 100.5 %] of the worst case (a sum of three uniform terms reaches its corner
// region in 10,000 draws), largest std within 3 % (≈ 4σ) of RSS/√3.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/tolerance.hpp"
#include "analysis/load.hpp"

namespace mechkin {
namespace tolerance_test {

TEST(Tolerance, LinearEnvelopesMatchMonteCarlo) {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-slider-crank.json");
  ASSERT_TRUE(r.ok());
  ToleranceOptions options;
  options.monte_carlo = 10000;
  options.seed = 7;
  const ToleranceReport rep = AnalyzeTolerances(*r.model, options);
  ASSERT_TRUE(rep.ok) << rep.message;
  EXPECT_EQ(rep.samples, 10000);
  EXPECT_EQ(rep.failed_samples, 0);
  ASSERT_EQ(rep.parameters.size(), 3u);
  int checked = 0;
  for (const auto& c : rep.columns) {
    if (c.max_worst_case < 1e-9) continue;  // piston.z: planar, no deviation at all
    ++checked;
    EXPECT_LE(c.mc_max_deviation, 1.005 * c.max_worst_case) << c.name;
    EXPECT_GE(c.mc_max_deviation, 0.85 * c.max_worst_case) << c.name;
    EXPECT_NEAR(c.mc_max_std, c.max_rss / std::sqrt(3.0), 0.03 * c.max_rss / std::sqrt(3.0)) << c.name;
  }
  EXPECT_EQ(checked, 3);  // piston.x, piston.y, stroke
}

// Seeded means reproducible to the last bit: the same report on 1, 2 and 3 threads
// (the Monte-Carlo sums run in fixed chunks, added in a fixed order).
TEST(Tolerance, MonteCarloIsTheSameOnAnyNumberOfThreads) {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-slider-crank.json");
  ASSERT_TRUE(r.ok());
  ToleranceOptions options;
  options.monte_carlo = 300;
  options.seed = 11;
  std::vector<double> first;
  for (int threads : {1, 2, 3}) {
    options.threads = threads;
    const ToleranceReport rep = AnalyzeTolerances(*r.model, options);
    ASSERT_TRUE(rep.ok) << rep.message;
    std::vector<double> stats;
    for (const auto& c : rep.columns) stats.insert(stats.end(), {c.mc_max_deviation, c.mc_max_std, c.t_mc_std});
    if (first.empty()) first = stats;
    for (size_t k = 0; k < stats.size(); ++k) EXPECT_EQ(stats[k], first[k]) << threads << " threads, statistic " << k;
  }
}

// piston.y = offset exactly: its worst case is the offset's tolerance, all of it.
TEST(Tolerance, OffsetAloneMovesThePistonLine) {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-slider-crank.json");
  ASSERT_TRUE(r.ok());
  const ToleranceReport rep = AnalyzeTolerances(*r.model, ToleranceOptions{});
  ASSERT_TRUE(rep.ok);
  int found = 0;
  for (const auto& c : rep.columns)
    if (c.name == "piston.y") {
      ++found;
      EXPECT_NEAR(c.max_worst_case, 0.1, 1e-9);
      EXPECT_EQ(c.contributions.front().first, "offset");
      EXPECT_NEAR(c.contributions[1].second, 0, 1e-9);
    }
  EXPECT_EQ(found, 1);
}

TEST(Tolerance, FileWithoutTolerancesIsExplained) {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/offset-slider-crank.json");
  ASSERT_TRUE(r.ok());
  const ToleranceReport rep = AnalyzeTolerances(*r.model, ToleranceOptions{});
  EXPECT_FALSE(rep.ok);
  EXPECT_NE(rep.message.find("no parameter declares a tolerance"), std::string::npos);
}

}  // namespace
}  // namespace mechkin
