#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "analysis/load.hpp"
#include "model/stray_points.hpp"

namespace mechkin {
namespace stray_points_test {

// The guard as the loader computed it before it became FindStrayJointPoints: every
// pair of points per joint (cubic in the joints), kept here as the reference.
std::vector<StrayJointPoint> Reference(const std::vector<JointEnds>& joints) {
  struct Point { int body; Vec3 p; size_t joint; };
  std::vector<Point> pts;
  for (size_t j = 0; j < joints.size(); ++j)
    for (int side = 0; side < 2; ++side) pts.push_back({joints[j].body[side], joints[j].point[side], j});
  std::vector<StrayJointPoint> out;
  for (size_t j = 0; j < joints.size(); ++j) {
    std::vector<double> others;
    double nearest[2] = {-1, -1};
    for (size_t a = 0; a < pts.size(); ++a)
      for (size_t b = a + 1; b < pts.size(); ++b) {
        if (pts[a].body != pts[b].body || pts[a].joint == pts[b].joint) continue;
        const double d = (pts[a].p - pts[b].p).norm();
        if (pts[a].joint != j && pts[b].joint != j) { others.push_back(d); continue; }
        const int side = pts[a].joint == j ? static_cast<int>(a % 2) : static_cast<int>(b % 2);
        nearest[side] = nearest[side] < 0 ? d : std::min(nearest[side], d);
      }
    if (others.size() < 2 || nearest[0] < 0 || nearest[1] < 0) continue;
    std::nth_element(others.begin(), others.begin() + others.size() / 2, others.end());
    const double typical = others[others.size() / 2];
    const double near = std::min(nearest[0], nearest[1]);
    if (typical > 0 && near > 5 * typical) out.push_back({j, near, typical});
  }
  return out;
}

JointEnds Ends(int b1, Vec3 p1, int b2, Vec3 p2) {
  JointEnds e;
  e.body[0] = b1, e.body[1] = b2;
  e.point[0] = p1, e.point[1] = p2;
  return e;
}

JointEnds At(int b1, int b2, Vec3 p) { return Ends(b1, p, b2, p); }

void ExpectSame(const std::vector<StrayJointPoint>& got, const std::vector<StrayJointPoint>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t k = 0; k < got.size(); ++k) {
    EXPECT_EQ(got[k].joint, want[k].joint);
    EXPECT_EQ(got[k].nearest, want[k].nearest);  // the same doubles, not close ones
    EXPECT_EQ(got[k].typical, want[k].typical);
  }
}

// A four-bar (ground -1, bodies 0..2) with one pivot typed 10× too far: the pivot's
// joint is stray, by the ratio of its nearest other joint point to the median link.
TEST(StrayJointPoints, FourBarWithASlippedDigit) {
  std::vector<JointEnds> j = {At(-1, 0, {0, 0, 0}), At(0, 1, {0.04, 0, 0}), At(1, 2, {0.12, 0.05, 0}),
                              At(2, -1, {1.0, 0, 0})};
  const auto got = FindStrayJointPoints(j);
  ExpectSame(got, Reference(j));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].joint, 3u);
  // Nearest of joint 3: (0.12, 0.05) on body 2 at hypot(0.88, 0.05); the other
  // lengths are 0.04 (body 0), hypot(0.08, 0.05) (body 1) and 1.0 on the ground
  // excluded: links not involving joint 3 are {0.04, 0.0943}, median index 1.
  EXPECT_DOUBLE_EQ(got[0].nearest, std::hypot(0.88, 0.05));
  EXPECT_DOUBLE_EQ(got[0].typical, std::hypot(0.08, 0.05));
}

// One joint per body: no body carries two joint points, so there is no link at all.
TEST(StrayJointPoints, OneJointPerBodyHasNoLinks) {
  std::vector<JointEnds> j = {At(-1, 0, {0, 0, 0}), At(1, 2, {5, 0, 0}), At(3, 4, {900, 0, 0})};
  EXPECT_TRUE(FindStrayJointPoints(j).empty());
  EXPECT_TRUE(Reference(j).empty());
}

// A joint whose second end shares its body with no other joint is never stray.
TEST(StrayJointPoints, AnEndAloneOnItsBodyIsNotJudged) {
  std::vector<JointEnds> j = {At(-1, 0, {0, 0, 0}), At(0, 1, {1, 0, 0}), At(1, -1, {2, 0, 0}),
                              At(-1, 7, {1000, 0, 0})};
  ExpectSame(FindStrayJointPoints(j), Reference(j));
  EXPECT_TRUE(FindStrayJointPoints(j).empty());
}

// Coincident points: lengths of zero make the median zero, and a zero median warns of nothing.
TEST(StrayJointPoints, CoincidentPointsGiveAZeroMedianAndNoWarning) {
  std::vector<JointEnds> j = {At(-1, 0, {0, 0, 0}), At(0, 1, {0, 0, 0}), At(1, 2, {0, 0, 0}),
                              At(2, -1, {0, 0, 0}), At(0, 2, {3, 0, 0})};
  ExpectSame(FindStrayJointPoints(j), Reference(j));
  EXPECT_TRUE(FindStrayJointPoints(j).empty());
}

// Bodies with two joints each (a chain): equal lengths everywhere, nothing stray;
// then one end moved far: stray, the same as the reference.
TEST(StrayJointPoints, ChainOfTwoJointBodies) {
  std::vector<JointEnds> j;
  for (int b = 0; b < 6; ++b) j.push_back(At(b - 1, b, {0.1 * b, 0, 0}));
  EXPECT_TRUE(FindStrayJointPoints(j).empty());
  ExpectSame(FindStrayJointPoints(j), Reference(j));
  j[3].point[1] = Vec3(40, 0, 0);  // one end far: its other end is still near a joint
  ExpectSame(FindStrayJointPoints(j), Reference(j));
  EXPECT_TRUE(FindStrayJointPoints(j).empty());
  j[3] = At(2, 3, {40, 0, 0});  // both ends far: 39.6 from joint 4, 39.8 from joint 2; the links left are 0.1
  const auto got = FindStrayJointPoints(j);
  ExpectSame(got, Reference(j));
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].joint, 3u);
  EXPECT_DOUBLE_EQ(got[0].nearest / got[0].typical, 396);
}

// Both ends of one joint on the same body: their pair is not a link, the rest is.
TEST(StrayJointPoints, BothEndsOnOneBody) {
  std::vector<JointEnds> j = {Ends(0, {0, 0, 0}, 0, {9, 0, 0}), At(0, 1, {0.1, 0, 0}), At(1, 2, {0.2, 0, 0}),
                              At(2, 0, {0.3, 0, 0})};
  ExpectSame(FindStrayJointPoints(j), Reference(j));
}

// Random mechanisms with few bodies (many joints each, ties from a coarse grid and
// an occasional far point): the same joints with the same doubles as the reference.
TEST(StrayJointPoints, RandomModelsMatchTheReference) {
  std::mt19937 rng(7);
  int warned = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int bodies = 1 + static_cast<int>(rng() % 6), joints = 1 + static_cast<int>(rng() % 14);
    std::vector<JointEnds> j;
    for (int k = 0; k < joints; ++k) {
      JointEnds e;
      for (int side = 0; side < 2; ++side) {
        e.body[side] = static_cast<int>(rng() % (bodies + 1)) - 1;
        for (int a = 0; a < 3; ++a) e.point[side][a] = static_cast<double>(rng() % 5);
        if (rng() % 10 == 0) e.point[side] *= 100;
      }
      if (rng() % 2) e.point[1] = e.point[0];
      j.push_back(e);
    }
    const auto got = FindStrayJointPoints(j);
    ExpectSame(got, Reference(j));
    warned += static_cast<int>(got.size());
  }
  EXPECT_GT(warned, 20);  // the comparison covered warnings, not only silence
}

// Through the loader: a four-bar in mm whose rocker pivot D was typed 1000 for 100
// warns once, on /joints/3, with the ratio 881.4/94.34 (nearest other joint point of
// D, the coupler pivot C; the median of the other links, B–C).
TEST(StrayJointPoints, LoaderWarnsWithThePointer) {
  const std::string text = R"({"mechkin": 1, "units": {"length": "mm", "angle": "deg"},
    "bodies": [{"name": "crank", "position": [20, 0, 0]}, {"name": "coupler", "position": [80, 25, 0]},
               {"name": "rocker", "position": [560, 25, 0]}],
    "joints": [
      {"name": "A", "type": "revolute", "body1": "ground", "body2": "crank", "origin": [0, 0, 0], "axis": [0, 0, 1]},
      {"name": "B", "type": "revolute", "body1": "crank", "body2": "coupler", "origin": [40, 0, 0], "axis": [0, 0, 1]},
      {"name": "C", "type": "revolute", "body1": "coupler", "body2": "rocker", "origin": [120, 50, 0], "axis": [0, 0, 1]},
      {"name": "D", "type": "revolute", "body1": "rocker", "body2": "ground", "origin": [1000, 0, 0], "axis": [0, 0, 1]}]})";
  const LoadResult r = LoadMechanismText(text, "four-bar", {});
  ASSERT_TRUE(r.ok());
  int stray = 0;
  for (const auto& w : r.warnings) {
    if (w.message.find("typical length") == std::string::npos) continue;
    ++stray;
    EXPECT_EQ(w.pointer, "/joints/3");
    EXPECT_EQ(w.message.rfind("joint 'D' lies 9.34", 0), 0u) << w.message;  // 881.42 / 94.34
    EXPECT_EQ(w.fix, "check its coordinates (a slipped digit or unit)");
  }
  EXPECT_EQ(stray, 1);
}

}  // namespace
}  // namespace mechkin
