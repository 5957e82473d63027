// The convex hull of a point set (a `convex` shape's "points", docs/format.md
// "Clearance"): its vertices and its faces as polygons, counter-clockwise seen from
// outside, in the layout FCL's Convex takes ([n, i0, …, i(n−1)] per face).
//
// Brute force over point triples (n ≤ kMaxHullPoints): a triple spans a face plane
// when every point lies on one side of it (to a tolerance relative to the set's
// size); the points on that plane form the face, ordered by a 2-D monotone chain.
// Coplanar points therefore give one polygon, not overlapping triangles, and the
// hull is closed (every edge in two faces), which FCL's support search relies on.
#pragma once

#include <string>
#include <vector>

#include "math/rotation.hpp"

namespace mechkin {

constexpr int kMaxHullPoints = 256;

struct ConvexHull {
  std::vector<Vec3> vertices;  // the hull's corners (interior and repeated points dropped)
  std::vector<int> faces;      // per face: its vertex count n, then n vertex indices
  int num_faces = 0;
};

/// The hull of `points`, or false with *why ("the points lie in one plane") when
/// they span no volume or there are more than kMaxHullPoints.
bool ComputeConvexHull(const std::vector<Vec3>& points, ConvexHull* hull, std::string* why);

}  // namespace mechkin
