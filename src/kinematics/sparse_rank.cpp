#include "kinematics/sparse_rank.hpp"

#include <Eigen/SPQRSupport>
#include <algorithm>
#include <cmath>

namespace mechkin {

struct SparseRowRank::Factors {
  Eigen::SPQR<Eigen::SparseMatrix<double>> qr;
  Eigen::SparseMatrix<double> R11;   // leading rank × rank block of R (upper triangular)
  Eigen::SparseMatrix<double> R;     // all of R (dead columns' projections live in its top rows)
  std::vector<long> E;               // column order of Jᵀ: live first, dead last
  long rows_of_A = 0;                // = columns of J
  bool factored = false;             // false: J has no rows or is zero (null space = everything)
};

SparseRowRank::SparseRowRank(const Eigen::SparseMatrix<double>& scaled_J, double rel_tol) : f_(new Factors) {
  const int m = static_cast<int>(scaled_J.rows());
  Eigen::SparseMatrix<double> A = scaled_J.transpose();
  A.makeCompressed();
  double max_norm = 0;
  for (int c = 0; c < A.cols(); ++c) max_norm = std::max(max_norm, A.col(c).norm());
  f_->rows_of_A = A.rows();
  if (m == 0 || max_norm == 0) {
    dependent_.resize(m);
    for (int r = 0; r < m; ++r) dependent_[r] = r;
    position_.assign(m, 0);
    ok_ = true;
    return;
  }
  // Natural order: the greedy file-order rule (module comment), as the dense path.
  f_->qr.setSPQROrdering(SPQR_ORDERING_FIXED);
  f_->qr.setPivotThreshold(rel_tol * max_norm);
  f_->qr.compute(A);
  if (f_->qr.info() != Eigen::Success) return;
  rank_ = static_cast<int>(f_->qr.rank());
  const long* e = f_->qr.colsPermutation().indices().data();  // null when E is the identity
  f_->R = f_->qr.matrixR();
  // SuiteSparseQR "squeezes" R when A is rank deficient: a dead column gets no new
  // pivot row, so column k (in E order) is live exactly when it reaches below the
  // live columns before it. Live columns first, dead last, each in E order.
  std::vector<long> live, dead;
  for (int k = 0; k < m; ++k) {
    long deepest = -1;
    for (Eigen::SparseMatrix<double>::InnerIterator it(f_->R, k); it; ++it)
      if (it.value() != 0) deepest = std::max<long>(deepest, it.row());
    (deepest >= static_cast<long>(live.size()) ? live : dead).push_back(k);
  }
  if (static_cast<int>(live.size()) != rank_) return;  // not the structure documented: no answer
  std::vector<long> order(live);
  order.insert(order.end(), dead.begin(), dead.end());
  // Columns of R in live-then-dead order, so R11 is the leading triangle.
  Eigen::SparseMatrix<double> R(f_->R.rows(), m);
  {
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 0; k < m; ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(f_->R, order[k]); it; ++it)
        t.emplace_back(static_cast<int>(it.row()), k, it.value());
    R.setFromTriplets(t.begin(), t.end());
  }
  f_->R = std::move(R);
  f_->E.resize(m);
  for (int k = 0; k < m; ++k) f_->E[k] = e ? e[order[k]] : order[k];
  position_.assign(m, 0);
  for (int k = 0; k < m; ++k) position_[f_->E[k]] = k;
  for (int k = 0; k < m; ++k) (k < rank_ ? independent_ : dependent_).push_back(static_cast<int>(f_->E[k]));
  std::sort(independent_.begin(), independent_.end());
  std::sort(dependent_.begin(), dependent_.end());
  f_->R11 = f_->R.topLeftCorner(rank_, rank_);
  f_->factored = true;
  smallest_pivot_ = rank_ ? std::abs(f_->R11.coeff(0, 0)) : 0;
  for (int k = 0; k < rank_; ++k) smallest_pivot_ = std::min(smallest_pivot_, std::abs(f_->R11.coeff(k, k)));
  for (int k = rank_; k < m; ++k)
    if (f_->R.rows() > rank_)
      largest_dead_ = std::max(largest_dead_, Eigen::VectorXd(f_->R.col(k)).tail(f_->R.rows() - rank_).norm());
  ok_ = true;
}

SparseRowRank::~SparseRowRank() = default;

// J_ind = R11ᵀ Q1ᵀ (J_indᵀ = Q1 R11), so x = Q1 y with R11ᵀ y = b_ind is the
// solution in the row space of J_ind: the minimum-norm one.
Eigen::VectorXd SparseRowRank::MinNormSolve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd z = Eigen::VectorXd::Zero(f_->rows_of_A);
  if (rank_ == 0 || !f_->factored) return z;
  Eigen::VectorXd bp(rank_);
  for (int k = 0; k < rank_; ++k) bp[k] = b[f_->E[k]];
  z.head(rank_) = f_->R11.transpose().triangularView<Eigen::Lower>().solve(bp);
  return f_->qr.matrixQ() * z;
}

// Dead column p of Jᵀ E: A_p = Q1 R(0:r, p), and A E1 = Q1 R11, so A_p = A E1 c with R11 c = R(0:r, p).
Eigen::VectorXd SparseRowRank::DependentCombination(int d) const {
  const int m = static_cast<int>(position_.size());
  Eigen::VectorXd coef = Eigen::VectorXd::Zero(m);
  if (rank_ == 0 || !f_->factored) return coef;
  const Eigen::VectorXd rp = Eigen::VectorXd(f_->R.col(position_[d])).head(rank_);
  const Eigen::VectorXd c = f_->R11.triangularView<Eigen::Upper>().solve(rp);
  for (int k = 0; k < rank_; ++k) coef[f_->E[k]] = c[k];
  return coef;
}

// Q's columns beyond the rank span the orthogonal complement of J's row space.
Eigen::MatrixXd SparseRowRank::NullSpace(int max_count) const {
  const long n = f_->rows_of_A;
  const int count = static_cast<int>(std::max(0L, std::min<long>(max_count, n - rank_)));
  Eigen::MatrixXd N(n, count);
  for (int j = 0; j < count; ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
    e[rank_ + j] = 1;
    N.col(j) = f_->factored ? Eigen::VectorXd(f_->qr.matrixQ() * e) : e;
  }
  return N;
}

Eigen::SparseMatrix<double> ScaledSparseJacobian(const ConstraintSystem& sys, const SystemState& s,
                                                 const std::vector<int>& rows) {
  SparseJacobian jac(sys, Formulation::Omega, rows);
  jac.Fill(sys, s);
  const Eigen::VectorXd w = RowScales(sys, rows);
  const Eigen::VectorXd col_scale = DimensionlessColumnScales(sys);
  Eigen::SparseMatrix<double> J = w.asDiagonal() * jac.matrix();
  J = J * col_scale.asDiagonal();
  J.makeCompressed();
  return J;
}

SolveSummary AssembleMinNormSparse(const ConstraintSystem& sys, const SolveOptions& options, SystemState* s) {
  const std::vector<int> rows = AllRows(sys);
  auto sparse_min_norm_step = [&](const SystemState& state, const Eigen::VectorXd& rs) {
    const SparseRowRank rr(ScaledSparseJacobian(sys, state, rows));
    return rr.ok() ? rr.MinNormSolve(rs) : Eigen::VectorXd(Eigen::VectorXd::Zero(6 * sys.num_bodies()));
  };
  return DampedGaussNewton(sys, rows, options, sparse_min_norm_step, s);
}

}  // namespace mechkin
