// Shapes (docs/format.md "Bodies", "Clearance"): box, cylinder, sphere, capsule,
// convex and mesh, in body coordinates (ground's: global), converted to SI. They are drawn
// (`shape`) and measured by clearance outputs; a malformed one is an error.
#include <cmath>

#include "math/convex_hull.hpp"
#include "model/compiler.hpp"

namespace mechkin {

std::optional<Shape> Compiler::CompileShape(const ShapeSpec& o) {
  if (!o.ok || !o.type) return std::nullopt;
  const std::string& ptr = o.pointer;
  Shape sh;
  if (auto c = Vector(o.center, false)) sh.center = *c * length_;
  bool ok = true;
  if (*o.type == "box") {
    sh.kind = Shape::Kind::Box;
    auto size = Vector(o.size, true);
    if (!size) Error(ptr + "/size", "a box needs 'size': [a, b, c] along the body axes"), ok = false;
    else sh.size = size->cwiseAbs() * length_;
  } else if (*o.type == "cylinder" || *o.type == "capsule" || *o.type == "sphere") {
    ok = CompileRoundShape(o, &sh);
  } else if (*o.type == "convex") {
    ok = CompileConvex(o, &sh);
  } else if (*o.type == "mesh") {
    ok = CompileMesh(o, &sh);
  } else {
    const std::vector<std::string> kinds = {"box", "cylinder", "sphere", "capsule", "convex", "mesh"};
    const std::string g = DidYouMean(*o.type, kinds);
    Error(ptr + "/type", "unknown shape '" + Shorten(*o.type) + "'",
          (g.empty() ? "" : "did you mean '" + g + "'? ") + "use box, cylinder, sphere, capsule, convex or mesh");
    return std::nullopt;
  }
  if (!ok) return std::nullopt;
  return sh;
}

std::vector<Shape> Compiler::CompileShapes(const std::vector<ShapeSpec>& shapes) {
  std::vector<Shape> out;
  for (const ShapeSpec& s : shapes)
    if (auto sh = CompileShape(s)) out.push_back(std::move(*sh));
  return out;
}

// Sphere (radius), cylinder and capsule (radius, length, axis; a capsule's length is
// between its two caps' centres, so it measures length + 2 radius end to end).
bool Compiler::CompileRoundShape(const ShapeSpec& o, Shape* sh) {
  const std::string& ptr = o.pointer;
  bool ok = true;
  auto positive = [&](const std::optional<Scalar>& value, const char* key) -> double {
    auto v = Value(value);
    if (!v || !(*v > 0)) {
      Error(ptr + "/" + key, std::string("'") + key + "' must be a positive number", "give the size in units/length");
      ok = false;
      return 0;
    }
    return *v * length_;
  };
  sh->radius = positive(o.radius, "radius");
  if (*o.type == "sphere") {
    sh->kind = Shape::Kind::Sphere;
    return ok;
  }
  const bool capsule = *o.type == "capsule";
  sh->kind = capsule ? Shape::Kind::Capsule : Shape::Kind::Cylinder;
  sh->length = positive(o.length, "length");
  if (auto a = Vector(o.axis, true)) {
    if (a->norm() > 0) sh->axis = a->normalized();
    else Error(ptr + "/axis", "the " + *o.type + " 'axis' is the zero vector", "give a direction, e.g. [0, 0, 1]"), ok = false;
  }
  return ok;
}

// The hull of "points" (body coordinates, file units), stored about `center`.
bool Compiler::CompileConvex(const ShapeSpec& o, Shape* sh) {
  const std::string& ptr = o.pointer;
  sh->kind = Shape::Kind::Convex;
  if (!o.points_error.empty()) {
    Error(ptr + "/points", o.points_error, "give \"points\": [[x, y, z], ...] (at least 4, not in one plane)");
    return false;
  }
  if (o.points.size() < 4) {
    Error(ptr + (o.points.empty() ? "" : "/points"),
          "a convex shape needs at least 4 points, not " + std::to_string(o.points.size()),
          "give \"points\": [[x, y, z], ...]: 4 or more corners, not in one plane");
    return false;
  }
  std::vector<Vec3> points;
  for (const Vector3Spec& v : o.points) {
    auto p = VectorValue(v, false);
    if (!p) return false;
    points.push_back(*p * length_);
  }
  ConvexHull hull;
  std::string why;
  if (!ComputeConvexHull(points, &hull, &why)) {
    Error(ptr + "/points", "the convex shape's points have no hull: " + why,
          "give 4 or more corners that are not all in one plane");
    return false;
  }
  sh->points = hull.vertices;
  sh->faces = hull.faces;
  sh->num_faces = hull.num_faces;
  return true;
}

// The triangles the reader took from the mesh's file (spec/read_shapes.cpp), scaled
// into the file's length unit by "scale" (default 1), then into SI.
bool Compiler::CompileMesh(const ShapeSpec& o, Shape* sh) {
  const std::string& ptr = o.pointer;
  sh->kind = Shape::Kind::Mesh;
  if (!o.file) {
    Error(ptr, "a mesh shape needs 'file'", "give \"file\": \"part.stl\" (STL or OBJ, relative to the mechanism file)");
    return false;
  }
  double scale = 1;
  if (o.scale) {
    auto v = Value(o.scale);
    if (!v || !(*v > 0) || !std::isfinite(*v)) {
      if (v) Error(ptr + "/scale", "'scale' must be a positive number, not " + FormatNumber(*v),
                   "give the factor from the mesh file's numbers to the file's length unit (0.001: a mesh in mm, a file in m)");
      return false;
    }
    scale = *v;
  }
  if (!o.mesh) return false;  // the reader reported why
  const double f = scale * length_;
  sh->points.reserve(o.mesh->vertices.size());
  for (const auto& p : o.mesh->vertices) sh->points.push_back(Vec3(p[0], p[1], p[2]) * f);
  sh->triangles = o.mesh->triangles;
  return true;
}

// A clearance output without "name" is named after its bodies: "clearance_crank_frame".
std::optional<std::string> Compiler::DefaultOutputName(const OutputSpec& o) const {
  if (!o.type || *o.type != "clearance" || !o.body1 || !o.body2) return std::nullopt;
  return "clearance_" + *o.body1 + "_" + *o.body2;
}

// {"type": "clearance", "body1", "body2"}: two different bodies, each with a shape.
bool Compiler::CompileClearanceOutput(const OutputSpec& o, Output* out) {
  const std::string& ptr = o.pointer;
  const auto b1 = BodyRef(o.body1, "body1", ptr);
  const auto b2 = BodyRef(o.body2, "body2", ptr);
  if (!b1 || !b2) return false;
  if (*b1 == *b2) {
    Error(ptr + "/body2", "a clearance output measures between two different bodies, not '" + *o.body1 + "' and itself",
          "name another body as body2");
    return false;
  }
  bool ok = true;
  for (const auto& [b, key] : {std::make_pair(*b1, "body1"), std::make_pair(*b2, "body2")}) {
    const bool shaped = b == kGround ? !model_.ground_shapes.empty()
                                     : model_.bodies[b].shape || !model_.bodies[b].shapes.empty();
    if (shaped) continue;
    Error(ptr + "/" + key, "'" + model_.BodyName(b) + "' has no shape to measure a clearance from",
          b == kGround ? "give ground shapes: \"ground\": {\"shapes\": [{\"type\": \"box\", ...}]} (global coordinates)"
                       : "give the body a \"shape\" or \"shapes\": [...] (body coordinates)");
    ok = false;
  }
  out->body1 = *b1;
  out->body2 = *b2;
  return ok;
}

}  // namespace mechkin
