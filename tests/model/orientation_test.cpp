#include <gtest/gtest.h>

#include "analysis/load.hpp"

namespace mechkin {
namespace orientation_test {

Vec4 LoadOrientation(const std::string& orientation, std::vector<Diagnostic>* warnings = nullptr) {
  const std::string text = R"({"mechkin": 1, "bodies": [{"name": "b", "position": [0, 0, 0], "orientation": )" +
                           orientation + R"(}], "joints": []})";
  const LoadResult r = LoadMechanismText(text, "inline");
  EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  if (warnings) *warnings = r.warnings;
  return r.ok() ? r.model->bodies[0].euler : Vec4::Zero();
}

// The three forms of one rotation (120° about (1,1,1)/√3, which permutes the axes
// x→y→z) give the same rotation matrix.
TEST(Orientation, ThreeFormsAgree) {
  Mat3 R;
  R << 0, 0, 1, 1, 0, 0, 0, 1, 0;  // columns = images of x, y, z
  const Vec4 a = LoadOrientation(R"({"axis": [1, 1, 1], "angle": 2.0943951023931953})");
  const Vec4 e = LoadOrientation(R"({"euler_parameters": [1, 1, 1, 1]})");
  const Vec4 m = LoadOrientation(R"({"matrix": [[0, 0, 1], [1, 0, 0], [0, 1, 0]]})");
  EXPECT_LT((CalcA(a) - R).norm(), 1e-15);
  EXPECT_LT((CalcA(e) - R).norm(), 1e-15);
  EXPECT_LT((CalcA(m) - R).norm(), 1e-15);
  EXPECT_NEAR(e.norm(), 1.0, 1e-16);  // normalised by the tool
}

// 180° rotations (e0 = 0) survive the matrix form: Shepperd's method picks the
// large component instead of dividing by e0.
TEST(Orientation, HalfTurnMatrix) {
  const Vec4 q = LoadOrientation(R"({"matrix": [[-1, 0, 0], [0, 1, 0], [0, 0, -1]]})");
  EXPECT_NEAR(std::abs(q[2]), 1.0, 1e-15);
  EXPECT_NEAR(q[0], 0.0, 1e-15);
}

TEST(Orientation, SlightlyNonOrthogonalMatrixIsRepairedWithWarning) {
  std::vector<Diagnostic> w;
  const Vec4 q = LoadOrientation(R"({"matrix": [[1, 0.0001, 0], [0, 1, 0], [0, 0, 1]]})", &w);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].pointer, "/bodies/0/orientation/matrix");
  const Mat3 A = CalcA(q);
  EXPECT_LT((A.transpose() * A - Mat3::Identity()).norm(), 1e-14);
  EXPECT_LT((A - Mat3::Identity()).norm(), 1e-4);
}

TEST(Orientation, QuatRoundTripsThroughMatrix) {
  for (const Vec4& q0 : {Vec4(0.3, -0.5, 0.7, 0.2), Vec4(0, 0, 0, 1), Vec4(1e-9, 1, 0, 0), Vec4(0.9, 0.1, -0.3, 0.1)}) {
    const Vec4 q = q0.normalized();
    Vec4 back = QuatFromMatrix(CalcA(q));
    if (back.dot(q) < 0) back = -back;
    EXPECT_LT((back - q).norm(), 1e-14);
  }
}

}  // namespace
}  // namespace mechkin
