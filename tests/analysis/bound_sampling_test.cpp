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
constexpr double kU = std::numeric_limits<double>::epsilon() / 2;
using Row = BoundSampler::Row;

// Rows (0-based) due for a sample among the first `rows`, every due row learning
// `measured` (as a `kind` row) against bounds from κ `from_kappa`.
std::vector<int> DueRows(BoundSampler* sampler, int rows, const double* from_kappa, const double* measured,
                         Row kind = Row::Sampled) {
  std::vector<int> due;
  for (int row = 0; row < rows; ++row) {
    if (sampler->Due()) {
      due.push_back(row);
      sampler->Learn(from_kappa, measured, kOrder, kind);
    } else {
      double bound[kOrder + 1] = {from_kappa[0], from_kappa[1], from_kappa[2], from_kappa[3]};
      sampler->RaiseUnsampled(5, bound, kOrder);
    }
  }
  return due;
}

// Takes rows up to and including the next due one, and learns `measured` there.
void SampleNext(BoundSampler* sampler, const double* from_kappa, const double* measured) {
  while (!sampler->Due()) {
  }
  sampler->Learn(from_kappa, measured, kOrder, Row::Sampled);
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

TEST(BoundSampling, RowsMeasuredWholeNeverLengthenTheInterval) {
  BoundSampler sampler;
  const double from_kappa[] = {1e-14, 1e-13, 1e-13, 1e-13};
  const double measured[] = {1e-14, 1e-14, 1e-14, 4e-14};  // quiet, but near a singular position
  EXPECT_EQ(DueRows(&sampler, 50, from_kappa, measured, Row::MeasuredWhole), (std::vector<int>{16, 24, 32, 40, 48}));
}

TEST(BoundSampling, ARowMeasuredWholeBeforeRowSixteenDoesNotStartTheSamplesEarly) {
  BoundSampler sampler;
  const double from_kappa[] = {1e-14, 1e-13, 1e-13, 1e-13};
  const double measured[] = {1e-14, 1e-13, 1e-13, 3e-13};
  ASSERT_FALSE(sampler.Due());  // row 0
  ASSERT_FALSE(sampler.Due());  // row 1, measured whole
  sampler.Learn(from_kappa, measured, kOrder, Row::MeasuredWhole);
  for (int row = 2; row < 16; ++row) EXPECT_FALSE(sampler.Due()) << row;
  EXPECT_TRUE(sampler.Due());  // row 16
}

TEST(BoundSampling, JudgesAgainstTheSmallestBoundFromKappaSinceTheLastSample) {
  // The sampled row's own bound from κ would call its measurement quiet (0.4×), but a row
  // since had a bound from κ 4× lower (a lower one-step κ): the samples stay dense.
  BoundSampler sampler;
  for (int row = 0; row < 16; ++row) ASSERT_FALSE(sampler.Due());
  ASSERT_TRUE(sampler.Due());  // row 16
  const double high[] = {1e-14, 1e-12, 1e-12, 1e-12};
  const double measured[] = {1e-14, 4e-13, 4e-13, 4e-13};
  sampler.Learn(high, measured, kOrder, Row::Sampled);  // quiet: next at 16 + 16
  int row = 17;
  for (; row < 32; ++row) {
    ASSERT_FALSE(sampler.Due()) << row;
    double bound[] = {1e-14, 2.5e-13, 2.5e-13, 2.5e-13};
    sampler.RaiseUnsampled(5, bound, kOrder);
  }
  ASSERT_TRUE(sampler.Due());                           // row 32
  sampler.Learn(high, measured, kOrder, Row::Sampled);  // 4e-13 against the 2.5e-13 seen: not quiet
  for (row = 33; row < 40; ++row) ASSERT_FALSE(sampler.Due()) << row;
  EXPECT_TRUE(sampler.Due());  // row 40: eight rows on
}

TEST(BoundSampling, RowsBeforeTheFirstSampleKeepTheirBoundsFromKappa) {
  BoundSampler sampler;
  for (int row = 0; row < 16; ++row) {
    double bound[] = {1e-14, 2e-13, 3e-13, 4e-13};
    ASSERT_FALSE(sampler.Due());
    sampler.RaiseUnsampled(5, bound, kOrder);
    EXPECT_EQ(bound[0], 1e-14);
    EXPECT_EQ(bound[1], 2e-13);
    EXPECT_EQ(bound[2], 3e-13);
    EXPECT_EQ(bound[3], 4e-13);
  }
}

TEST(BoundSampling, RowsBetweenSamplesCarryTheLargerOfTheLastTwoMeasuredBoundsUpToTheCeiling) {
  BoundSampler sampler;
  const double from_kappa[] = {1e-14, 1e-13, 1e-13, 1e-13};
  const double first[] = {1e-14, 2e-13, 1e-13, 1e-10};
  const double second[] = {1e-14, 1e-13, 5e-13, 1e-10};
  SampleNext(&sampler, from_kappa, first);
  SampleNext(&sampler, from_kappa, second);
  ASSERT_FALSE(sampler.Due());
  const double kappa = 10;
  double bound[] = {1e-14, 1e-13, 1e-13, 1e-13};
  sampler.RaiseUnsampled(kappa, bound, kOrder);
  EXPECT_EQ(bound[0], 1e-14);  // measured no higher than the bound from κ
  EXPECT_EQ(bound[1], 2e-13);  // the first sample's, the larger
  EXPECT_EQ(bound[2], 5e-13);  // the second's
  // The jerk's 1e-10 is above the ceiling 2κ³(e_0 + 8u) = 2.2e-11.
  EXPECT_DOUBLE_EQ(bound[3], 2 * (1e-14 + 8 * kU) * kappa * kappa * kappa);
  // A third sample: the first one's velocity bound is no longer carried.
  const double third[] = {1e-14, 1e-13, 1e-13, 1e-13};
  SampleNext(&sampler, from_kappa, third);
  double next[] = {1e-14, 1e-13, 1e-13, 1e-13};
  sampler.RaiseUnsampled(kappa, next, kOrder);
  EXPECT_EQ(next[1], 1e-13);
  EXPECT_EQ(next[2], 5e-13);  // the second's, still one of the last two
}

TEST(BoundSampling, TheCeilingIsTheRowsOwnPositionBoundFromKappaNotTheCarriedOne) {
  // A carried position bound above the row's own must not lift the derivatives' ceiling
  // (RaiseUnsampled goes from the top order down for that).
  BoundSampler sampler;
  const double from_kappa[] = {1e-14, 1e-13, 1e-13, 1e-13};
  const double measured[] = {1e-12, 1e-10, 1e-10, 1e-10};  // far above every ceiling
  SampleNext(&sampler, from_kappa, measured);
  ASSERT_FALSE(sampler.Due());
  const double kappa = 10;
  double bound[] = {1e-14, 1e-13, 1e-13, 1e-13};
  sampler.RaiseUnsampled(kappa, bound, kOrder);
  const double e0 = 1e-14 + 8 * kU;
  EXPECT_DOUBLE_EQ(bound[0], 2 * e0);
  EXPECT_DOUBLE_EQ(bound[1], 2 * e0 * kappa);
  EXPECT_DOUBLE_EQ(bound[2], 2 * e0 * kappa * kappa);
  EXPECT_DOUBLE_EQ(bound[3], 2 * e0 * kappa * kappa * kappa);
}

TEST(BoundSampling, ASampledRowReportsItsMeasuredBoundBetweenTheBoundFromKappaAndTheCeiling) {
  const double kappa = 10;
  const double from_kappa[] = {1e-14, 1e-13, 1e-12, 1e-11};
  double measured[] = {1e-15, 2e-13, 5e-13, 1.0};
  BoundSampler::ClampSampled(kappa, from_kappa, measured, kOrder);
  EXPECT_EQ(measured[0], 1e-14);  // raised to the bound from κ
  EXPECT_EQ(measured[1], 2e-13);  // as measured: between 1e-13 and 2κ(e_0 + 8u) = 2.2e-13
  EXPECT_EQ(measured[2], 1e-12);  // raised to the bound from κ
  EXPECT_DOUBLE_EQ(measured[3], 2 * (1e-14 + 8 * kU) * kappa * kappa * kappa);  // the ceiling
}

TEST(BoundSampling, ANanOrZeroIsNeverQuiet) {
  BoundSampler sampler;
  const double zero_from_kappa[] = {1e-14, 0, 1e-13, 1e-13};
  const double measured[] = {1e-14, 0, 0, 0};
  EXPECT_EQ(DueRows(&sampler, 40, zero_from_kappa, measured), (std::vector<int>{16, 24, 32}));
  BoundSampler nan_sampler;
  const double from_kappa[] = {1e-14, 1e-13, 1e-13, 1e-13};
  const double nan_measured[] = {1e-14, std::numeric_limits<double>::quiet_NaN(), 0, 0};
  EXPECT_EQ(DueRows(&nan_sampler, 40, from_kappa, nan_measured), (std::vector<int>{16, 24, 32}));
}

}  // namespace
}  // namespace mechkin
