#include "spec/mesh_file.hpp"

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace mechkin {

namespace {

bool Fail(MeshFileProblem* p, std::string message, std::string fix) {
  p->message = std::move(message);
  p->fix = std::move(fix);
  return false;
}

std::string Line(int line) { return "line " + std::to_string(line) + ": "; }

// A finite number from a token; false for anything else (trailing characters too).
bool ToNumber(const std::string& token, double* v) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  *v = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && std::isfinite(*v);
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// ---- STL -----------------------------------------------------------------------

// Binary STL: an 80-byte header, the triangle count (uint32, little-endian), then per
// triangle the normal and three vertices (12 float32) and a 2-byte attribute.
bool ParseBinaryStl(const std::string& data, MeshSpec* mesh, MeshFileProblem* problem) {
  const auto* b = reinterpret_cast<const unsigned char*>(data.data());
  const uint32_t n = uint32_t(b[80]) | uint32_t(b[81]) << 8 | uint32_t(b[82]) << 16 | uint32_t(b[83]) << 24;
  const uint64_t want = 84 + 50 * uint64_t(n);
  if (data.size() != want)
    return Fail(problem,
                "a binary STL whose header counts " + std::to_string(n) + " triangles (" + std::to_string(want) +
                    " bytes) but the file has " + std::to_string(data.size()) + " bytes: truncated or not an STL",
                "export the part again as STL (binary or ASCII)");
  for (uint32_t t = 0; t < n; ++t) {
    std::array<int, 3> tri{};
    for (int v = 0; v < 3; ++v) {
      std::array<double, 3> p{};
      for (int a = 0; a < 3; ++a) {
        const unsigned char* at = b + 84 + 50 * size_t(t) + 12 + 12 * v + 4 * a;
        const uint32_t bits = uint32_t(at[0]) | uint32_t(at[1]) << 8 | uint32_t(at[2]) << 16 | uint32_t(at[3]) << 24;
        float f;
        std::memcpy(&f, &bits, 4);
        if (!std::isfinite(f))
          return Fail(problem, "triangle " + std::to_string(t + 1) + " has a coordinate that is not a finite number",
                      "export the part again as STL");
        p[a] = f;
      }
      tri[v] = static_cast<int>(mesh->vertices.size());
      mesh->vertices.push_back(p);
    }
    mesh->triangles.push_back(tri);
  }
  return true;
}

// ASCII STL: "solid …", then facets "facet normal … outer loop vertex x y z ×3
// endloop endfacet", "endsolid".
bool ParseAsciiStl(const std::string& text, MeshSpec* mesh, MeshFileProblem* problem) {
  std::istringstream lines(text);
  std::string raw;
  int line = 0, in_facet = 0, facet_line = 0;
  std::vector<std::array<double, 3>> corners;
  const std::string fix = "an ASCII STL facet is 'facet normal nx ny nz', 'outer loop', three 'vertex x y z', "
                          "'endloop', 'endfacet'; export the part again";
  while (std::getline(lines, raw)) {
    ++line;
    std::istringstream words(raw);
    std::string word;
    if (!(words >> word)) continue;
    word = Lower(word);
    if (word == "facet") {
      if (in_facet) return Fail(problem, Line(line) + "a facet begins inside the facet of line " + std::to_string(facet_line), fix);
      in_facet = 1, facet_line = line, corners.clear();
    } else if (word == "vertex") {
      std::array<double, 3> p{};
      for (double& c : p) {
        std::string token;
        if (!(words >> token) || !ToNumber(token, &c))
          return Fail(problem, Line(line) + "a vertex needs three finite numbers: '" + raw + "'", fix);
      }
      if (!in_facet) return Fail(problem, Line(line) + "a vertex outside any facet", fix);
      corners.push_back(p);
    } else if (word == "endfacet") {
      if (!in_facet) return Fail(problem, Line(line) + "'endfacet' without a facet", fix);
      if (corners.size() != 3)
        return Fail(problem, Line(facet_line) + "a facet with " + std::to_string(corners.size()) + " vertices, not 3", fix);
      const int first = static_cast<int>(mesh->vertices.size());
      mesh->vertices.insert(mesh->vertices.end(), corners.begin(), corners.end());
      mesh->triangles.push_back({first, first + 1, first + 2});
      in_facet = 0;
    }
  }
  if (in_facet)
    return Fail(problem, Line(facet_line) + "the file ends inside this facet: truncated", fix);
  return true;
}

// ---- OBJ -----------------------------------------------------------------------

// One "f" token ("7", "7/2", "7//3", "7/2/3", or negative: from the end) → a vertex index.
bool ObjIndex(const std::string& token, int count, int line, int* index, MeshFileProblem* problem) {
  const std::string head = token.substr(0, token.find('/'));
  char* end = nullptr;
  const long k = std::strtol(head.c_str(), &end, 10);
  if (head.empty() || end != head.c_str() + head.size() || k == 0)
    return Fail(problem, Line(line) + "'" + token + "' is not a vertex index",
                "a face lists vertex numbers counted from 1 (or from the end, -1 the last)");
  const long i = k > 0 ? k - 1 : count + k;
  if (i < 0 || i >= count)
    return Fail(problem,
                Line(line) + "face vertex " + std::to_string(k) + " is out of range: " + std::to_string(count) +
                    " vertices up to here",
                "a face may name only vertices ('v' lines) before it, counted from 1");
  *index = static_cast<int>(i);
  return true;
}

bool ParseObj(const std::string& text, MeshSpec* mesh, MeshFileProblem* problem) {
  std::istringstream lines(text);
  std::string raw;
  int line = 0;
  while (std::getline(lines, raw)) {
    ++line;
    std::istringstream words(raw);
    std::string word;
    if (!(words >> word)) continue;
    if (word == "v") {
      std::array<double, 3> p{};
      for (double& c : p) {
        std::string token;
        if (!(words >> token) || !ToNumber(token, &c))
          return Fail(problem, Line(line) + "a vertex needs three finite numbers: '" + raw + "'", "write 'v x y z'");
      }
      mesh->vertices.push_back(p);
    } else if (word == "f") {
      std::vector<int> poly;
      for (std::string token; words >> token;) {
        int i = 0;
        if (!ObjIndex(token, static_cast<int>(mesh->vertices.size()), line, &i, problem)) return false;
        poly.push_back(i);
      }
      if (poly.size() < 3)
        return Fail(problem, Line(line) + "a face with " + std::to_string(poly.size()) + " vertices",
                    "a face needs at least 3 vertices");
      for (size_t k = 1; k + 1 < poly.size(); ++k) mesh->triangles.push_back({poly[0], poly[k], poly[k + 1]});
    }
  }
  return true;
}

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

bool ParseMeshText(const std::string& text, bool obj, MeshSpec* mesh, MeshFileProblem* problem) {
  mesh->vertices.clear();
  mesh->triangles.clear();
  bool ok;
  if (obj) {
    ok = ParseObj(text, mesh, problem);
  } else {
    // "solid" opens an ASCII STL, but binary exporters write it into their header too:
    // a file whose size is exactly what its triangle count says is binary.
    const size_t start = text.find_first_not_of(" \t\r\n");
    const bool solid = start != std::string::npos && Lower(text.substr(start, 5)) == "solid";
    bool binary_size = false;
    if (text.size() >= 84) {
      const auto* b = reinterpret_cast<const unsigned char*>(text.data());
      const uint64_t n = uint32_t(b[80]) | uint32_t(b[81]) << 8 | uint32_t(b[82]) << 16 | uint32_t(b[83]) << 24;
      binary_size = text.size() == 84 + 50 * n;
    }
    const bool facets = text.find("facet") != std::string::npos;
    if (binary_size || (text.size() >= 84 && (!solid || !facets))) ok = ParseBinaryStl(text, mesh, problem);
    else if (solid) ok = ParseAsciiStl(text, mesh, problem);
    else
      return Fail(problem, "a file of " + std::to_string(text.size()) + " bytes is neither a binary STL (84 bytes or more) "
                  "nor an ASCII STL ('solid …'): truncated or not an STL", "export the part again as STL");
  }
  if (ok && mesh->triangles.empty())
    return Fail(problem, "the file has no triangles", obj ? "give a mesh with 'f' lines (faces)" : "give a mesh with facets");
  return ok;
}

bool ReadMeshFile(const std::string& path, MeshSpec* mesh, MeshFileProblem* problem) {
  mesh->path = path;
  const std::string lower = Lower(path);
  const bool obj = EndsWith(lower, ".obj");
  if (!obj && !EndsWith(lower, ".stl"))
    return Fail(problem, "a mesh file must be STL (.stl) or OBJ (.obj)", "give an .stl or .obj file");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    return Fail(problem, std::string("cannot open it: ") + std::strerror(errno),
                "give the path relative to the mechanism file's folder (or an absolute path)");
  if (!S_ISREG(st.st_mode)) return Fail(problem, "it is not a regular file", "give an STL or OBJ file");
  if (static_cast<std::size_t>(st.st_size) > kMaxMeshFileBytes)
    return Fail(problem, "it is larger than 256 MiB", "give a coarser mesh: clearance needs the shape, not its finish");
  std::ifstream f(path, std::ios::binary);
  if (!f) return Fail(problem, std::string("cannot read it: ") + std::strerror(errno), "check its permissions");
  std::ostringstream data;
  data << f.rdbuf();
  return ParseMeshText(data.str(), obj, mesh, problem);
}

}  // namespace mechkin
