// Reading the triangle files of mesh shapes (docs/format.md "Clearance"): STL,
// binary or ASCII, and Wavefront OBJ (its "v" and "f" lines; a polygon is split
// into a fan of triangles from its first vertex; other lines are skipped). A small
// reader of the project's own: no geometry library is needed for two formats this
// plain. It never throws; a problem comes back as a message naming the line (or the
// triangle of a binary STL) and a fix.
#pragma once

#include <string>

#include "spec/spec.hpp"

namespace mechkin {

/// Largest mesh file read (bytes).
constexpr std::size_t kMaxMeshFileBytes = 256u << 20;

struct MeshFileProblem {
  std::string message;  // "line 12: face vertex 9 is out of range: 8 vertices up to here"
  std::string fix;
};

/// Reads `path` (".stl" or ".obj", any case) into *mesh; false with *problem
/// otherwise (a missing or unreadable file, a truncated STL, an OBJ index out of
/// range, a file without triangles, a number that is not finite).
bool ReadMeshFile(const std::string& path, MeshSpec* mesh, MeshFileProblem* problem);

/// Triangles from text: STL ("solid …") or OBJ; `obj` picks the reader. For tests.
bool ParseMeshText(const std::string& text, bool obj, MeshSpec* mesh, MeshFileProblem* problem);

}  // namespace mechkin
