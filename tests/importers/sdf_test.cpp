// SDFormat import (issue 26, docs/import.md): a four-bar whose links are placed through
// relative_to frames imports to the native file's mobility, redundant equations and
// motion; joint types, axes expressed in other frames, screw pitch, static models,
// frames as joint ends; malformed and unsupported elements named with file:line.
#include <gtest/gtest.h>

#include <cmath>

#include "import_test_util.hpp"

namespace mechkin::import_test {
namespace sdf_test {

using importers::ForeignFormat;

const double kC[3] = {0.13388096599604965, 0.07247123666099901, 0};
const double kTracer[3] = {0.0769404829980248, 0.0735561264061878, 0};

std::string FourBarSdf() { return Source("mechanisms/imported/four-bar.sdf"); }

TEST(SdfImport, FourBarLoopChecksLikeTheNativeFile) {
  const auto r = importers::ImportFile(FourBarSdf());
  ASSERT_TRUE(r.ok()) << Errors(r);
  ASSERT_EQ(r.spec->joints.size(), 4u);
  const auto native = CheckReport(Source("mechanisms/planar-four-bar.json"));
  const auto imported = CheckReport(FourBarSdf());
  EXPECT_EQ(imported["mobility"]["mobility"], 1);
  EXPECT_EQ(imported["mobility"]["redundant"], 3);
  EXPECT_EQ(imported["mobility"]["redundant_equations"], native["mobility"]["redundant_equations"]);
}

TEST(SdfImport, FourBarRunsLikeTheNativeFile) {
  // Both solved to 1e-14 of the size: the paths agree to 1e-12 of the 0.1 m frame.
  const Table native = RunTable(Source("mechanisms/planar-four-bar.json") + " --tol 1e-14");
  const Table imported = RunTable(FourBarSdf() + " --drive A=2*pi*t --tol 1e-14");
  ASSERT_EQ(imported.at("t").size(), 361u);
  EXPECT_LT(PathDistance(PointPath(imported, "coupler", kC), PointPath(native, "coupler", kC)), 1e-13);
  EXPECT_LT(PathDistance(PointPath(imported, "coupler", kTracer), PointPath(native, "coupler", kTracer)), 1e-13);
}

const char* kTypes = R"(<sdf version="1.9">
  <model name="types">
    <pose>1 0 0 0 0 0</pose>
    <link name="base"/>
    <link name="ball"><pose>0 1 0 0 0 0</pose></link>
    <link name="cross"><pose rotation_format="quat_xyzw">0 2 0 0 0 0.7071067811865476 0.7071067811865476</pose></link>
    <link name="nut"><pose degrees="true">0 3 0 90 0 0</pose></link>
    <link name="bolted"><pose>0 4 0 0 0 0</pose></link>
    <frame name="tip" attached_to="nut"><pose>0 0 0.5 0 0 0</pose></frame>
    <joint name="fix" type="fixed"><parent>world</parent><child>base</child></joint>
    <joint name="sph" type="ball"><parent>base</parent><child>ball</child></joint>
    <joint name="uj" type="universal"><parent>base</parent><child>cross</child>
      <axis><xyz>1 0 0</xyz></axis><axis2><xyz>0 1 0</xyz></axis2></joint>
    <joint name="sc" type="screw"><parent>base</parent><child>tip</child><screw_thread_pitch>0.002</screw_thread_pitch>
      <axis><xyz expressed_in="__model__">0 1 0</xyz><limit><lower>-1</lower><upper>2</upper></limit></axis></joint>
    <joint name="bolt" type="fixed"><parent>nut</parent><child>bolted</child></joint>
  </model>
</sdf>
)";

TEST(SdfImport, TypesAxesPitchFramesAndFixedJoints) {
  const auto r = Import(kTypes, ForeignFormat::Sdf, "types.sdf");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const MechanismSpec& s = *r.spec;
  ASSERT_EQ(s.bodies.size(), 3u);  // base is ground's; bolted is the nut's
  ASSERT_EQ(s.joints.size(), 3u);
  EXPECT_EQ(*s.joints[0].type, "spherical");
  EXPECT_EQ(*s.joints[0].body1, "ground");
  EXPECT_EQ(*s.joints[1].type, "universal");
  EXPECT_EQ(*s.joints[2].type, "screw");
  EXPECT_EQ(*s.joints[2].body2, "nut");  // the frame 'tip' is attached to the nut
  EXPECT_EQ(s.joints[2].pitch->number, 0.002);
  EXPECT_EQ((*s.joints[2].limits)[1].number, 2);
  // The screw axis is the model's y: in the nut (turned 90° about x) it is the nut's −z... at the tip.
  const MarkerSpec& m = s.bodies[2].markers[0];
  EXPECT_NEAR(m.axis->c[2].number, -1, 1e-12);
  EXPECT_NEAR(m.point->c[2].number, 0.5, 1e-12);
  // The cross turned 90° about z (quat_xyzw), in a model moved 1 along x.
  EXPECT_NEAR(s.bodies[1].position->c[0].number, 1, 1e-15);
  EXPECT_NEAR(s.bodies[1].orientation->matrix[0][1].number, -1, 1e-12);
  bool frame_named = false;
  for (const auto& w : r.warnings) frame_named |= w.message.find("read as joining the links") != std::string::npos;
  EXPECT_TRUE(frame_named);
  EXPECT_TRUE(CheckReport(TempFile("types.sdf", kTypes)).value("valid", false));
}

struct BadCase {
  const char* what;
  std::string model;  // inside <model name="m">, from line 3
  int line;
  const char* element;
  const char* reason;
};

TEST(SdfImport, MalformedAndUnsupportedNameFileLineElementReason) {
  const std::string l = "    <link name=\"a\"/>\n";  // line 3
  const std::vector<BadCase> cases = {
      {"revolute2", l + "    <joint name=\"j\" type=\"revolute2\"><parent>world</parent><child>a</child></joint>\n", 4, "<joint name=\"j\">", "unsupported joint type 'revolute2'"},
      {"gearbox", l + "    <joint name=\"j\" type=\"gearbox\"><parent>world</parent><child>a</child></joint>\n", 4, "<joint name=\"j\">", "unsupported joint type 'gearbox'"},
      {"no child", l + "    <joint name=\"j\" type=\"revolute\"><parent>world</parent></joint>\n", 4, "<joint name=\"j\">", "needs <parent> and <child>"},
      {"unknown link", l + "    <joint name=\"j\" type=\"revolute\"><parent>world</parent><child>zz</child></joint>\n", 4, "<child>", "'zz' is no link or frame"},
      {"bad pose", "    <link name=\"a\"><pose>1 2 3</pose></link>\n", 3, "<pose>", "must hold 6 numbers"},
      {"relative_to", "    <link name=\"a\"><pose relative_to=\"nowhere\">0 0 0 0 0 0</pose></link>\n", 3, "<link name=\"a\">", "relative_to 'nowhere': no such frame"},
      {"cycle", "    <frame name=\"f\"><pose relative_to=\"g\"/></frame>\n    <frame name=\"g\"><pose relative_to=\"f\"/></frame>\n" + l + "    <link name=\"b\"><pose relative_to=\"f\"/></link>\n", 3, "<frame name=\"f\">", "is a cycle"},
      {"screw pitch", l + "    <joint name=\"j\" type=\"screw\"><parent>world</parent><child>a</child></joint>\n", 4, "<joint name=\"j\">", "needs <screw_thread_pitch>"},
      {"universal axes", l + "    <joint name=\"j\" type=\"universal\"><parent>world</parent><child>a</child><axis><xyz>1 0 0</xyz></axis><axis2><xyz>1 1 0</xyz></axis2></joint>\n", 4, "<joint name=\"j\">", "not perpendicular"},
      {"nested model", l + "    <model name=\"inner\"/>\n", 4, "<model name=\"inner\">", "nested model"},
      {"duplicate", l + l, 4, "<link name=\"a\">", "the name 'a' is taken"},
      {"zero axis", l + "    <joint name=\"j\" type=\"revolute\"><parent>world</parent><child>a</child><axis><xyz>0 0 0</xyz></axis></joint>\n", 4, "<xyz>", "zero vector"},
  };
  for (const BadCase& c : cases) {
    const std::string text = "<sdf version=\"1.9\">\n  <model name=\"m\">\n" + c.model + "  </model>\n</sdf>\n";
    const auto r = Import(text, ForeignFormat::Sdf, "bad.sdf");
    EXPECT_FALSE(r.ok()) << c.what;
    const std::string all = Errors(r);
    const std::string place = "bad.sdf:" + std::to_string(c.line) + ": " + c.element;
    EXPECT_NE(all.find(place), std::string::npos) << c.what << ": " << all;
    EXPECT_NE(all.find(c.reason), std::string::npos) << c.what << ": " << all;
  }
  const auto two = Import("<sdf version=\"1.9\">\n<model name=\"a\"/>\n<model name=\"b\"/>\n</sdf>\n", ForeignFormat::Sdf,
                          "two.sdf");
  EXPECT_NE(Errors(two).find("two.sdf:1: <sdf>: more than one moving <model>"), std::string::npos) << Errors(two);
}

TEST(SdfImport, CommandsExitOneAndWriteNothing) {
  const std::string bad = TempFile("bad.sdf", "<sdf version=\"1.9\">\n  <model name=\"m\">\n    <link name=\"a\"/>\n"
                                              "    <joint name=\"j\" type=\"gearbox\"><parent>world</parent><child>a</child>"
                                              "</joint>\n  </model>\n</sdf>\n");
  const std::string out = TempFile("never-written-sdf.json", "") + ".x";
  for (const std::string& cmd : {"import " + bad + " -o " + out, "check " + bad}) {
    const auto r = mechkin_test::RunCli(cmd);
    EXPECT_EQ(r.code, 1) << cmd << ": " << r.out;
    EXPECT_NE(r.out.find("bad.sdf:4: <joint name=\"j\">: unsupported joint type 'gearbox'"), std::string::npos) << r.out;
  }
  EXPECT_FALSE(std::ifstream(out).good());
}

}  // namespace
}  // namespace mechkin::import_test

namespace mechkin::import_test {
namespace sdf_test {

// Files in the wild: "--" inside a comment is read; stray text after the root element is
// skipped with a warning naming the line, as the formats' own parsers do.
TEST(SdfImport, ToleratesWhatTheFormatsOwnParsersRead) {
  std::string text = ReadText(FourBarSdf());
  text.insert(text.find("<sdf"), "<!-- generated -- by hand -->\n");
  text += "\ntrailing words\n";
  const auto r = Import(text, ForeignFormat::Sdf, "wild.sdf");
  ASSERT_TRUE(r.ok()) << Errors(r);
  bool skipped = false;
  for (const auto& w : r.warnings) skipped |= w.ToString().find("text after the root element's </sdf> is skipped") != std::string::npos;
  EXPECT_TRUE(skipped);
  const auto empty = mechkin_test::RunCli("check " + TempFile("empty.urdf", ""));
  EXPECT_EQ(empty.code, 1);
  EXPECT_NE(empty.out.find("empty.urdf"), std::string::npos);
  EXPECT_NE(empty.out.find("not well-formed XML"), std::string::npos) << empty.out;
}

}  // namespace
}  // namespace mechkin::import_test
