// Position-level solves Φ(q, t) = 0 on the configuration manifold.
//
// Updates are (δr, δπ') per body in the ω' layout; Euler parameters move by the
// body-frame retraction of §1.5 and stay unit exactly, so no normalization
// equation is needed. Success is judged only on the scaled residual
// max_k |Φ_k| / L^power_k ≤ tolerance (L = characteristic length), never on a
// solver's own flag.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "constraints/system.hpp"

namespace mechkin {

struct SolveOptions {
  double tolerance = 1e-10;  // on the scaled residual (relative to the mechanism size)
  int max_iterations = 50;
  // Full-system Newton only: after meeting `tolerance`, up to two more iterations
  // with the factorization held toward this residual (never a failure); 0 = none.
  double target = 0;
  // Full-system Newton only: then refine in extended precision (Φ and the pose in
  // long double, corrections back-solved with the double factorization), for rows
  // whose derivatives need a residual below double round-off (error_bounds.hpp).
  bool extended_precision = false;
};

struct SolveSummary {
  bool success = false;
  int iterations = 0;
  double residual = -1;  // scaled max-abs residual at the end
  std::string message;
};

/// Row weights 1/L^power for the given rows of the system.
Eigen::VectorXd RowScales(const ConstraintSystem& sys, const std::vector<int>& rows);
/// max_k |Φ_k| · scale_k over `rows` (phi is the full Φ).
double ScaledResidual(const Eigen::VectorXd& phi, const std::vector<int>& rows, const Eigen::VectorXd& scales);
/// Moves every body by dq (ω' layout, 6 per body).
void ApplyStep(const Eigen::VectorXd& dq, SystemState* s);
/// All rows 0..m−1.
std::vector<int> AllRows(const ConstraintSystem& sys);

/// A Gauss–Newton step in scaled variables: dq_s with J_s dq_s ≈ rs (rs: the scaled
/// residual of the selected rows); the caller scales back and line-searches.
using ScaledStep = std::function<Eigen::VectorXd(const SystemState&, const Eigen::VectorXd& rs)>;
/// Damped Gauss–Newton with backtracking on the scaled residual of `rows`.
SolveSummary DampedGaussNewton(const ConstraintSystem& sys, const std::vector<int>& rows, const SolveOptions& options,
                               const ScaledStep& step, SystemState* s);

/// Damped minimum-norm Gauss–Newton on the selected rows (dense; any shape of
/// system). Used to assemble rough design poses and by the mobility analysis.
SolveSummary AssembleMinNorm(const ConstraintSystem& sys, const std::vector<int>& rows, const SolveOptions& options,
                             SystemState* s);

/// Rows chosen greedily in order so that the kept rows are independent:
/// scaled Jacobian, relative threshold `rel_tol` on the new direction's norm.
std::vector<int> IndependentRows(const Eigen::MatrixXd& scaled_J, double rel_tol, std::vector<int>* dependent);

/// Column scales of the dimensionless Jacobian (ω' layout): L for the three
/// translation columns of each body, 1 for the rotation columns.
Eigen::VectorXd DimensionlessColumnScales(const ConstraintSystem& sys);
/// ‖W J D‖_F for a sparse J over the given rows (row_scales = W) and columns (D),
/// without forming the product.
double DimensionlessNorm(const Eigen::SparseMatrix<double>& J, const Eigen::VectorXd& row_scales,
                         const Eigen::VectorXd& col_scales);

/// Jacobian (ω') scaled to be dimensionless: rows by 1/L^power, r columns by L.
Eigen::MatrixXd ScaledJacobian(const ConstraintSystem& sys, const SystemState& s);

}  // namespace mechkin
