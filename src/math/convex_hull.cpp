#include "math/convex_hull.hpp"

#include <algorithm>
#include <cmath>

namespace mechkin {
namespace {

struct Plane {
  Vec3 normal;  // outward, unit
  double offset;
};

// The points without near-duplicates (closer than eps).
std::vector<Vec3> Distinct(const std::vector<Vec3>& points, double eps) {
  std::vector<Vec3> out;
  for (const Vec3& p : points)
    if (std::none_of(out.begin(), out.end(), [&](const Vec3& q) { return (p - q).norm() <= eps; })) out.push_back(p);
  return out;
}

// The outward plane through p[i], p[j], p[k] when every point is on its inner side.
bool SupportingPlane(const std::vector<Vec3>& p, size_t i, size_t j, size_t k, double eps, Plane* plane) {
  const Vec3 n = (p[j] - p[i]).cross(p[k] - p[i]);
  const double len = n.norm();
  if (!(len > eps * ((p[j] - p[i]).norm() + (p[k] - p[i]).norm()))) return false;  // (nearly) collinear
  const Vec3 u = n / len;
  const double d = u.dot(p[i]);
  bool above = false, below = false;
  for (const Vec3& q : p) {
    const double s = u.dot(q) - d;
    above = above || s > eps;
    below = below || s < -eps;
    if (above && below) return false;
  }
  *plane = below ? Plane{u, d} : Plane{-u, -d};
  return true;
}

double Cross2(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// The face on `plane`: the points on it, ordered counter-clockwise about the outward
// normal by Andrew's monotone chain in the plane's (u, v) coordinates, u × v = normal.
std::vector<int> FacePolygon(const std::vector<Vec3>& p, const Plane& plane, double eps) {
  const Vec3 n = plane.normal;
  const Vec3 u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 v = n.cross(u);
  std::vector<std::pair<Eigen::Vector2d, int>> on;
  for (size_t k = 0; k < p.size(); ++k)
    if (std::abs(n.dot(p[k]) - plane.offset) <= eps) on.push_back({Eigen::Vector2d(u.dot(p[k]), v.dot(p[k])), int(k)});
  std::sort(on.begin(), on.end(), [](const auto& a, const auto& b) {
    return a.first.x() < b.first.x() || (a.first.x() == b.first.x() && a.first.y() < b.first.y());
  });
  std::vector<std::pair<Eigen::Vector2d, int>> chain(2 * on.size());
  size_t m = 0;
  for (size_t k = 0; k < on.size(); ++k) {  // lower chain
    while (m >= 2 && Cross2(chain[m - 2].first, chain[m - 1].first, on[k].first) <= eps * eps) --m;
    chain[m++] = on[k];
  }
  for (size_t k = on.size() - 1, lower = m + 1; k-- > 0;) {  // upper chain
    while (m >= lower && Cross2(chain[m - 2].first, chain[m - 1].first, on[k].first) <= eps * eps) --m;
    chain[m++] = on[k];
  }
  std::vector<int> face;
  for (size_t k = 0; k + 1 < m; ++k) face.push_back(chain[k].second);
  return face;
}

bool Seen(const std::vector<Plane>& planes, const Plane& p, double eps) {
  return std::any_of(planes.begin(), planes.end(), [&](const Plane& q) {
    return q.normal.dot(p.normal) > 1 - 1e-9 && std::abs(q.offset - p.offset) <= eps;
  });
}

// Vertices used by the faces only, renumbered.
void Compact(const std::vector<Vec3>& p, const std::vector<std::vector<int>>& faces, ConvexHull* hull) {
  std::vector<int> index(p.size(), -1);
  hull->vertices.clear();
  hull->faces.clear();
  for (const auto& f : faces) {
    hull->faces.push_back(static_cast<int>(f.size()));
    for (int k : f) {
      if (index[k] < 0) index[k] = static_cast<int>(hull->vertices.size()), hull->vertices.push_back(p[k]);
      hull->faces.push_back(index[k]);
    }
  }
  hull->num_faces = static_cast<int>(faces.size());
}

}  // namespace

bool ComputeConvexHull(const std::vector<Vec3>& points, ConvexHull* hull, std::string* why) {
  if (points.size() > static_cast<size_t>(kMaxHullPoints)) {
    *why = "a convex shape takes at most " + std::to_string(kMaxHullPoints) + " points, not " +
           std::to_string(points.size());
    return false;
  }
  double size = 0;
  for (const Vec3& a : points) size = std::max(size, (a - points.front()).norm());
  const double eps = 1e-9 * size;
  const std::vector<Vec3> p = Distinct(points, eps);
  std::vector<Plane> planes;
  std::vector<std::vector<int>> faces;
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = i + 1; j < p.size(); ++j)
      for (size_t k = j + 1; k < p.size(); ++k) {
        Plane plane;
        if (!SupportingPlane(p, i, j, k, eps, &plane) || Seen(planes, plane, eps)) continue;
        planes.push_back(plane);
        faces.push_back(FacePolygon(p, plane, eps));
      }
  // A solid has at least 4 faces; points in one plane give that plane twice (both sides).
  if (faces.size() < 4) {
    *why = p.size() < 4 ? "the points are fewer than 4 distinct ones" : "the points lie in one plane: they span no volume";
    return false;
  }
  Compact(p, faces, hull);
  return true;
}

}  // namespace mechkin
