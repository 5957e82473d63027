// Shapes (docs/format.md "Bodies" and "Clearance"): a body's "shape", its "shapes"
// and ground's "shapes". The reader checks the keys and reads a mesh shape's file
// (spec/mesh_file.hpp); kinds, sizes, the convex hull and the mesh's scale are
// compile's (src/model/compile_shapes.cpp).
#include "spec/json_reader.hpp"
#include "spec/mesh_file.hpp"

namespace mechkin::spec_reader {

namespace {

// "points": [[x, y, z], ...] of a convex shape; a wrong form goes to points_error.
void ReadConvexPoints(JsonReader& rd, const json& o, const std::string& ptr, ShapeSpec* sh) {
  if (!o.contains("points")) return;
  const json& pts = o.at("points");
  if (!pts.is_array()) {
    sh->points_error = "'points' must be an array of points [x, y, z], not " + TypeName(pts);
    return;
  }
  for (size_t k = 0; k < pts.size(); ++k)
    sh->points.push_back(rd.VectorValue(pts[k], ptr + "/points/" + std::to_string(k), "points/" + std::to_string(k)));
}

// A mesh shape's "file", relative to the mechanism file's folder (or absolute): read
// now, so that every variant compiled from the spec shares its triangles. A problem
// names the shape's "file" pointer, the file as opened and a fix; the shape is then
// refused (not ok), without a second message from compile.
void ReadMesh(JsonReader& rd, const std::string& ptr, ShapeSpec* sh) {
  if (!sh->file) return;
  const std::string& name = *sh->file;
  const std::string path = !name.empty() && name[0] == '/' ? name : rd.folder() + name;
  auto mesh = std::make_shared<MeshSpec>();
  MeshFileProblem problem;
  if (ReadMeshFile(path, mesh.get(), &problem)) {
    sh->mesh = std::move(mesh);
    return;
  }
  rd.Error(ptr + "/file", "mesh file '" + name + "'" + (path == name ? "" : " (" + path + ")") + ": " + problem.message,
           problem.fix);
  sh->ok = false;
}

}  // namespace

// {"type": "box", "size"} | {"type": "cylinder" or "capsule", "radius", "length", "axis"}
// | {"type": "sphere", "radius"} | {"type": "convex", "points"} | {"type": "mesh", "file",
// "scale"}, with an optional "center".
std::optional<ShapeSpec> ReadShape(JsonReader& rd, const json& o, const std::string& ptr) {
  ShapeSpec sh;
  sh.pointer = ptr;
  sh.type = rd.String(o, "type", ptr);
  if (!rd.CheckObject(o, ptr, {"type", "size", "radius", "length", "axis", "center", "points", "file", "scale"}, {"type"},
                      "'shape'") ||
      !sh.type)
    return std::nullopt;
  sh.center = rd.Vector(o, "center", ptr);
  sh.size = rd.Vector(o, "size", ptr);
  sh.axis = rd.Vector(o, "axis", ptr);
  sh.radius = rd.Number(o, "radius", ptr);
  sh.length = rd.Number(o, "length", ptr);
  ReadConvexPoints(rd, o, ptr, &sh);
  sh.file = rd.String(o, "file", ptr);
  sh.scale = rd.Number(o, "scale", ptr);
  if (*sh.type == "mesh") ReadMesh(rd, ptr, &sh);
  return sh;
}

// A shape that the reader refused stays in the list, not ok, so that the indices of
// the others (and their pointers) do not move.
std::vector<ShapeSpec> ReadShapeList(JsonReader& rd, const json& shapes, const std::string& ptr) {
  std::vector<ShapeSpec> out;
  if (!shapes.is_array()) {
    rd.Error(ptr, "'shapes' must be an array of shape objects, not " + TypeName(shapes),
             "write \"shapes\": [{\"type\": \"capsule\", \"radius\": r, \"length\": l, \"axis\": [0, 0, 1]}]");
    return out;
  }
  for (size_t k = 0; k < shapes.size(); ++k) {
    const std::string p = ptr + "/" + std::to_string(k);
    std::optional<ShapeSpec> sh = ReadShape(rd, shapes[k], p);
    if (!sh) {
      sh = ShapeSpec{};
      sh->ok = false;
      sh->pointer = p;
    }
    out.push_back(std::move(*sh));
  }
  return out;
}

}  // namespace mechkin::spec_reader
