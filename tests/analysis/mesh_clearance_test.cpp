// Mesh shapes (issue 28, docs/format.md "Clearance"): a box given as 12 triangles in
// a file — binary STL, ASCII STL, OBJ of 6 quads (fan-split) — measures like the
// analytic box along a motion (every row and the located contact, to 1e-9), also
// against a mesh on ground; a tetrahedron mesh against a sphere on a slider matches
// the point–triangle distance minus the radius (face, edge and vertex regions) and
// its contact time. The files are written here into a temporary folder, next to the
// mechanism file that names them relatively.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "analysis/motion.hpp"
#include "spec/mesh_file.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace mesh_clearance_test {

using nlohmann::json;
using Tri = std::array<Vec3, 3>;

std::string Dir() {
  static const std::string d = [] {
    std::string t = ::testing::TempDir() + "/mesh_clearance_XXXXXX";
    return std::string(::mkdtemp(t.data()));
  }();
  return d + "/";
}

// ---- Writing mesh files ---------------------------------------------------------

void WriteBinaryStl(const std::string& path, const std::vector<Tri>& tris) {
  std::ofstream f(path, std::ios::binary);
  std::string header(80, ' ');
  header.replace(0, 13, "solid binary ");  // as some exporters do: must still read as binary
  f.write(header.data(), 80);
  const uint32_t n = static_cast<uint32_t>(tris.size());
  f.write(reinterpret_cast<const char*>(&n), 4);
  for (const Tri& t : tris) {
    float v[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) v[3 + 3 * k + a] = static_cast<float>(t[k][a]);
    f.write(reinterpret_cast<const char*>(v), 48);
    f.write("\0\0", 2);
  }
}

void WriteAsciiStl(const std::string& path, const std::vector<Tri>& tris) {
  std::ofstream f(path);
  f.precision(17);
  f << "solid part\n";
  for (const Tri& t : tris) {
    f << "  facet normal 0 0 0\n    outer loop\n";
    for (const Vec3& p : t) f << "      vertex " << p.x() << " " << p.y() << " " << p.z() << "\n";
    f << "    endloop\n  endfacet\n";
  }
  f << "endsolid part\n";
}

// A box of half-sizes h about the origin: its corners, its 6 faces as quads (outward,
// counter-clockwise) and the 12 triangles of their fans.
std::vector<Vec3> BoxCorners(const Vec3& h) {
  std::vector<Vec3> c;
  for (int k = 0; k < 8; ++k) c.emplace_back(k & 1 ? h.x() : -h.x(), k & 2 ? h.y() : -h.y(), k & 4 ? h.z() : -h.z());
  return c;
}
const int kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

std::vector<Tri> BoxTriangles(const Vec3& h) {
  const std::vector<Vec3> c = BoxCorners(h);
  std::vector<Tri> out;
  for (const auto& q : kQuads) {
    out.push_back({c[q[0]], c[q[1]], c[q[2]]});
    out.push_back({c[q[0]], c[q[2]], c[q[3]]});
  }
  return out;
}

void WriteBoxObj(const std::string& path, const Vec3& h) {
  std::ofstream f(path);
  f << "# a box\no box\n";
  for (const Vec3& p : BoxCorners(h)) f << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  f << "vn 0 0 1\n";
  for (const auto& q : kQuads) f << "f " << q[0] + 1 << "//1 " << q[1] + 1 << "//1 " << q[2] + 1 << " " << q[3] - 8 << "\n";
}

// ---- A box on a slider passing a fixed box (as tests/analysis/clearance_test.cpp) ---

constexpr double kV = 0.1, kX = 0.1033;  // m/s; the fixed box's centre x (m); both boxes 20 mm

json SliderPastBox() {
  return {{"mechkin", 1},
          {"units", {{"length", "m"}, {"angle", "rad"}}},
          {"ground", {{"shapes", {{{"type", "box"}, {"size", {0.02, 0.02, 0.02}}, {"center", {kX, 0, 0}}}}}}},
          {"bodies", {{{"name", "slider"}, {"position", {0, 0, 0}}, {"shape", {{"type", "box"}, {"size", {0.02, 0.02, 0.02}}}}}}},
          {"joints", {{{"name", "P"}, {"type", "prismatic"}, {"body1", "ground"}, {"body2", "slider"},
                       {"origin", {0, 0, 0}}, {"axis", {1, 0, 0}}}}},
          {"drivers", {{{"name", "push"}, {"type", "translation"}, {"joint", "P"}, {"function", "0.1*t"}}}},
          {"analysis", {{"start", 0}, {"end", 1}, {"steps", 100}}},
          {"outputs", {{{"name", "gap"}, {"type", "clearance"}, {"body1", "slider"}, {"body2", "ground"}}}}};
}

Motion RunFile(const json& doc, const std::string& name) {
  const std::string path = Dir() + name;
  std::ofstream(path) << doc.dump(1);
  LoadResult r = LoadMechanismFile(path);
  EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  if (!r.ok()) return RunMotion(Model{}, AnalysisOptions{}, TableOptions{});
  return RunMotion(*r.model, AnalysisOptions{}, TableOptions{});
}

// Rows of `mesh` against `box`: the largest difference of the clearance, its rate and
// the closest points' x over the clear rows; the contacts' times.
void ExpectSameClearance(const Motion& box, const Motion& mesh, const char* what) {
  ASSERT_EQ(box.rows(), mesh.rows());
  const int gap = box.layout().Find("gap"), p1 = box.layout().Find(Quantity::ClearancePoint, 0, 0, 0);
  ASSERT_EQ(gap, mesh.layout().Find("gap"));
  double worst = 0, worst_rate = 0, worst_x = 0;
  int clear = 0;
  for (int r = 0; r < box.rows(); ++r) {
    if (!(box.at(r, gap) > 0)) continue;
    ++clear;
    worst = std::max(worst, std::abs(mesh.at(r, gap) - box.at(r, gap)));
    worst_rate = std::max(worst_rate, std::abs(mesh.at(r, gap + 1) - box.at(r, gap + 1)));
    worst_x = std::max({worst_x, std::abs(mesh.at(r, p1) - box.at(r, p1)), std::abs(mesh.at(r, p1 + 3) - box.at(r, p1 + 3))});
  }
  std::printf("[measured] %s: %d clear rows, clearance off the box's by %.2e m, rate by %.2e m/s, points' x by %.2e m\n",
              what, clear, worst, worst_rate, worst_x);
  EXPECT_GT(clear, 80);
  EXPECT_LT(worst, 1e-9) << what;
  EXPECT_LT(worst_rate, 1e-9) << what;
  EXPECT_LT(worst_x, 1e-9) << what;
  ASSERT_EQ(box.report.contacts.size(), 1u);
  ASSERT_EQ(mesh.report.contacts.size(), 1u) << what;
  const double t0 = (kX - 0.02) / kV;  // the faces meet
  std::printf("[measured] %s: contact at %.12f s, the box's at %.12f s, closed form %.12f s\n", what,
              mesh.report.contacts[0].t, box.report.contacts[0].t, t0);
  EXPECT_NEAR(mesh.report.contacts[0].t, t0, 1e-9) << what;
  EXPECT_NEAR(mesh.report.contacts[0].t, box.report.contacts[0].t, 1e-9) << what;
}

TEST(MeshClearance, ABoxMeshInEveryFormatMeasuresLikeTheBox) {
  const Motion box = RunFile(SliderPastBox(), "box.json");
  // The mesh in millimetres (exact in float32), the mechanism in metres: "scale" 0.001.
  const Vec3 h(10, 10, 10);
  WriteBinaryStl(Dir() + "box-binary.stl", BoxTriangles(h));
  WriteAsciiStl(Dir() + "box-ascii.STL", BoxTriangles(h));
  WriteBoxObj(Dir() + "box.obj", h);
  for (const char* file : {"box-binary.stl", "box-ascii.STL", "box.obj"}) {
    json doc = SliderPastBox();
    doc["bodies"][0]["shape"] = {{"type", "mesh"}, {"file", file}, {"scale", 0.001}};
    const Motion mesh = RunFile(doc, std::string(file) + ".json");
    ExpectSameClearance(box, mesh, file);
  }
}

TEST(MeshClearance, MeshAgainstMeshMeasuresLikeTwoBoxes) {
  const Motion box = RunFile(SliderPastBox(), "box.json");
  WriteAsciiStl(Dir() + "box-m.stl", BoxTriangles(Vec3(0.01, 0.01, 0.01)));
  json doc = SliderPastBox();
  doc["bodies"][0]["shape"] = {{"type", "mesh"}, {"file", "box-m.stl"}};
  doc["ground"]["shapes"][0] = {{"type", "mesh"}, {"file", Dir() + "box-m.stl"}, {"center", {kX, 0, 0}}};  // absolute path
  ExpectSameClearance(box, RunFile(doc, "mesh-mesh.json"), "mesh against mesh");
}

// ---- A tetrahedron against a sphere on a slider --------------------------------

constexpr double kA = 0.05, kR = 0.006;  // the tetrahedron's edge along the axes; the sphere's radius (m)
const Vec3 kStart(0.06, -0.02, 0.015), kDir = Vec3(-1, 0.5, 0.2).normalized();  // the sphere's centre at t = 0
constexpr double kSpeed = 0.05;                                                 // m/s

// The distance from p to the segment ab and to the triangle abc (the projection
// inside the triangle, else the nearest edge).
double SegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (p - a - s * (b - a)).norm();
}
double TriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a).normalized();
  const Vec3 q = p - n.dot(p - a) * n;
  const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                      (a - c).cross(q - c).dot(n) >= 0;
  if (inside) return std::abs(n.dot(p - a));
  return std::min({SegmentDistance(p, a, b), SegmentDistance(p, b, c), SegmentDistance(p, c, a)});
}
const Vec3 kTet[4] = {Vec3(0, 0, 0), Vec3(kA, 0, 0), Vec3(0, kA, 0), Vec3(0, 0, kA)};
const int kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

double TetGap(double t) {
  const Vec3 c = kStart + kSpeed * t * kDir;
  double d = INFINITY;
  for (const auto& f : kTetFaces) d = std::min(d, TriangleDistance(c, kTet[f[0]], kTet[f[1]], kTet[f[2]]));
  return d - kR;
}

TEST(MeshClearance, TetrahedronAgainstASphereMatchesThePointTriangleDistance) {
  {
    std::ofstream f(Dir() + "tet.obj");
    for (const Vec3& v : kTet) f << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
    for (const auto& t : kTetFaces) f << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  }
  const json doc = {
      {"mechkin", 1},
      {"units", {{"length", "m"}, {"angle", "rad"}}},
      {"ground", {{"shapes", {{{"type", "mesh"}, {"file", "tet.obj"}}}}}},
      {"bodies", {{{"name", "ball"}, {"position", {kStart.x(), kStart.y(), kStart.z()}}, {"shape", {{"type", "sphere"}, {"radius", kR}}}}}},
      {"joints", {{{"name", "P"}, {"type", "prismatic"}, {"body1", "ground"}, {"body2", "ball"},
                   {"origin", {kStart.x(), kStart.y(), kStart.z()}}, {"axis", {kDir.x(), kDir.y(), kDir.z()}}}}},
      {"drivers", {{{"name", "push"}, {"type", "translation"}, {"joint", "P"}, {"function", std::to_string(kSpeed) + "*t"}}}},
      {"analysis", {{"start", 0}, {"end", 1}, {"steps", 200}}},
      {"outputs", {{{"name", "gap"}, {"type", "clearance"}, {"body1", "ball"}, {"body2", "ground"}}}}};
  const Motion run = RunFile(doc, "tet.json");
  ASSERT_GT(run.rows(), 1);
  const int gap = run.layout().Find("gap");
  double worst = 0;
  int clear = 0;
  for (int r = 0; r < run.rows(); ++r) {
    const double t = run.at(r, 0);
    if (TetGap(t) <= 0) continue;
    ++clear;
    worst = std::max(worst, std::abs(run.at(r, gap) - TetGap(t)));
  }
  std::printf("[measured] tetrahedron mesh against a sphere: %d clear rows, off the closed form by %.2e m\n", clear, worst);
  EXPECT_GT(clear, 50);
  EXPECT_LT(worst, 1e-9);
  ASSERT_FALSE(run.report.contacts.empty());
  int first = 0;
  while (TetGap(run.at(first, 0)) > 0) ++first;
  double a = run.at(first - 1, 0), b = run.at(first, 0);
  while (b - a > 1e-14) (TetGap(0.5 * (a + b)) > 0 ? a : b) = 0.5 * (a + b);
  std::printf("[measured] tetrahedron contact at %.12f s, closed form %.12f s\n", run.report.contacts[0].t, a);
  // Not yet to 1e-9 s: FCL's GJK between the sphere (a capsule of length 0) and a
  // triangle reads a gap of ~1e-9 m as clear while the bodies already touch, so the
  // contact comes 2.6e-8 s late here (the box meshes' contacts are exact).
  EXPECT_NEAR(run.report.contacts[0].t, a, 1e-7);
}

// ---- The reader ----------------------------------------------------------------

TEST(MeshFile, ReadsTheTrianglesAndNamesTheProblems) {
  MeshSpec mesh;
  MeshFileProblem problem;
  ASSERT_TRUE(ParseMeshText("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2/2/2 3/3/3 -1/4/4\n", true, &mesh, &problem));
  ASSERT_EQ(mesh.triangles.size(), 2u);  // the quad's fan
  EXPECT_EQ(mesh.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_FALSE(ParseMeshText("v 0 0 0\nv 1 0 0\nf 1 2 5\n", true, &mesh, &problem));
  EXPECT_EQ(problem.message, "line 3: face vertex 5 is out of range: 2 vertices up to here");
  EXPECT_FALSE(ParseMeshText("v 0 0 0\nv 1 0 0\nv 0 1 0\n", true, &mesh, &problem));
  EXPECT_EQ(problem.message, "the file has no triangles");
  EXPECT_FALSE(ParseMeshText("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n", false, &mesh, &problem));
  EXPECT_EQ(problem.message, "line 2: the file ends inside this facet: truncated");
  EXPECT_FALSE(ParseMeshText("v 0 0 nan\n", true, &mesh, &problem));
  EXPECT_NE(problem.message.find("line 1: a vertex needs three finite numbers"), std::string::npos);
}

}  // namespace
}  // namespace mechkin
