#include "constraints/constraint.hpp"

#include <cmath>

namespace mechkin {

void CalcPVersionJacobian(const Constraint& c, const ConstraintInput& in, const JacobianBlocks& J,
                          Eigen::Matrix<double, kMaxRows, 4>* p_i, Eigen::Matrix<double, kMaxRows, 4>* p_j) {
  (void)c;
  *p_i = 2 * J.pi_i * CalcG(in.i.p);
  *p_j = 2 * J.pi_j * CalcG(in.j.p);
}

Eigen::Matrix<double, kMaxRows, 4> PVersionBlock(const ConstraintInput& in, const JacobianBlocks& J, int side) {
  return 2 * J.Pi(side) * CalcG(in.Side(side).p);
}

void CalcPVersionRhs(const Constraint& c, const ConstraintInput& in, int k, double* rhs) {
  c.CalcRhs(in, k, rhs);
  if (k < 3) return;
  JacobianBlocks J;
  c.CalcJacobian(in, &J);
  for (int side = 0; side < c.num_sides(); ++side) {
    const Vec3& v = k == 3 ? in.Side(side).v : in.Side(side).v3;
    for (int row = 0; row < c.size(); ++row) rhs[row] -= J.Pi(side).row(row).dot(v);
  }
}


}  // namespace mechkin
