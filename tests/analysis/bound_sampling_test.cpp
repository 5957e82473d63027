// The default's sampled error bounds (analysis/bound_sampling.hpp): which rows take a
// sample, and what the rows between report. The bounds they give on the piston toward
// its dead centre are checked against the closed form in python/tests/test_error_bounds.py.
#include "analysis/bound_sampling.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace mechkin {
namespace {

constexpr int kOrder = 3;

// Rows (0-based) due for a sample among the first `rows`, with every due row learning
// `measured` against bounds from κ `from_kappa`.
std::vector<int> DueRows(BoundSampler* sampler, int rows, const double* from_kappa, const double* measured) {
  std::vector<int> due;
  for (int row = 0; row < rows; ++row) {
    if (sampler->Due()) {
      due.push_back(row);
      sampler->Learn(from_kappa, measured, kOrder);
    } else {
      double bound[kOrder + 1] = {from_kappa[0], from_kappa[1], from_kappa[2], from_kappa[3]};
      sampler->Apply(5, bound, kOrder);
    }
  }
  return due;
}

TEST(BoundSampling, SamplesEveryEightRowsWhileTheBoundFromKappaFallsShort) {
  BoundSampler sampler;
  const double from_kappa[] = {1e-14, 1e-13, 1e-13, 1e-13};
  const double measured[] = {1e-14, 1e-13, 1e-13, 3e-13};  // the jerk's 3× the bound from κ
  EXPECT_EQ(DueRows(&sampler, 50, from_kappa, measured), (std::vector<int>{16, 24, 32, 40, 48}));
}

TEST(BoundSampling, SamplesEverMoreSparselyWhileTheBoundFromKappaHolds) {
  BoundSampler sampler;
  const double from_kappa[] = {1e-14, 1e-13, 1e-13, 1e-13};
  const double measured[] = {1e-14, 1e-14, 1e-14, 4e-14};  // below half the bound from κ
  EXPECT_EQ(DueRows(&sampler, 1200, from_kappa, measured),
            (std::vector<int>{16, 32, 64, 128, 256, 512, 768, 1024}));  // 16, 32, ... up to 256
}

TEST(BoundSampling, JudgesAgainstTheSmallestBoundFromKappaSinceTheLastSample) {
  // The sampled row's own bound from κ would call its measurement quiet (0.4×), but a row
  // since had a bound from κ 4× lower (a lower one-step κ): the samples stay dense.
  BoundSampler sampler;
  for (int row = 0; row < 16; ++row) ASSERT_FALSE(sampler.Due());
  ASSERT_TRUE(sampler.Due());  // row 16
  const double high[] = {1e-14, 1e-12, 1e-12, 1e-12};
  const double measured[] = {1e-14, 4e-13, 4e-13, 4e-13};
  sampler.Learn(high, measured, kOrder);  // quiet: next at 16 + 16
  int row = 17;
  for (; row < 32; ++row) {
    ASSERT_FALSE(sampler.Due()) << row;
    double bound[] = {1e-14, 2.5e-13, 2.5e-13, 2.5e-13};
    sampler.Apply(5, bound, kOrder);
  }
  ASSERT_TRUE(sampler.Due());             // row 32
  sampler.Learn(high, measured, kOrder);  // 4e-13 against the 2.5e-13 seen: not quiet
  for (row = 33; row < 40; ++row) ASSERT_FALSE(sampler.Due()) << row;
  EXPECT_TRUE(sampler.Due());  // row 40: eight rows on
}

TEST(BoundSampling, RowsBeforeTheFirstSampleKeepTheirBoundsFromKappa) {
  BoundSampler sampler;
  double bound[] = {1e-14, 2e-13, 3e-13, 4e-13};
  ASSERT_FALSE(sampler.Due());
  sampler.Apply(5, bound, kOrder);
  EXPECT_EQ(bound[0], 1e-14);
  EXPECT_EQ(bound[1], 2e-13);
  EXPECT_EQ(bound[2], 3e-13);
  EXPECT_EQ(bound[3], 4e-13);
}

TEST(BoundSampling, RowsBetweenSamplesCarryTheLargerOfTheLastTwoMeasuredBoundsUpToTheCeiling) {
  BoundSampler sampler;
  for (int row = 0; row < 16; ++row) ASSERT_FALSE(sampler.Due());
  const double from_kappa[] = {1e-14, 1e-13, 1e-13, 1e-13};
  const double first[] = {1e-14, 2e-13, 1e-13, 1e-10};
  const double second[] = {1e-14, 1e-13, 5e-13, 1e-10};
  ASSERT_TRUE(sampler.Due());
  sampler.Learn(from_kappa, first, kOrder);
  for (int row = 17; row < 24; ++row) ASSERT_FALSE(sampler.Due());
  ASSERT_TRUE(sampler.Due());
  sampler.Learn(from_kappa, second, kOrder);
  ASSERT_FALSE(sampler.Due());
  const double kappa = 10;
  double bound[] = {1e-14, 1e-13, 1e-13, 1e-13};
  sampler.Apply(kappa, bound, kOrder);
  EXPECT_EQ(bound[0], 1e-14);  // measured no higher than the bound from κ
  EXPECT_EQ(bound[1], 2e-13);  // the first sample's, the larger
  EXPECT_EQ(bound[2], 5e-13);  // the second's
  // The jerk's 1e-10 is above the ceiling 2κ³(e_0 + 8u) = 2.2e-11.
  const double u = std::numeric_limits<double>::epsilon() / 2;
  EXPECT_DOUBLE_EQ(bound[3], 2 * (1e-14 + 8 * u) * kappa * kappa * kappa);
  EXPECT_LT(bound[3], 1e-10);
}

TEST(BoundSampling, ASampledRowReportsItsMeasuredBoundBetweenTheBoundFromKappaAndTheCeiling) {
  const double kappa = 10;
  const double from_kappa[] = {1e-14, 1e-13, 1e-12, 1e-11};
  double measured[] = {1e-15, 2e-13, 5e-13, 1.0};
  BoundSampler::Report(kappa, from_kappa, measured, kOrder);
  const double u = std::numeric_limits<double>::epsilon() / 2;
  EXPECT_EQ(measured[0], 1e-14);  // raised to the bound from κ
  EXPECT_EQ(measured[1], 2e-13);  // as measured: between 1e-13 and 2κ(e_0 + 8u) = 2.4e-13
  EXPECT_EQ(measured[2], 1e-12);  // raised to the bound from κ
  EXPECT_DOUBLE_EQ(measured[3], 2 * (1e-14 + 8 * u) * kappa * kappa * kappa);  // the ceiling
}

}  // namespace
}  // namespace mechkin
