// Rank, independent rows and null space of a large scaled Jacobian by a sparse
// rank-revealing QR (SuiteSparseQR) of its transpose:
//   J_sᵀ E = Q R,   J_s = W J D (rows by 1/L^power, translation columns by L; the
//   dimensionless Jacobian of constraints.md §6, as the dense path uses).
// With the fixed (natural) column order, SuiteSparseQR's Heath rule declares a row of
// J_s dependent when its component orthogonal to the rows before it is at most
// `tol` — the same greedy, file-order rule as the dense IndependentRows, so the
// later equation is the redundant one. Dependent ("dead") rows come last in E.
// Used where the dense SVD would not fit: models with more than 200 bodies.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>
#include <vector>

#include "constraints/system.hpp"
#include "kinematics/position.hpp"

namespace mechkin {

/// Default relative threshold (times the largest row norm) for a dependent row.
constexpr double kSparseRowIndependence = 1e-7;

class SparseRowRank {
 public:
  explicit SparseRowRank(const Eigen::SparseMatrix<double>& scaled_J, double rel_tol = kSparseRowIndependence);
  ~SparseRowRank();
  SparseRowRank(const SparseRowRank&) = delete;
  SparseRowRank& operator=(const SparseRowRank&) = delete;

  bool ok() const { return ok_; }
  int rank() const { return rank_; }
  /// Rows of J kept (increasing) and set aside (increasing).
  const std::vector<int>& independent() const { return independent_; }
  const std::vector<int>& dependent() const { return dependent_; }
  /// Smallest |R_kk| kept, largest column norm left over (the margin of the rank decision).
  double smallest_pivot() const { return smallest_pivot_; }
  double largest_dead() const { return largest_dead_; }

  /// Minimum-norm x with J_ind x = b_ind (b indexed by all rows of J; dependent rows ignored).
  Eigen::VectorXd MinNormSolve(const Eigen::VectorXd& b) const;
  /// c with row d of J = Σ_k c_k · row independent()[k] (d a dependent row).
  Eigen::VectorXd DependentCombination(int d) const;
  /// Up to max_count orthonormal vectors spanning the null space of J.
  Eigen::MatrixXd NullSpace(int max_count) const;

 private:
  struct Factors;
  std::unique_ptr<Factors> f_;
  bool ok_ = false;
  int rank_ = 0;
  std::vector<int> independent_, dependent_;
  std::vector<int> position_;  // row of J → its column position in E
  double smallest_pivot_ = 0, largest_dead_ = 0;
};

/// The scaled Jacobian J_s (ω' layout) of `rows` as a sparse matrix.
Eigen::SparseMatrix<double> ScaledSparseJacobian(const ConstraintSystem& sys, const SystemState& s,
                                                 const std::vector<int>& rows);

/// AssembleMinNorm for large systems: damped minimum-norm Gauss–Newton on the rows
/// the sparse QR finds independent at each iterate.
SolveSummary AssembleMinNormSparse(const ConstraintSystem& sys, const SolveOptions& options, SystemState* s);

}  // namespace mechkin
