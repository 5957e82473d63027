// The dense LU's solves over the listed nonzeros (math/small_lu.hpp) give the dense
// substitution's bits, the sign of a zero included, on sparse matrices like a
// mechanism's Jacobian and on right-hand sides with zeros, negative zeros and
// non-finite entries; and both solve the system (residual against the matrix itself).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "math/small_lu.hpp"

namespace mechkin {
namespace small_lu_test {

bool SameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

// A random matrix with about `fill` of its places nonzero and a dominant,
// shuffled diagonal of both signs (row swaps happen, no pivot is small; a zero
// divided by a negative pivot is −0).
Eigen::MatrixXd SparseMatrix(int n, double fill, std::mt19937* rng) {
  std::uniform_real_distribution<double> value(-1, 1), coin(0, 1);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (coin(*rng) < fill) a(i, j) = value(*rng);
      else if (coin(*rng) < 0.2) a(i, j) = -0.0;  // a −0 the factors carry along
  std::vector<int> rows(n);
  for (int i = 0; i < n; ++i) rows[i] = i;
  std::shuffle(rows.begin(), rows.end(), *rng);
  for (int j = 0; j < n; ++j) a(rows[j], j) = (coin(*rng) < 0.5 ? -4 : 4) + value(*rng);
  return a;
}

// b with exact zeros of both signs among random entries.
Eigen::VectorXd RightHandSide(int n, std::mt19937* rng) {
  std::uniform_real_distribution<double> value(-1, 1), coin(0, 1);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const double c = coin(*rng);
    b[i] = c < 0.3 ? 0.0 : c < 0.6 ? -0.0 : value(*rng);
  }
  return b;
}

TEST(SmallLU, ListedSolvesGiveTheDenseBitsAndSolveTheSystem) {
  std::mt19937 rng(7);
  int compared = 0;
  for (int n : {1, 2, 5, 18, 40, 64, 65, 90}) {
    for (double fill : {0.1, 0.3, 1.0}) {
      for (int trial = 0; trial < 40; ++trial) {
        const Eigen::MatrixXd a = SparseMatrix(n, fill, &rng);
        Eigen::MatrixXd factors = a;
        SmallLU lu;
        ASSERT_TRUE(lu.Compute(&factors));
        const Eigen::VectorXd b = RightHandSide(n, &rng);
        Eigen::VectorXd x, x_dense, xt, xt_dense;
        lu.Solve(b, &x);
        lu.DenseSolve(b, &x_dense);
        lu.SolveTranspose(b, &xt);
        lu.DenseSolveTranspose(b, &xt_dense);
        ASSERT_TRUE(SameBits(x, x_dense)) << "n " << n << " fill " << fill << " trial " << trial;
        ASSERT_TRUE(SameBits(xt, xt_dense)) << "n " << n << " fill " << fill << " trial " << trial;
        // Backward-stable: residual within n·u of ‖A‖‖x‖ (1e-14 ≈ 45u, for the growth).
        EXPECT_LE((a * x - b).norm(), 1e-14 * n * (a.norm() * x.norm() + b.norm()));
        EXPECT_LE((a.transpose() * xt - b).norm(), 1e-14 * n * (a.norm() * xt.norm() + b.norm()));
        Eigen::VectorXd aliased = b;  // x may alias b
        lu.Solve(aliased, &aliased);
        ASSERT_TRUE(SameBits(aliased, x_dense));
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 8 * 3 * 40);
}

// The identity's zero below the diagonal, skipped by the listed solve: the dense one
// computes −0 − (0 · −1) = +0, so the result's second entry is +0, not −0.
TEST(SmallLU, ASkippedZeroTermKeepsTheDenseSignOfZero) {
  Eigen::MatrixXd factors = Eigen::MatrixXd::Identity(2, 2);
  SmallLU lu;
  ASSERT_TRUE(lu.Compute(&factors));
  const Eigen::VectorXd b = (Eigen::VectorXd(2) << -1.0, -0.0).finished();
  Eigen::VectorXd x, xt;
  lu.Solve(b, &x);
  EXPECT_EQ(x[0], -1.0);
  EXPECT_EQ(x[1], 0.0);
  EXPECT_FALSE(std::signbit(x[1]));
  lu.SolveTranspose((Eigen::VectorXd(2) << -0.0, -1.0).finished(), &xt);
  EXPECT_FALSE(std::signbit(xt[0]));  // −0 − (0 · −1) in the Lᵀ sum
}

// Both solves against the dense ones, bit for bit, also with x aliasing b.
void ExpectDenseBits(SmallLU& lu, const Eigen::VectorXd& b, const std::string& what) {
  Eigen::VectorXd x, x_dense, xt, xt_dense;
  lu.Solve(b, &x);
  lu.DenseSolve(b, &x_dense);
  lu.SolveTranspose(b, &xt);
  lu.DenseSolveTranspose(b, &xt_dense);
  EXPECT_TRUE(SameBits(x, x_dense)) << what;
  EXPECT_TRUE(SameBits(xt, xt_dense)) << what;
  Eigen::VectorXd aliased = b;
  lu.Solve(aliased, &aliased);
  EXPECT_TRUE(SameBits(aliased, x_dense)) << what << " (aliased)";
  aliased = b;
  lu.SolveTranspose(aliased, &aliased);
  EXPECT_TRUE(SameBits(aliased, xt_dense)) << what << " (aliased, transposed)";
}

TEST(SmallLU, NonFiniteRightHandSidesGiveTheDenseResult) {
  std::mt19937 rng(11);
  const Eigen::MatrixXd a = SparseMatrix(18, 0.3, &rng);
  Eigen::MatrixXd factors = a;
  SmallLU lu;
  ASSERT_TRUE(lu.Compute(&factors));
  for (double bad : {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(18, 1, 2);
    b[3] = bad;
    ExpectDenseBits(lu, b, "b[3] = " + std::to_string(bad));
    Eigen::VectorXd x;
    lu.Solve(b, &x);
    EXPECT_FALSE(x.allFinite());
  }
}

// 1e300 / 1e-300 overflows to ∞ from finite data; the dense solve then makes the
// first entry 1 − 0·∞ = NaN, which the skipped term would not.
TEST(SmallLU, AnOverflowGivesTheDenseResult) {
  Eigen::MatrixXd factors = Eigen::MatrixXd::Identity(2, 2);
  factors(1, 1) = 1e-300;
  SmallLU lu;
  ASSERT_TRUE(lu.Compute(&factors));
  const Eigen::VectorXd b = (Eigen::VectorXd(2) << 1.0, 1e300).finished();
  ExpectDenseBits(lu, b, "overflow");
  Eigen::VectorXd x;
  lu.Solve(b, &x);
  EXPECT_TRUE(std::isnan(x[0]));
  EXPECT_TRUE(std::isinf(x[1]));
}

// 0 − 0.25 · 5e-324 is +0 rounded apart; fused into one multiply-add it would be −0
// on a row the tracking does not watch, and the next skipped term would keep it −0
// where the dense solve makes +0. Fails in a build that contracts a − l·y.
TEST(SmallLU, ATinyProductRoundedApartKeepsTheDenseBits) {
  Eigen::MatrixXd factors = Eigen::MatrixXd::Identity(3, 3);
  factors(2, 0) = 0.25;
  SmallLU lu;
  ASSERT_TRUE(lu.Compute(&factors));
  const Eigen::VectorXd b = (Eigen::VectorXd(3) << 5e-324, -1.0, 0.0).finished();
  ExpectDenseBits(lu, b, "subnormal");
  Eigen::VectorXd x;
  lu.Solve(b, &x);
  EXPECT_FALSE(std::signbit(x[2]));
}

// The edges of the bit masks: no unknowns, and 64 (row and column 63 used, −0 in b).
TEST(SmallLU, EmptyAndSixtyFourUnknowns) {
  Eigen::MatrixXd empty(0, 0);
  SmallLU lu;
  ASSERT_TRUE(lu.Compute(&empty));
  Eigen::VectorXd x;
  lu.Solve(Eigen::VectorXd(0), &x);
  EXPECT_EQ(x.size(), 0);
  std::mt19937 rng(13);
  Eigen::MatrixXd factors = SparseMatrix(64, 0.1, &rng);
  factors(63, 0) = 0.5;
  factors(0, 63) = -0.5;
  ASSERT_TRUE(lu.Compute(&factors));
  Eigen::VectorXd b = RightHandSide(64, &rng);
  b[63] = -0.0;
  ExpectDenseBits(lu, b, "n = 64");
}

TEST(SmallLU, AZeroPivotIsRefused) {
  Eigen::Matrix2d singular;
  singular << 1, 2, 2, 4;
  Eigen::MatrixXd factors = singular;
  SmallLU lu;
  EXPECT_FALSE(lu.Compute(&factors));
}

}  // namespace small_lu_test
}  // namespace mechkin
