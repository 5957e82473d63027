#include "mobility/grubler.hpp"

#include <cmath>
#include <vector>

#include "model/frames.hpp"

namespace mechkin {

int CalcGrublerCount(const Model& model) {
  int m = 6 * model.num_bodies();
  for (const auto& j : model.joints) m -= j.type->Rows();
  return m - static_cast<int>(model.couplers.size());  // one equation per coupler (§3.11)
}

namespace {

constexpr double kParallel = 1e-9;  // |sin| or |cos| of the angle between unit axes

// A joint's axis (h of its frame in body1) in global coordinates at the design pose.
Vec3 GlobalAxis(const Model& m, const Joint& j) {
  const Vec3 h = j.frame1.h.normalized();
  return j.body1 == kGround ? h : Vec3(CalcA(m.bodies[j.body1].euler) * h);
}

// Its axis along the plane's normal in a planar mechanism (a revolute or planar joint).
bool TurnsAboutAxis(const Joint& j) { return j.type->planar == PlanarRole::Turn || j.type->planar == PlanarRole::Plane; }

// The plane's normal: a revolute or planar joint's axis; else the
// cross product of two prismatic axes that are not parallel; else any direction
// across the (parallel) prismatic axes. nullopt without a joint that has an axis.
std::optional<Vec3> PlaneNormal(const Model& m) {
  std::vector<Vec3> slides;
  for (const Joint& j : m.joints) {
    if (TurnsAboutAxis(j)) return GlobalAxis(m, j);
    if (j.type->planar == PlanarRole::Slide) slides.push_back(GlobalAxis(m, j));
  }
  if (slides.empty()) return std::nullopt;
  for (const Vec3& s : slides) {
    const Vec3 n = slides.front().cross(s);
    if (n.norm() > kParallel) return n.normalized();
  }
  return MakeFrame(Vec3::Zero(), slides.front()).f;
}

}  // namespace

std::optional<PlanarStructure> FindPlanarStructure(const Model& m) {
  const std::optional<Vec3> normal = PlaneNormal(m);
  if (!normal) return std::nullopt;
  PlanarStructure p;
  p.normal = *normal;
  for (const Joint& j : m.joints) {
    if (j.type->planar == PlanarRole::Link) {
      ++p.higher_pairs;
      continue;
    }
    const Vec3 axis = GlobalAxis(m, j);
    if (TurnsAboutAxis(j)) {
      if (axis.cross(p.normal).norm() > kParallel) return std::nullopt;
    } else if (j.type->planar == PlanarRole::Slide) {
      if (std::abs(axis.dot(p.normal)) > kParallel) return std::nullopt;
    } else {
      return std::nullopt;  // spherical, universal, screw, cylindrical (its slide leaves any plane): spatial
    }
    if (j.type->planar == PlanarRole::Plane) ++p.planar_joints;
    else ++p.lower_pairs;
  }
  p.couplers = static_cast<int>(m.couplers.size());
  p.count = 3 * m.num_bodies() - 2 * p.lower_pairs - p.higher_pairs - p.couplers;
  return p;
}

}  // namespace mechkin
