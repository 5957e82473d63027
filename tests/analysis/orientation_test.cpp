// Orientation outputs' formulas (analysis/orientation.hpp) for all twelve
// intrinsic sequences: the angles recompose the rotation, their rates equal
// differences of the angles along the rotation, and gimbal lock is detected.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/orientation.hpp"

namespace mechkin {
namespace orientation_test {

const char* kSequences[] = {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ"};

BodyKinematics Body(const Vec4& p, const Vec3& w) {
  BodyKinematics b;
  b.SetPose(Vec3::Zero(), p.normalized());
  b.w[0] = w;
  b.UpdateDerived(1);
  return b;
}

Eigen::Matrix3d Compose(const std::string& seq, const std::array<Jet, 3>& a) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  for (int k = 0; k < 3; ++k) R = R * Eigen::AngleAxisd(a[k].c[0], Vec3::Unit(seq[k] - 'X')).toRotationMatrix();
  return R;
}

TEST(Orientation, EverySequenceRecomposesAndDifferentiates) {
  const BodyKinematics ground;
  const Vec4 p(0.8, 0.3, -0.4, 0.35);
  const Vec3 w(0.7, -1.1, 0.4);  // body-frame angular velocity
  const BodyKinematics b = Body(p, w);
  const double h = 1e-6;
  const BodyKinematics bp = Body(QuatRetractBody(p.normalized(), h * w), w);
  const BodyKinematics bm = Body(QuatRetractBody(p.normalized(), -h * w), w);
  for (const char* seq : kSequences) {
    std::array<Jet, 3> a, ap, am;
    ASSERT_TRUE(SequenceAngles(RelativeRotation(ground, b, 1), seq, &a)) << seq;
    EXPECT_LT((Compose(seq, a) - b.A).norm(), 1e-14) << seq;
    SequenceAngles(RelativeRotation(ground, bp, 1), seq, &ap);
    SequenceAngles(RelativeRotation(ground, bm, 1), seq, &am);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(a[k].Derivative(1), (ap[k].c[0] - am[k].c[0]) / (2 * h), 1e-8) << seq << k;
  }
}

TEST(Orientation, GimbalLockIsDetected) {
  const BodyKinematics ground;
  // Pitch +90° for ZYX; a zero middle angle for ZXZ.
  const BodyKinematics pitched = Body(QuatFromAxisAngle(Vec3::UnitY(), M_PI / 2), Vec3::Zero());
  std::array<Jet, 3> a;
  EXPECT_FALSE(SequenceAngles(RelativeRotation(ground, pitched, 1), "ZYX", &a));
  EXPECT_NEAR(a[1].c[0], M_PI / 2, 1e-15);
  const BodyKinematics yawed = Body(QuatFromAxisAngle(Vec3::UnitZ(), 0.5), Vec3::Zero());
  EXPECT_FALSE(SequenceAngles(RelativeRotation(ground, yawed, 1), "ZXZ", &a));
  EXPECT_TRUE(SequenceAngles(RelativeRotation(ground, yawed, 1), "ZYX", &a));
  EXPECT_NEAR(a[0].c[0], 0.5, 1e-15);
}

// Through θ = 0 the rotation vector's rate is the angular velocity itself.
TEST(Orientation, RotationVectorIsSmoothAtZero) {
  const BodyKinematics ground;
  const Vec3 w(0.3, -0.2, 0.9);
  const BodyKinematics b = Body(Vec4(1, 0, 0, 0), w);
  const auto q = RelativeEulerParameters(ground, b, 1);
  const auto v = RotationVector(q);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(v[k].c[0], 0, 1e-300);
    EXPECT_NEAR(v[k].Derivative(1), w[k], 1e-15);
  }
  // And away from zero: |θn| = the rotation angle.
  const BodyKinematics c = Body(QuatFromAxisAngle(Vec3(1, 2, 2).normalized(), 2.5), w);
  const auto u = RotationVector(RelativeEulerParameters(ground, c, 1));
  EXPECT_NEAR(std::sqrt(u[0].c[0] * u[0].c[0] + u[1].c[0] * u[1].c[0] + u[2].c[0] * u[2].c[0]), 2.5, 1e-14);
  EXPECT_NEAR(u[0].c[0], 2.5 / 3, 1e-14);
}

}  // namespace
}  // namespace mechkin
