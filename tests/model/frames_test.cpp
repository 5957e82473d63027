#include <gtest/gtest.h>

#include "analysis/load.hpp"

namespace mechkin {
namespace frames_test {

std::string Path(const std::string& name) { return std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/" + name; }

// Every joint frame of every bundled mechanism is orthonormal and right-handed,
// and mapping it back to global coordinates from either body recovers the
// joint's origin and axis as written in the file (to 1e-12 of the mechanism size).
TEST(JointFrames, OrthonormalAndRecoverGlobalGeometry) {
  for (const char* file : {"spatial-slider-crank.json", "bennett-linkage.json", "hooke-joint-30deg.json",
                           "screw-jack.json", "stewart-platform-sps-legs.json", "planar-xy-table.json"}) {
    const LoadResult r = LoadMechanismFile(Path(file));
    ASSERT_TRUE(r.ok()) << file;
    const Model& m = *r.model;
    for (const Joint& j : m.joints) {
      if (j.type->frames == JointFrameRule::TwoPoints) continue;
      Vec3 origin[2], h[2];
      int side = 0;
      for (const auto& [b, fr] : {std::pair{j.body1, j.frame1}, std::pair{j.body2, j.frame2}}) {
        const Mat3 A = b == kGround ? Mat3::Identity() : CalcA(m.bodies[b].euler);
        const Vec3 r0 = b == kGround ? Vec3::Zero() : m.bodies[b].position;
        Mat3 C;
        C << fr.f, fr.g, fr.h;
        EXPECT_LT((C.transpose() * C - Mat3::Identity()).norm(), 1e-14) << file << " " << j.name;
        EXPECT_NEAR(C.determinant(), 1.0, 1e-14);
        origin[side] = r0 + A * fr.origin;
        h[side] = A * fr.h;
        ++side;
      }
      EXPECT_LT((origin[0] - origin[1]).norm(), 1e-12 * m.characteristic_length) << file << " " << j.name;
      if (j.type->frames == JointFrameRule::Axis || j.type->frames == JointFrameRule::Normal) {
        EXPECT_LT((h[0] - h[1]).norm(), 1e-12) << file << " " << j.name;
      }
    }
  }
}

// The frames recover the literal numbers of the file: spatial slider-crank's
// guide is along global x through (x_C, 0.02, 0.05) m.
TEST(JointFrames, PrismaticAxisAsWritten) {
  const LoadResult r = LoadMechanismFile(Path("spatial-slider-crank.json"));
  ASSERT_TRUE(r.ok());
  const Model& m = *r.model;
  const Joint& guide = m.joints[3];
  ASSERT_EQ(guide.name, "guide");
  EXPECT_LT((guide.frame1.h - Vec3::UnitX()).norm(), 1e-15);  // ground frame = global
  EXPECT_NEAR(guide.frame1.origin.y(), 0.02, 1e-15);
  EXPECT_NEAR(guide.frame1.origin.z(), 0.05, 1e-15);
  // Universal: h on body1 = axis1, h on body2 = axis2, perpendicular.
  const Joint& wrist = m.joints[2];
  const Mat3 A1 = CalcA(m.bodies[wrist.body1].euler), A2 = CalcA(m.bodies[wrist.body2].euler);
  EXPECT_NEAR((A1 * wrist.frame1.h).dot(A2 * wrist.frame2.h), 0.0, 1e-15);
  EXPECT_LT((A2 * wrist.frame2.h - Vec3::UnitZ()).norm(), 1e-15);
}

TEST(CharacteristicLength, ScalesWithTheFileUnit) {
  const LoadResult a = LoadMechanismFile(Path("planar-four-bar.json"));
  ASSERT_TRUE(a.ok());
  // Four-bar in mm: the spread of its points is of order 0.06 m.
  EXPECT_GT(a.model->characteristic_length, 0.03);
  EXPECT_LT(a.model->characteristic_length, 0.2);
}

}  // namespace
}  // namespace mechkin
