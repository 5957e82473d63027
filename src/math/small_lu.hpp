// In-place LU with partial pivoting for small dense systems (up to ~120 unknowns).
// Eigen's PartialPivLU is tuned for large matrices (blocking, BLAS-like kernels);
// for the 18×18 Jacobian of a slider-crank its overhead is several times the
// arithmetic, so the per-step solve uses this plain Doolittle elimination.
//
// The factors of a mechanism's Jacobian are mostly exact zeros (the slider-crank's
// L and U hold about a third of their places), so after each factorization the
// nonzeros of each column are marked once and the solves visit only those. Skipping
// a term a − 0·y changes nothing but the sign of a zero a, and only an element
// holding −0 can be turned, so those take every term: the solves give the dense
// ones' bits, and where the result has a non-finite entry (a skipped 0·∞ is NaN)
// the dense solve is run instead (constraints.md §1.6). This holds in IEEE double
// arithmetic as C++ gives it by default: round to nearest, subnormals kept (no
// flush-to-zero), products and differences rounded apart (small_lu.cpp is compiled
// without contraction into fused multiply-adds).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

namespace mechkin {

class SmallLU {
 public:
  /// Factorizes `a` (square) in place: afterwards it holds L (unit, below the
  /// diagonal) and U. Returns false on an exactly zero or non-finite pivot.
  bool Compute(Eigen::MatrixXd* a);
  /// x = A⁻¹ b with the factors (x may alias b). Bit for bit DenseSolve's result.
  void Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x);
  /// x = A⁻ᵀ b with the same factors. Bit for bit DenseSolveTranspose's result.
  void SolveTranspose(const Eigen::VectorXd& b, Eigen::VectorXd* x);
  /// The same solves over every place of the factors (the reference the listed
  /// solves reproduce, and their fallback).
  void DenseSolve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const;
  void DenseSolveTranspose(const Eigen::VectorXd& b, Eigen::VectorXd* x) const;
  double sign() const { return sign_; }

 private:
  void ListNonzeros();
  void SolveListed(double* y) const;
  void SolveTransposeListed(double* y) const;
  template <typename T>
  void Permute(T* y) const {
    for (int k = 0; k < n_; ++k) std::swap(y[k], y[perm_[k]]);
  }
  void Unpermute(double* y) const;
  static std::uint64_t NonzeroBits(const double* col, int n);
  static bool HasNonFinite(const double* y, int n);

  const Eigen::MatrixXd* lu_ = nullptr;
  int n_ = 0;
  std::vector<int> perm_;
  double sign_ = 1;
  bool listed_ = false;  // the last Compute succeeded and listed its nonzeros (n ≤ 64)
  // Column j's nonzero rows of L (below the diagonal) as the bits of lower_[j], of U
  // (above it) as those of upper_[j]; listed for up to 64 unknowns.
  std::vector<std::uint64_t> lower_, upper_;
  std::vector<int> row_of_;        // P b = b[row_of_[i]]: the row swaps composed
  Eigen::VectorXd work_;           // the listed solves' working vector (one solve at a time)
};

}  // namespace mechkin
