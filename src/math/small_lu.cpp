#include "math/small_lu.hpp"

// a − l·y as a rounded product and a rounded difference, never one fused operation:
// the −0 argument below needs it (CMakeLists.txt also passes -ffp-contract=off).
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

#include <cmath>
#include <utility>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mechkin {

namespace {

bool IsNegativeZero(double v) { return v == 0 && std::signbit(v); }

// The rows among `rows` (bits) where y holds −0.
std::uint64_t NegativeZeros(const double* y, std::uint64_t rows) {
  std::uint64_t kept = 0;
  for (std::uint64_t m = rows; m; m &= m - 1) {
    const int i = __builtin_ctzll(m);
    kept |= static_cast<std::uint64_t>(IsNegativeZero(y[i])) << i;
  }
  return kept;
}

std::uint64_t RowsBelow(int j) { return ~((std::uint64_t{2} << j) - 1); }  // rows > j (j < 64)
std::uint64_t RowsAbove(int j) { return (std::uint64_t{1} << j) - 1; }     // rows < j
std::uint64_t AllRows(int n) { return n == 64 ? ~std::uint64_t{0} : RowsAbove(n); }

// y_i −= col_i · yj for the rows `rows` (bits).
void SubtractColumn(double* y, const double* col, double yj, std::uint64_t rows) {
  for (std::uint64_t m = rows; m; m &= m - 1) {
    const int i = __builtin_ctzll(m);
    y[i] -= col[i] * yj;
  }
}

// v − Σ col_i · y_i over the rows `rows` (bits), ascending.
double SubtractDot(double v, const double* col, const double* y, std::uint64_t rows) {
  for (std::uint64_t m = rows; m; m &= m - 1) {
    const int i = __builtin_ctzll(m);
    v -= col[i] * y[i];
  }
  return v;
}

}  // namespace

bool SmallLU::Compute(Eigen::MatrixXd* a) {
  lu_ = a;
  listed_ = false;
  const int n = static_cast<int>(a->rows());
  n_ = n;
  perm_.resize(n);
  sign_ = 1;
  Eigen::MatrixXd& A = *a;
  for (int k = 0; k < n; ++k) {
    int p = k;
    double best = std::abs(A(k, k));
    for (int i = k + 1; i < n; ++i)
      if (std::abs(A(i, k)) > best) { best = std::abs(A(i, k)); p = i; }
    perm_[k] = p;
    if (!(best > 0) || !std::isfinite(best)) return false;
    if (p != k) {
      double* data = A.data();
      for (int c = 0; c < n; ++c) std::swap(data[k + c * n], data[p + c * n]);
      sign_ = -sign_;
    }
    const double inv = 1.0 / A(k, k);
    for (int i = k + 1; i < n; ++i) A(i, k) *= inv;
    for (int j = k + 1; j < n; ++j) {
      const double akj = A(k, j);
      if (akj == 0) continue;
      double* col = &A(0, j);
      const double* lk = &A(0, k);
      for (int i = k + 1; i < n; ++i) col[i] -= lk[i] * akj;
    }
  }
  listed_ = n <= 64;
  if (listed_) ListNonzeros();
  return true;
}

// One bit per row of each column: nonzero (NaN included) or not. n ≤ 64.
void SmallLU::ListNonzeros() {
  const int n = n_;
  lower_.resize(n);
  upper_.resize(n);
  work_.resize(n);
  row_of_.resize(n);
  for (int i = 0; i < n; ++i) row_of_[i] = i;
  Permute(row_of_.data());
  const double* a = lu_->data();
  for (int j = 0; j < n; ++j) {
    const std::uint64_t m = NonzeroBits(a + static_cast<size_t>(j) * n, n);
    upper_[j] = m & RowsAbove(j);
    lower_[j] = m & RowsBelow(j);
  }
}

std::uint64_t SmallLU::NonzeroBits(const double* col, int n) {
  std::uint64_t m = 0;
  int i = 0;
#if defined(__SSE2__)
  const __m128d zero = _mm_setzero_pd();
  for (; i + 1 < n; i += 2)
    m |= static_cast<std::uint64_t>(_mm_movemask_pd(_mm_cmpneq_pd(_mm_loadu_pd(col + i), zero))) << i;
#endif
  for (; i < n; ++i) m |= static_cast<std::uint64_t>(col[i] != 0) << i;
  return m;
}

void SmallLU::Unpermute(double* y) const {
  for (int k = n_ - 1; k >= 0; --k) std::swap(y[k], y[perm_[k]]);
}

// y − y is 0 for a finite y, NaN for ±∞ and NaN; their sum tells, in any order: four
// running sums, not one chain of n dependent additions (each solve ends with this).
bool SmallLU::HasNonFinite(const double* y, int n) {
  double sum[4] = {0, 0, 0, 0};
  int i = 0;
  for (; i + 3 < n; i += 4)
    for (int l = 0; l < 4; ++l) sum[l] += y[i + l] - y[i + l];
  for (; i < n; ++i) sum[0] += y[i] - y[i];
  return (sum[0] + sum[1]) + (sum[2] + sum[3]) != 0;
}

// Column-oriented substitution as DenseSolve, each element's updates in the same
// order (columns ascending for L, descending for U), the zero terms a − (±0)
// skipped. That is exact except for an element holding −0, which −(−0) turns to +0;
// and only such an element can be −0 (x − p is −0 only for x = −0, p = +0; a
// division may make one, the divided element). So the elements holding −0 take
// every term of the column, as in the dense substitution.
void SmallLU::SolveListed(double* y) const {
  const double* a = lu_->data();
  const int n = n_;
  std::uint64_t negative_zero = NegativeZeros(y, AllRows(n));
  for (int j = 0; j < n; ++j) {
    const double yj = y[j];
    if (yj == 0) continue;
    const std::uint64_t below = negative_zero & RowsBelow(j);
    SubtractColumn(y, a + static_cast<size_t>(j) * n, yj, lower_[j] | below);
    if (below) negative_zero = (negative_zero & ~below) | NegativeZeros(y, below);
  }
  // Here y_j is final once divided: only the rows above it are tracked on.
  for (int j = n - 1; j >= 0; --j) {
    const double* col = a + static_cast<size_t>(j) * n;
    y[j] /= col[j];
    const double yj = y[j];
    if (yj == 0) continue;
    const std::uint64_t above = negative_zero & RowsAbove(j);
    SubtractColumn(y, col, yj, upper_[j] | above);
    if (above) negative_zero = (negative_zero & ~above) | NegativeZeros(y, above);
  }
}

// Row-oriented substitution as DenseSolveTranspose (each sum over ascending rows),
// the zero terms skipped: exact unless the sum starts at −0 (only then can it be −0
// when a term comes), and such a sum takes every term.
void SmallLU::SolveTransposeListed(double* y) const {
  const double* a = lu_->data();
  const int n = n_;
  for (int j = 0; j < n; ++j) {  // Uᵀ z = b
    const double* col = a + static_cast<size_t>(j) * n;
    const double v = y[j];
    y[j] = SubtractDot(v, col, y, IsNegativeZero(v) ? RowsAbove(j) : upper_[j]) / col[j];
  }
  for (int j = n - 1; j >= 0; --j) {  // Lᵀ w = z
    const double v = y[j];
    y[j] = SubtractDot(v, a + static_cast<size_t>(j) * n, y, IsNegativeZero(v) ? RowsBelow(j) & AllRows(n) : lower_[j]);
  }
}

// The listed solves work in work_ and leave b as it was: the dense solve of a
// non-finite result (a skipped 0 · ∞ is NaN in it) reads b again. row_of_ gathers
// P b in one pass (the row swaps composed).
void SmallLU::Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) {
  if (!listed_) return DenseSolve(b, x);
  const int n = n_;
  double* y = work_.data();
  for (int i = 0; i < n; ++i) y[i] = b[row_of_[i]];
  SolveListed(y);
  if (HasNonFinite(y, n)) return DenseSolve(b, x);
  x->resize(n);
  for (int i = 0; i < n; ++i) (*x)[i] = y[i];
}

void SmallLU::SolveTranspose(const Eigen::VectorXd& b, Eigen::VectorXd* x) {
  if (!listed_) return DenseSolveTranspose(b, x);
  const int n = n_;
  double* y = work_.data();
  for (int i = 0; i < n; ++i) y[i] = b[i];
  SolveTransposeListed(y);
  if (HasNonFinite(y, n)) return DenseSolveTranspose(b, x);
  x->resize(n);
  for (int i = 0; i < n; ++i) (*x)[row_of_[i]] = y[i];  // Pᵀ, the swaps undone
}

void SmallLU::DenseSolve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const {
  const Eigen::MatrixXd& A = *lu_;
  const int n = n_;
  if (x != &b) *x = b;
  Eigen::VectorXd& y = *x;
  Permute(y.data());
  for (int j = 0; j < n; ++j) {  // L y = P b, column by column
    const double yj = y[j];
    if (yj != 0) for (int i = j + 1; i < n; ++i) y[i] -= A(i, j) * yj;
  }
  for (int j = n - 1; j >= 0; --j) {  // U x = y
    y[j] /= A(j, j);
    const double yj = y[j];
    if (yj != 0) for (int i = 0; i < j; ++i) y[i] -= A(i, j) * yj;
  }
}

// PA = LU gives Aᵀ = Uᵀ Lᵀ P, so solve Uᵀ z = b (forward), Lᵀ w = z (backward),
// then undo the row swaps in reverse.
void SmallLU::DenseSolveTranspose(const Eigen::VectorXd& b, Eigen::VectorXd* x) const {
  const Eigen::MatrixXd& A = *lu_;
  const int n = n_;
  if (x != &b) *x = b;
  Eigen::VectorXd& y = *x;
  for (int j = 0; j < n; ++j) {  // Uᵀ z = b: row j of Uᵀ is column j of U
    double v = y[j];
    const double* uj = &A(0, j);
    for (int i = 0; i < j; ++i) v -= uj[i] * y[i];
    y[j] = v / A(j, j);
  }
  for (int j = n - 1; j >= 0; --j) {  // Lᵀ w = z, unit diagonal
    double v = y[j];
    const double* lj = &A(0, j);
    for (int i = j + 1; i < n; ++i) v -= lj[i] * y[i];
    y[j] = v;
  }
  Unpermute(y.data());
}

}  // namespace mechkin
