// The convex hull of a `convex` shape's points (math/convex_hull.hpp): a cube with
// interior and repeated points gives its 8 corners and 6 quadrilateral faces, each
// counter-clockwise seen from outside; a flat or short point set is refused.
#include <gtest/gtest.h>

#include "math/convex_hull.hpp"

namespace mechkin {
namespace convex_hull_test {

TEST(ConvexHull, CubeWithInteriorPointsHasEightCornersAndSixOutwardQuads) {
  std::vector<Vec3> pts;
  for (int k = 0; k < 8; ++k) pts.emplace_back(k & 1 ? 1 : -1, k & 2 ? 2 : -2, k & 4 ? 3 : -3);
  pts.emplace_back(0, 0, 0);
  pts.emplace_back(0.5, -1, 2);
  pts.push_back(pts[3]);  // a repeated corner
  ConvexHull hull;
  std::string why;
  ASSERT_TRUE(ComputeConvexHull(pts, &hull, &why)) << why;
  EXPECT_EQ(hull.vertices.size(), 8u);
  ASSERT_EQ(hull.num_faces, 6);
  size_t at = 0;
  int edges = 0;
  for (int f = 0; f < hull.num_faces; ++f) {
    const int n = hull.faces[at];
    ASSERT_EQ(n, 4);
    const Vec3 a = hull.vertices[hull.faces[at + 1]], b = hull.vertices[hull.faces[at + 2]],
               c = hull.vertices[hull.faces[at + 3]];
    // Outward: the face normal points away from the centre (the origin).
    EXPECT_GT((b - a).cross(c - b).dot(a), 0) << "face " << f;
    edges += n;
    at += n + 1;
  }
  EXPECT_EQ(edges / 2, 12);  // every edge in two faces
}

TEST(ConvexHull, FlatOrTooFewPointsAreRefused) {
  ConvexHull hull;
  std::string why;
  EXPECT_FALSE(ComputeConvexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.5, 0}}, &hull, &why));
  EXPECT_NE(why.find("one plane"), std::string::npos) << why;
  EXPECT_FALSE(ComputeConvexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}}, &hull, &why));
  EXPECT_NE(why.find("fewer than 4"), std::string::npos) << why;
}

}  // namespace
}  // namespace mechkin
