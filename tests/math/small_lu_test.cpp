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

TEST(SmallLU, NonFiniteRightHandSidesGiveTheDenseResult) {
  std::mt19937 rng(11);
  const Eigen::MatrixXd a = SparseMatrix(18, 0.3, &rng);
  Eigen::MatrixXd factors = a;
  SmallLU lu;
  ASSERT_TRUE(lu.Compute(&factors));
  for (double bad : {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(18, 1, 2);
    b[3] = bad;
    Eigen::VectorXd x, x_dense, xt, xt_dense;
    lu.Solve(b, &x);
    lu.DenseSolve(b, &x_dense);
    lu.SolveTranspose(b, &xt);
    lu.DenseSolveTranspose(b, &xt_dense);
    for (int i = 0; i < 18; ++i) {
      EXPECT_EQ(std::isnan(x[i]), std::isnan(x_dense[i])) << i;
      if (!std::isnan(x[i])) {
        EXPECT_EQ(x[i], x_dense[i]) << i;
      }
      EXPECT_EQ(std::isnan(xt[i]), std::isnan(xt_dense[i])) << i;
      if (!std::isnan(xt[i])) {
        EXPECT_EQ(xt[i], xt_dense[i]) << i;
      }
    }
    EXPECT_FALSE(x.allFinite());
  }
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
