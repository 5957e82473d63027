#include "constraints/constraint.hpp"

#include <cmath>

namespace mechkin {

void CalcPVersionJacobian(const Constraint& c, const ConstraintInput& in, const JacobianBlocks& J,
                          Eigen::Matrix<double, kMaxRows, 4>* p_i, Eigen::Matrix<double, kMaxRows, 4>* p_j) {
  (void)c;
  *p_i = 2 * J.pi_i * CalcG(in.i.p);
  *p_j = 2 * J.pi_j * CalcG(in.j.p);
}

void CalcPVersionRhs(const Constraint& c, const ConstraintInput& in, int k, double* rhs) {
  c.CalcRhs(in, k, rhs);
  if (k < 3) return;
  JacobianBlocks J;
  c.CalcJacobian(in, &J);
  const Vec3& vi = k == 3 ? in.i.v : in.i.v3;
  const Vec3& vj = k == 3 ? in.j.v : in.j.v3;
  for (int row = 0; row < c.size(); ++row) rhs[row] -= J.pi_i.row(row).dot(vi) + J.pi_j.row(row).dot(vj);
}


}  // namespace mechkin
