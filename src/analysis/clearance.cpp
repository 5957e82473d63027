#include "analysis/clearance.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace mechkin {

struct ClearanceEvaluator::Geometry {
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> shapes;
  std::vector<fcl::Transform3d> in_body;  // each shape's frame in the body
  // Each shape as measured against a mesh: a sphere as a capsule of length 0 (FCL's
  // GJK; its sphere–triangle specialisation misreads contacts at edges), others as is.
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> against_mesh;
  double reach = 0;
};

namespace {

// FCL's cylinders and capsules lie along their z axis: the rotation taking z to `axis`.
fcl::Transform3d ShapeFrame(const Shape& sh) {
  fcl::Transform3d T = fcl::Transform3d::Identity();
  if (sh.kind == Shape::Kind::Cylinder || sh.kind == Shape::Kind::Capsule)
    T.linear() = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), sh.axis).toRotationMatrix();
  T.translation() = sh.center;
  return T;
}

// A mesh (constraints.md §13) as FCL's bounding-volume hierarchy of its triangles (oriented boxes and
// swept spheres: FCL's distance queries need an oriented volume). Its distance is the
// surface's: exact between triangles, GJK between a triangle and a primitive.
std::shared_ptr<fcl::CollisionGeometryd> MakeMesh(const Shape& sh) {
  auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Vector3d> vertices(sh.points.begin(), sh.points.end());
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(sh.triangles.size());
  for (const auto& t : sh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  bvh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  bvh->addSubModel(vertices, triangles);
  bvh->endModel();
  bvh->computeLocalAABB();
  return bvh;
}

// The FCL shape and its reach about its own frame's origin.
std::shared_ptr<fcl::CollisionGeometryd> MakeShape(const Shape& sh, double* reach) {
  switch (sh.kind) {
    case Shape::Kind::Box:
      *reach = 0.5 * sh.size.norm();
      return std::make_shared<fcl::Boxd>(sh.size.x(), sh.size.y(), sh.size.z());
    case Shape::Kind::Sphere:
      *reach = sh.radius;
      return std::make_shared<fcl::Sphered>(sh.radius);
    case Shape::Kind::Cylinder:
      *reach = std::hypot(sh.radius, 0.5 * sh.length);
      return std::make_shared<fcl::Cylinderd>(sh.radius, sh.length);
    case Shape::Kind::Capsule:
      *reach = sh.radius + 0.5 * sh.length;
      return std::make_shared<fcl::Capsuled>(sh.radius, sh.length);
    case Shape::Kind::Convex:
    case Shape::Kind::Mesh:
      break;
  }
  *reach = 0;
  for (const Vec3& p : sh.points) *reach = std::max(*reach, p.norm());
  if (sh.kind == Shape::Kind::Mesh) return MakeMesh(sh);
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>(sh.points.begin(), sh.points.end());
  auto faces = std::make_shared<std::vector<int>>(sh.faces);
  return std::make_shared<fcl::Convexd>(vertices, sh.num_faces, faces);
}

fcl::Transform3d BodyPose(const BodyKinematics& k) {
  fcl::Transform3d T = fcl::Transform3d::Identity();
  T.linear() = k.A;
  T.translation() = k.r[0];
  return T;
}

// The velocity of the material point of body k at the global point x (order ≥ 1 solved).
Vec3 MaterialVelocity(const BodyKinematics& k, const Vec3& x) {
  return k.PointDerivative(k.A.transpose() * (x - k.r[0]), 1);
}

}  // namespace

std::vector<const Shape*> ClearanceShapes(const Model& model, BodyIndex body) {
  std::vector<const Shape*> out;
  if (body == kGround) {
    for (const Shape& s : model.ground_shapes) out.push_back(&s);
    return out;
  }
  const Body& b = model.bodies[body];
  if (b.shape) out.push_back(&*b.shape);
  for (const Shape& s : b.shapes) out.push_back(&s);
  return out;
}

std::vector<ClearancePair> ClearanceOutputPairs(const Model& model) {
  std::vector<ClearancePair> out;
  for (size_t o = 0; o < model.outputs.size(); ++o)
    if (model.outputs[o].kind == OutputKind::Clearance)
      out.push_back({model.outputs[o].body1, model.outputs[o].body2, static_cast<int>(o)});
  return out;
}

std::vector<ClearancePair> ShapedBodyPairs(const Model& model) {
  std::vector<BodyIndex> shaped;
  if (!model.ground_shapes.empty()) shaped.push_back(kGround);
  for (int b = 0; b < model.num_bodies(); ++b)
    if (!ClearanceShapes(model, b).empty()) shaped.push_back(b);
  auto jointed = [&](BodyIndex a, BodyIndex b) {
    return std::any_of(model.joints.begin(), model.joints.end(), [&](const Joint& j) {
      return (j.body1 == a && j.body2 == b) || (j.body1 == b && j.body2 == a);
    });
  };
  std::vector<ClearancePair> out;
  for (size_t i = 0; i < shaped.size(); ++i)
    for (size_t k = i + 1; k < shaped.size(); ++k)
      if (!jointed(shaped[i], shaped[k])) out.push_back({shaped[i], shaped[k], -1});
  return out;
}

ClearanceEvaluator::ClearanceEvaluator(const Model& model, std::vector<ClearancePair> pairs)
    : pairs_(std::move(pairs)) {
  // GJK stops when a step gains less than this: far below the 1e-9 s a contact is
  // located to at any speed the mechanism's size makes plausible.
  tolerance_ = 1e-12 * model.characteristic_length;
  for (int b = 0; b <= model.num_bodies(); ++b) {
    auto g = std::make_unique<Geometry>();
    for (const Shape* sh : ClearanceShapes(model, b == model.num_bodies() ? kGround : b)) {
      double reach = 0;
      g->shapes.push_back(MakeShape(*sh, &reach));
      g->against_mesh.push_back(sh->kind == Shape::Kind::Sphere ? std::make_shared<fcl::Capsuled>(sh->radius, 0.0)
                                                                : g->shapes.back());
      g->in_body.push_back(ShapeFrame(*sh));
      g->reach = std::max(g->reach, sh->center.norm() + reach);
    }
    bodies_.push_back(std::move(g));
  }
}

ClearanceEvaluator::~ClearanceEvaluator() = default;

const ClearanceEvaluator::Geometry& ClearanceEvaluator::Of(BodyIndex body) const {
  return *bodies_[body == kGround ? bodies_.size() - 1 : static_cast<size_t>(body)];
}

double ClearanceEvaluator::Reach(BodyIndex body) const { return Of(body).reach; }

namespace {

// In contact: minus the penetration depth from FCL's contact (analytic for spheres
// and boxes, MPR otherwise; a mesh's: its crossing triangles'), its witness points ∓
// half the depth along the normal (from shape 1 to shape 2); false when apart.
bool ContactDistance(const fcl::CollisionGeometryd* a, const fcl::Transform3d& Ta, const fcl::CollisionGeometryd* b,
                     const fcl::Transform3d& Tb, double* d, Vec3* pa, Vec3* pb) {
  fcl::CollisionRequestd touching(1, true);
  fcl::CollisionResultd contact;
  if (fcl::collide(a, Ta, b, Tb, touching, contact) == 0) return false;
  const fcl::Contactd& c = contact.getContact(0);
  *pa = c.pos + 0.5 * c.penetration_depth * c.normal;
  *pb = c.pos - 0.5 * c.penetration_depth * c.normal;
  *d = -c.penetration_depth;
  return true;
}

// FCL's distance between a mesh and a sphere gives its nearest points in the two
// shapes' own frames (Debian's FCL 0.7), its other pairs global: the pair whose gap
// is the distance.
void GlobalNearestPoints(const fcl::DistanceResultd& r, double d, const fcl::Transform3d& Ta,
                         const fcl::Transform3d& Tb, Vec3* pa, Vec3* pb) {
  *pa = r.nearest_points[0];
  *pb = r.nearest_points[1];
  const double slack = 1e-9 * std::max(d, (*pb - *pa).norm()) + 1e-300;
  if (std::abs((*pb - *pa).norm() - d) <= slack) return;
  const Vec3 qa = Ta * *pa, qb = Tb * *pb;
  if (std::abs((qb - qa).norm() - d) <= std::abs((*pb - *pa).norm() - d)) *pa = qa, *pb = qb;
}

// One shape pair: GJK's distance and closest points (global) while apart, else the
// contact's. FCL's signed distance (EPA) is not used: it trips an assertion of
// Debian's build on penetrating spheres. A mesh goes first (FCL misses some contacts
// of a sphere with a mesh's edge asked the other way round).
double ShapePairDistance(const fcl::CollisionGeometryd* a, const fcl::Transform3d& Ta,
                         const fcl::CollisionGeometryd* b, const fcl::Transform3d& Tb, double tolerance, Vec3* pa,
                         Vec3* pb) {
  if (b->getObjectType() == fcl::OT_BVH && a->getObjectType() != fcl::OT_BVH) {
    const double d = ShapePairDistance(b, Tb, a, Ta, tolerance, pb, pa);
    return d;
  }
  const bool mesh = a->getObjectType() == fcl::OT_BVH;
  fcl::DistanceRequestd request(true, false, 0.0, 0.0, tolerance);
  fcl::DistanceResultd result;
  double d = fcl::distance(a, Ta, b, Tb, request, result);
  if (mesh) GlobalNearestPoints(result, d, Ta, Tb, pa, pb);
  else *pa = result.nearest_points[0], *pb = result.nearest_points[1];
  // A mesh's distance within GJK's tolerance of 0 may be a crossing's unset value.
  if (d > (mesh ? tolerance : 0.0)) return d;
  if (!ContactDistance(a, Ta, b, Tb, &d, pa, pb)) return std::max(d, 0.0);
  return d;
}

}  // namespace

// The smallest signed distance over the shape pairs, then d' = n·(v₂ − v₁) with n
// the unit vector from the closest point on body1 to the one on body2, reversed in
// penetration (§13).
ClearanceValue ClearanceEvaluator::Evaluate(const SystemState& s, int pair, bool with_rate) const {
  const ClearancePair& p = pairs_[pair];
  const BodyKinematics &k1 = s.Kin(p.body1), &k2 = s.Kin(p.body2);
  const Geometry &g1 = Of(p.body1), &g2 = Of(p.body2);
  const fcl::Transform3d T1 = BodyPose(k1), T2 = BodyPose(k2);
  ClearanceValue best;
  best.distance = std::numeric_limits<double>::infinity();
  Vec3 pa, pb;
  for (size_t a = 0; a < g1.shapes.size(); ++a)
    for (size_t b = 0; b < g2.shapes.size(); ++b) {
      const bool mesh1 = g1.shapes[a]->getObjectType() == fcl::OT_BVH, mesh2 = g2.shapes[b]->getObjectType() == fcl::OT_BVH;
      const double d = ShapePairDistance((mesh2 ? g1.against_mesh : g1.shapes)[a].get(), T1 * g1.in_body[a],
                                         (mesh1 ? g2.against_mesh : g2.shapes)[b].get(), T2 * g2.in_body[b], tolerance_,
                                         &pa, &pb);
      if (!(d < best.distance)) continue;
      best.distance = d;
      best.point1 = pa;
      best.point2 = pb;
    }
  best.rate = std::nan("");
  const Vec3 gap = best.point2 - best.point1;
  if (with_rate && gap.norm() > 0) {
    const Vec3 n = (best.distance < 0 ? -gap : gap).normalized();
    best.rate = n.dot(MaterialVelocity(k2, best.point2) - MaterialVelocity(k1, best.point1));
  }
  return best;
}

}  // namespace mechkin
