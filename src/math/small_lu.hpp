// In-place LU with partial pivoting for small dense systems (up to ~120 unknowns).
// Eigen's PartialPivLU is tuned for large matrices (blocking, BLAS-like kernels);
// for the 18×18 Jacobian of a slider-crank its overhead is several times the
// arithmetic, so the per-step solve uses this plain Doolittle elimination.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace mechkin {

class SmallLU {
 public:
  /// Factorizes `a` (square) in place: afterwards it holds L (unit, below the
  /// diagonal) and U. Returns false on an exactly zero or non-finite pivot.
  bool Compute(Eigen::MatrixXd* a) {
    lu_ = a;
    const int n = static_cast<int>(a->rows());
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
      if (p != k) { A.row(k).swap(A.row(p)); sign_ = -sign_; }
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
    return true;
  }
  /// x = A⁻¹ b with the factors (x may alias b).
  void Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const {
    const Eigen::MatrixXd& A = *lu_;
    const int n = static_cast<int>(A.rows());
    if (x != &b) *x = b;
    Eigen::VectorXd& y = *x;
    for (int k = 0; k < n; ++k) std::swap(y[k], y[perm_[k]]);
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
  /// x = A⁻ᵀ b with the same factors: PA = LU gives Aᵀ = Uᵀ Lᵀ P, so solve
  /// Uᵀ z = b (forward), Lᵀ w = z (backward), then undo the row swaps in reverse.
  void SolveTranspose(const Eigen::VectorXd& b, Eigen::VectorXd* x) const {
    const Eigen::MatrixXd& A = *lu_;
    const int n = static_cast<int>(A.rows());
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
    for (int k = n - 1; k >= 0; --k) std::swap(y[k], y[perm_[k]]);
  }
  double sign() const { return sign_; }

 private:
  const Eigen::MatrixXd* lu_ = nullptr;
  std::vector<int> perm_;
  double sign_ = 1;
};

}  // namespace mechkin
