// The sparse rank-revealing QR against the dense greedy rule and closed facts:
// same independent rows, J x = b with minimum norm, dependent rows rebuilt from
// the independent ones, null space annihilated by J.
#include <gtest/gtest.h>

#include <random>

#include "kinematics/position.hpp"
#include "kinematics/sparse_rank.hpp"

namespace mechkin {
namespace sparse_rank_test {

// m × n sparse matrix with a few nonzeros per row; row `copy_of[k]` ≥ 0 makes row k
// a combination of two earlier rows (a redundant equation).
Eigen::MatrixXd BandedWithDependentRows(int m, int n, unsigned seed, std::vector<int>* expected_dependent) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, n);
  for (int r = 0; r < m; ++r) {
    if (r > 4 && r % 5 == 3) {  // 1.5 × an earlier row − 0.5 × another
      J.row(r) = 1.5 * J.row(r - 2) - 0.5 * J.row(r - 3);
      expected_dependent->push_back(r);
      continue;
    }
    const int c0 = (r * n) / m;
    for (int c = c0; c < std::min(n, c0 + 4); ++c) J(r, c) = u(rng);
  }
  return J;
}

TEST(SparseRowRank, AgreesWithTheDenseGreedyRule) {
  std::vector<int> expected;
  const Eigen::MatrixXd J = BandedWithDependentRows(60, 80, 7, &expected);
  std::vector<int> dense_dependent;
  const std::vector<int> dense_kept = IndependentRows(J, 1e-7, &dense_dependent);
  const SparseRowRank rr(J.sparseView());
  ASSERT_TRUE(rr.ok());
  EXPECT_EQ(rr.dependent(), expected);
  EXPECT_EQ(rr.dependent(), dense_dependent);
  EXPECT_EQ(rr.independent(), dense_kept);
  EXPECT_EQ(rr.rank(), 60 - static_cast<int>(expected.size()));
}

TEST(SparseRowRank, MinimumNormSolutionAndCombinations) {
  std::vector<int> dep;
  const Eigen::MatrixXd J = BandedWithDependentRows(40, 70, 11, &dep);
  const SparseRowRank rr(J.sparseView());
  ASSERT_TRUE(rr.ok());
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(40, -1, 2);
  for (int r : dep) b[r] = 1e3;  // ignored: only the independent rows are solved
  const Eigen::VectorXd x = rr.MinNormSolve(b);
  Eigen::MatrixXd Jind(rr.independent().size(), J.cols());
  Eigen::VectorXd bind(rr.independent().size());
  for (size_t k = 0; k < rr.independent().size(); ++k) {
    Jind.row(k) = J.row(rr.independent()[k]);
    bind[k] = b[rr.independent()[k]];
  }
  const Eigen::VectorXd reference = Jind.completeOrthogonalDecomposition().solve(bind);  // minimum norm
  EXPECT_LT((Jind * x - bind).norm(), 1e-12);
  EXPECT_LT((x - reference).norm(), 1e-12 * reference.norm());
  for (int d : rr.dependent()) {
    const Eigen::VectorXd c = rr.DependentCombination(d);
    EXPECT_LT((c.transpose() * J - J.row(d)).norm(), 1e-12) << d;
    EXPECT_NEAR(c[d - 2], 1.5, 1e-12);
    EXPECT_NEAR(c[d - 3], -0.5, 1e-12);
  }
  const Eigen::MatrixXd N = rr.NullSpace(100);
  EXPECT_EQ(N.cols(), 70 - rr.rank());
  EXPECT_LT((J * N).norm(), 1e-12);
  EXPECT_LT((N.transpose() * N - Eigen::MatrixXd::Identity(N.cols(), N.cols())).norm(), 1e-12);
}

TEST(SparseRowRank, ZeroRowsAndAnEmptyMatrix) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, 5);
  J(1, 2) = 2.0;
  const SparseRowRank rr(J.sparseView());
  EXPECT_EQ(rr.rank(), 1);
  EXPECT_EQ(rr.independent(), std::vector<int>{1});
  EXPECT_EQ(rr.dependent(), (std::vector<int>{0, 2}));
  const SparseRowRank empty(Eigen::SparseMatrix<double>(0, 4));
  EXPECT_EQ(empty.rank(), 0);
  EXPECT_EQ(empty.NullSpace(10).cols(), 4);
}

}  // namespace
}  // namespace mechkin
