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


namespace {
Mat3R TildeExtended(const Vec3& a) {
  Mat3R t;
  t << 0, -a[2], a[1], a[2], 0, -a[0], -a[1], a[0], 0;
  return t;
}
}  // namespace

JetPose JetPoseOf(const BodyKinematics& body, const Mat3R& A, int order) {
  static constexpr Real kFactorial[] = {1, 1, 2, 6, 24};
  Mat3R a[kMaxOrder + 1];
  a[0] = A;
  for (int k = 0; k < order; ++k) {
    a[k + 1].setZero();
    for (int j = 0; j <= k; ++j) a[k + 1] += a[j] * TildeExtended(body.w[k - j]) / kFactorial[k - j];
    a[k + 1] /= k + 1;
  }
  JetPose pose;
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k <= order; ++k) pose.r[i].c[k] = body.r[k][i] / kFactorial[k];
    for (int j = 0; j < 3; ++j) {
      pose.A(i, j) = ExtendedJet(0);
      for (int k = 0; k <= order; ++k) pose.A(i, j).c[k] = a[k](i, j);
    }
  }
  return pose;
}

}  // namespace mechkin
