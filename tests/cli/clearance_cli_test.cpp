// The clearance commands as a user runs them (issue 28): `run --on-contact stop`
// stops at the first contact with the exit code of the other stops (1, partial
// table), the default notes it and exits 0; `check --clearance` names the tightest
// pair and where; `expect min_clearance` fails the check (exit 1) naming the value
// and where; malformed shapes and a clearance output naming an unknown body are
// refused with their JSON pointer, the problem and a fix (exit 1).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace mechkin {
namespace clearance_cli_test {

using mechkin_test::RunCli;
using nlohmann::json;

std::string WriteTemp(const std::string& name, const json& doc) {
  const std::string p = ::testing::TempDir() + "/" + name;
  std::ofstream(p) << doc.dump(1);
  return p;
}

// A slider's box (20 mm) pushed at 100 mm/s towards a fixed box centred at x = 103.3 mm
// (20 mm): the faces meet at t = 0.833 s.
json SliderPastBox() {
  return {{"mechkin", 1},
          {"units", {{"length", "mm"}, {"angle", "deg"}}},
          {"ground", {{"shapes", {{{"type", "box"}, {"size", {20, 20, 20}}, {"center", {103.3, 0, 0}}}}}}},
          {"bodies", {{{"name", "slider"}, {"position", {0, 0, 0}}, {"shape", {{"type", "box"}, {"size", {20, 20, 20}}}}}}},
          {"joints", {{{"name", "P"}, {"type", "prismatic"}, {"body1", "ground"}, {"body2", "slider"},
                       {"origin", {0, 0, 0}}, {"axis", {1, 0, 0}}}}},
          {"drivers", {{{"name", "push"}, {"type", "translation"}, {"joint", "P"}, {"function", "100*t"}}}},
          {"analysis", {{"start", 0}, {"end", 1}, {"steps", 100}}},
          {"outputs", {{{"name", "gap"}, {"type", "clearance"}, {"body1", "slider"}, {"body2", "ground"}}}}};
}

TEST(ClearanceCli, OnContactStopStopsLikeALimitAndReportGoesOn) {
  const std::string file = WriteTemp("slider-box.json", SliderPastBox());
  const auto stop = RunCli("run " + file + " --on-contact stop --bodies '' --order 1");
  EXPECT_EQ(stop.code, 1) << stop.out;
  EXPECT_NE(stop.out.find("# PARTIAL TABLE: bodies `slider` and `ground` come into contact at t = 0.833 s "
                          "(driver `push` = 83.3 mm) at [93.3, 10, 10] mm, clearance output `gap`"),
            std::string::npos)
      << stop.out;
  EXPECT_NE(stop.out.find("the run stops there after 84 rows"), std::string::npos) << stop.out;
  EXPECT_NE(stop.out.find("gap [mm],gap_t [mm/s],gap.point1.x [mm]"), std::string::npos) << stop.out;
  const auto report = RunCli("run " + file + " --bodies '' --order 1 -o " + ::testing::TempDir() + "/gap.csv");
  EXPECT_EQ(report.code, 0) << report.out;
  EXPECT_NE(report.out.find("mechkin run: note: bodies `slider` and `ground` come into contact at t = 0.833 s"),
            std::string::npos)
      << report.out;
}

TEST(ClearanceCli, CheckClearanceAndExpectMinClearance) {
  json doc = SliderPastBox();
  doc["analysis"]["end"] = 0.5;  // the slider stops 33.3 mm short of the box's face
  const auto swept = RunCli("check --clearance " + WriteTemp("short.json", doc));
  EXPECT_EQ(swept.code, 0) << swept.out;
  EXPECT_NE(swept.out.find("clearance: tightest `slider` and `ground`: 33.3 mm at t = 0.5 s (driver `push` = 50 mm)"),
            std::string::npos)
      << swept.out;
  doc["expect"] = {{"min_clearance", 35}};
  const auto failed = RunCli("check " + WriteTemp("tight.json", doc));
  EXPECT_EQ(failed.code, 1) << failed.out;
  EXPECT_NE(failed.out.find("expect min_clearance = 35.0: FAILED (actual 33."), std::string::npos) << failed.out;
  EXPECT_NE(failed.out.find("`slider` and `ground`: 33.3 mm at t = 0.5 s"), std::string::npos) << failed.out;
  doc["expect"] = {{"min_clearance", 30}};
  EXPECT_EQ(RunCli("check " + WriteTemp("loose.json", doc)).code, 0);
}

TEST(ClearanceCli, MalformedShapesAndUnknownBodiesNamePointerMessageAndFix) {
  const std::string dir = std::string(MECHKIN_SOURCE_DIR) + "/tests/invalid/";
  struct Case { std::string file, error, fix; };
  const std::vector<Case> cases = {
      {"shape-negative-radius.json", "/bodies/0/shape/radius: 'radius' must be a positive number", "units/length"},
      {"convex-three-points.json", "/bodies/1/shapes/1/points: a convex shape needs at least 4 points, not 3",
       "4 or more corners"},
      {"shape-unknown-kind.json", "/bodies/2/shape/type: unknown shape 'cone'", "use box, cylinder, sphere, capsule, convex or mesh"},
      {"clearance-unknown-body.json", "/outputs/1/body2: unknown body 'slidr'", "did you mean 'slider'?"}};
  for (const Case& c : cases) {
    const auto r = RunCli("check " + dir + c.file);
    EXPECT_EQ(r.code, 1) << c.file;
    EXPECT_NE(r.out.find(c.error), std::string::npos) << c.file << ": " << r.out;
    EXPECT_NE(r.out.find("fix: "), std::string::npos) << c.file << ": " << r.out;
    EXPECT_NE(r.out.find(c.fix), std::string::npos) << c.file << ": " << r.out;
  }
  json doc = SliderPastBox();
  doc["ground"].erase("shapes");
  const auto unshaped = RunCli("check " + WriteTemp("unshaped.json", doc));
  EXPECT_EQ(unshaped.code, 1);
  EXPECT_NE(unshaped.out.find("/outputs/0/body2: 'ground' has no shape to measure a clearance from"),
            std::string::npos)
      << unshaped.out;
  doc = SliderPastBox();
  doc["bodies"][0]["shapes"] = {{{"type", "convex"}, {"points", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}}}};
  const auto flat = RunCli("check " + WriteTemp("flat.json", doc));
  EXPECT_EQ(flat.code, 1);
  EXPECT_NE(flat.out.find("/bodies/0/shapes/0/points: the convex shape's points have no hull: the points lie in one plane"),
            std::string::npos)
      << flat.out;
}

// Mesh shapes' files: each problem names the shape's "file" pointer, the file, what is
// wrong (the line of an OBJ face) and a fix, exit 1.
TEST(ClearanceCli, BadMeshFilesNamePointerFileProblemAndFix) {
  const std::string dir = ::testing::TempDir() + "/";
  std::ofstream(dir + "short.stl", std::ios::binary) << std::string(80, 'x') << std::string("\x02\0\0\0", 4)
                                                     << std::string(60, '\0');  // 2 triangles announced, 1.2 given
  std::ofstream(dir + "cut.stl") << "solid cut\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n";
  std::ofstream(dir + "bad-index.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n# a face\nf 1 2 4\n";
  std::ofstream(dir + "empty.obj") << "# only vertices\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
  std::ofstream(dir + "part.step") << "ISO-10303-21;\n";
  struct Case { std::string file, problem, fix; };
  const std::vector<Case> cases = {
      {"no-such-part.stl", "cannot open it: No such file or directory", "relative to the mechanism file's folder"},
      {"short.stl", "a binary STL whose header counts 2 triangles (184 bytes) but the file has 144 bytes: truncated",
       "export the part again"},
      {"cut.stl", "line 2: the file ends inside this facet: truncated", "endfacet"},
      {"bad-index.obj", "line 5: face vertex 4 is out of range: 3 vertices up to here", "counted from 1"},
      {"empty.obj", "the file has no triangles", "'f' lines"},
      {"part.step", "a mesh file must be STL (.stl) or OBJ (.obj)", "give an .stl or .obj file"}};
  for (const Case& c : cases) {
    json doc = SliderPastBox();
    doc["bodies"][0]["shapes"] = {{{"type", "box"}, {"size", {1, 1, 1}}}, {{"type", "mesh"}, {"file", c.file}}};
    const auto r = RunCli("check " + WriteTemp("mesh-" + c.file + ".json", doc));
    EXPECT_EQ(r.code, 1) << c.file << ": " << r.out;
    const std::string where = "/bodies/0/shapes/1/file: mesh file '" + c.file + "' (" + dir + c.file + "): " + c.problem;
    EXPECT_NE(r.out.find(where), std::string::npos) << where << "\n" << r.out;
    EXPECT_NE(r.out.find("fix: "), std::string::npos) << c.file << ": " << r.out;
    EXPECT_NE(r.out.find(c.fix), std::string::npos) << c.file << ": " << r.out;
    EXPECT_EQ(r.out.find("internal error"), std::string::npos) << r.out;
  }
  json doc = SliderPastBox();
  doc["bodies"][0]["shape"] = {{"type", "mesh"}};
  const auto nofile = RunCli("check " + WriteTemp("mesh-nofile.json", doc));
  EXPECT_EQ(nofile.code, 1);
  EXPECT_NE(nofile.out.find("/bodies/0/shape: a mesh shape needs 'file'"), std::string::npos) << nofile.out;
  std::ofstream(dir + "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  doc["bodies"][0]["shape"] = {{"type", "mesh"}, {"file", "tri.obj"}, {"scale", -2}};
  const auto negative = RunCli("check " + WriteTemp("mesh-negative.json", doc));
  EXPECT_EQ(negative.code, 1);
  EXPECT_NE(negative.out.find("/bodies/0/shape/scale: 'scale' must be a positive number, not -2"), std::string::npos)
      << negative.out;
  doc["bodies"][0]["shape"]["scale"] = 1;
  EXPECT_EQ(RunCli("check " + WriteTemp("mesh-ok.json", doc)).code, 0);
}

}  // namespace
}  // namespace mechkin
