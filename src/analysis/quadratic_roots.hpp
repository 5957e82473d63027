// All real roots of k quadratic equations in k unknowns (small k), by total-degree
// homotopy continuation: the second-order tangent cone of a singular position
// (docs/singularities.md §3) is such a system, and counting its real roots counts
// the branches that cross the singular position.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace mechkin {

/// F_j(x) = c_j + 2 b_jᵀx + xᵀA_j x, j = 0..k−1 (A_j symmetric).
struct QuadraticSystem {
  Eigen::VectorXd c;               // k
  Eigen::MatrixXd b;               // k × k, row j = b_jᵀ
  std::vector<Eigen::MatrixXd> A;  // k matrices k × k
  int size() const { return static_cast<int>(c.size()); }
  Eigen::VectorXcd Value(const Eigen::VectorXcd& x) const;
  Eigen::MatrixXcd Jacobian(const Eigen::VectorXcd& x) const;
};

struct QuadraticRoots {
  std::vector<Eigen::VectorXd> real;  // distinct real finite roots
  // False when a path could not be tracked or ended on a singular (multiple or
  // non-isolated) root: the count is then not certain.
  bool complete = true;
};

/// The 2^k paths from x_j² = 1 (γ trick: a fixed complex factor on the start
/// system keeps the paths apart). Paths that grow beyond `infinity` end at roots
/// at infinity (directions in which the quadratic part alone vanishes). k ≤ 8.
QuadraticRoots RealRootsOfQuadratics(const QuadraticSystem& q, double infinity = 1e7);

}  // namespace mechkin
