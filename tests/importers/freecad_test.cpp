// FreeCAD Assembly import (issue 26, docs/import.md): tests/data/import/four-bar-Document.xml
// zipped into an .FCStd imports to the native four-bar's mobility, redundant equations and
// motion (a revolute saved with opposite z axes included); unsupported joint kinds are
// named with what they would need; malformed archives and documents are refused.
#include <gtest/gtest.h>
#include <zip.h>

#include <cmath>

#include "import_test_util.hpp"

namespace mechkin::import_test {
namespace freecad_test {

using importers::ForeignFormat;

const double kC[3] = {0.13388096599604965, 0.07247123666099901, 0};
const double kTracer[3] = {0.0769404829980248, 0.0735561264061878, 0};

std::string FourBarDocument() { return ReadText(Source("tests/data/import/four-bar-Document.xml")); }

TEST(FreeCadImport, FourBarChecksAndRunsLikeTheNativeFile) {
  const std::string path = Fcstd("four-bar.FCStd", FourBarDocument());
  const auto r = importers::ImportFile(path);
  ASSERT_TRUE(r.ok()) << Errors(r);
  ASSERT_EQ(r.spec->bodies.size(), 3u);  // the frame is grounded
  EXPECT_EQ(*r.spec->bodies[0].name, "crank");
  ASSERT_EQ(r.spec->joints.size(), 4u);
  EXPECT_EQ(*r.spec->joints[2].name, "C");
  bool flipped = false;
  for (const auto& w : r.warnings)
    flipped |=
        w.ToString().find("<Object name=\"Joint002\">: the joint's two frames have opposite z") != std::string::npos;
  EXPECT_TRUE(flipped);
  const auto native = CheckReport(Source("mechanisms/planar-four-bar.json"));
  const auto imported = CheckReport(path);
  EXPECT_EQ(imported["mobility"]["mobility"], 1) << imported.dump();
  EXPECT_EQ(imported["mobility"]["redundant"], 3);
  EXPECT_EQ(imported["mobility"]["redundant_equations"], native["mobility"]["redundant_equations"]);
  // Both solved to 1e-14 of the size: the paths agree to 1e-12 of the 0.1 m frame.
  const Table nt = RunTable(Source("mechanisms/planar-four-bar.json") + " --tol 1e-14");
  const Table it = RunTable(path + " --drive A=2*pi*t --tol 1e-14");
  ASSERT_EQ(it.at("t").size(), 361u);
  EXPECT_LT(PathDistance(PointPath(it, "coupler", kC), PointPath(nt, "coupler", kC)), 1e-13);
  EXPECT_LT(PathDistance(PointPath(it, "coupler", kTracer), PointPath(nt, "coupler", kTracer)), 1e-13);
}

// The four-bar document with joint D's type index replaced.
std::string WithJointType(int index) {
  std::string doc = FourBarDocument();
  const auto d = doc.find("<Object name=\"Joint003\">");
  const std::string was = "<Integer value=\"1\"/>";
  const auto k = doc.find(was, d);
  doc.replace(k, was.size(), "<Integer value=\"" + std::to_string(index) + "\"/>");
  return doc;
}

int LineOf(const std::string& text, const std::string& what) {
  const auto k = text.find(what);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(k), '\n'));
}

TEST(FreeCadImport, UnsupportedJointKindsSayWhatTheyNeed) {
  const std::string doc = FourBarDocument();
  const int line = LineOf(doc, "<Object name=\"Joint003\">");
  const std::pair<int, const char*> kinds[] = {
      {5, "Distance joint is not supported"},
      {6, "Parallel joint is not supported"},
      {7, "Perpendicular joint is not supported"},
      {8, "Angle joint is not supported"},
      {9, "RackPinion joint is not supported — it would need the revolute and prismatic"},
      {10, "Screw joint is not supported"},
      {11, "Gears joint is not supported — it would need the two revolute joints it couples"},
      {12, "Belt joint is not supported"},
      {13, "JointType 13 is not in its list of 13 joint types"}};
  for (const auto& [index, reason] : kinds) {
    const auto r = Import(WithJointType(index), ForeignFormat::FreeCad, "a.FCStd:Document.xml");
    EXPECT_FALSE(r.ok()) << index;
    const std::string all = Errors(r);
    const int at = index == 13 ? LineOf(doc, "<Object name=\"Joint003\">") + 3 : line;
    EXPECT_NE(all.find("a.FCStd:Document.xml:" + std::to_string(at) + ": "), std::string::npos) << index << ": " << all;
    EXPECT_NE(all.find(reason), std::string::npos) << index << ": " << all;
  }
}

// `text` with `from` replaced by `to` once, at or after `after` (the test fails when absent).
std::string Replaced(std::string text, const std::string& from, const std::string& to, const std::string& after = "") {
  const auto start = after.empty() ? 0 : text.find(after);
  const auto k = start == std::string::npos ? start : text.find(from, start);
  EXPECT_NE(k, std::string::npos) << from;
  if (k != std::string::npos) text.replace(k, from.size(), to);
  return text;
}

// The coupler's path of an imported four-bar document against the native file's (m).
double CouplerPathError(const std::string& fcstd) {
  const Table nt = RunTable(Source("mechanisms/planar-four-bar.json") + " --tol 1e-14");
  const Table it = RunTable(fcstd + " --drive A=2*pi*t --tol 1e-14");
  if (it.count("t") == 0 || it.at("t").size() != 361u) return INFINITY;
  return PathDistance(PointPath(it, "coupler", kTracer), PointPath(nt, "coupler", kTracer));
}

// JointType is an index into the joint's own CustomEnumList when the file has one.
TEST(FreeCadImport, JointTypeIsReadFromTheFilesOwnEnumList) {
  const std::string was = "<Integer value=\"1\"/>", at = "<Object name=\"Joint003\">";
  const std::string reordered =
      Replaced(FourBarDocument(), was,
               "<Integer value=\"2\" CustomEnum=\"true\"/><CustomEnumList count=\"3\"><Enum "
               "value=\"Fixed\"/><Enum value=\"Slider\"/><Enum value=\"Revolute\"/></CustomEnumList>",
               at);
  const auto r = Import(reordered, ForeignFormat::FreeCad, "a.FCStd:Document.xml");
  ASSERT_TRUE(r.ok()) << Errors(r);
  ASSERT_EQ(r.spec->joints.size(), 4u);
  EXPECT_EQ(*r.spec->joints[3].name, "D");
  EXPECT_EQ(*r.spec->joints[3].type, "revolute");  // index 2 of the file's list, not FreeCAD's Cylindrical
  const std::string unknown = Replaced(
      FourBarDocument(), was,
      "<Integer value=\"0\" CustomEnum=\"true\"/><CustomEnumList count=\"1\"><Enum value=\"Hinge\"/></CustomEnumList>",
      at);
  const auto u = Import(unknown, ForeignFormat::FreeCad, "a.FCStd:Document.xml");
  EXPECT_FALSE(u.ok());
  EXPECT_NE(Errors(u).find("JointType 'Hinge' is not one of FreeCAD 1.x's joint types"), std::string::npos)
      << Errors(u);
}

// Activated=false and Suppressed=true joints are skipped, each with a warning naming it.
TEST(FreeCadImport, DeactivatedAndSuppressedJointsAreSkippedWithAWarning) {
  const std::string was = "<Property name=\"JointType\"";
  for (const auto& [prop, says] :
       {std::pair<std::string, std::string>{"Activated\" type=\"App::PropertyBool\"><Bool value=\"false\"/>",
                                            "Revolute joint 'D' is not activated"},
        {"Suppressed\" type=\"App::PropertyBool\"><Bool value=\"true\"/>",
         "suppressed Revolute joint 'D': not imported"}}) {
    const std::string doc = Replaced(FourBarDocument(), was, "<Property name=\"" + prop + "</Property>" + was,
                                     "<Object name=\"Joint003\">");
    const auto r = Import(doc, ForeignFormat::FreeCad, "a.FCStd:Document.xml");
    ASSERT_TRUE(r.ok()) << Errors(r);
    EXPECT_EQ(r.spec->joints.size(), 3u) << says;
    bool warned = false;
    for (const auto& w : r.warnings) warned |= w.ToString().find(says) != std::string::npos;
    EXPECT_TRUE(warned) << says;
  }
}

// An App::Link part is placed by its LinkPlacement; a part inside an App::Part container
// (Reference "RockerPart.Rocker.Vertex1") moves as the container, its joint frames
// relative to the inner object.
TEST(FreeCadImport, LinksAndPartContainersArePlacedAsFreeCadPlacesThem) {
  const std::string rocker_placement =
      "<Property name=\"Placement\" type=\"App::PropertyPlacement\"><PropertyPlacement Px=\"100.0\"";
  const std::string linked = Replaced(FourBarDocument(), rocker_placement,
                                      "<Property name=\"Placement\" type=\"App::PropertyPlacement\"><PropertyPlacement "
                                      "Px=\"500\" Py=\"0\" Pz=\"0\" Q0=\"0\" "
                                      "Q1=\"0\" Q2=\"0\" Q3=\"1\"/></Property><Property name=\"LinkPlacement\" "
                                      "type=\"App::PropertyPlacement\"><PropertyPlacement Px=\"100.0\"",
                                      "<Object name=\"Rocker\">");
  const auto r = Import(linked, ForeignFormat::FreeCad, "a.FCStd:Document.xml");
  ASSERT_TRUE(r.ok()) << Errors(r);
  ASSERT_EQ(*r.spec->bodies[2].name, "rocker");
  EXPECT_NEAR(r.spec->bodies[2].position->c[0].number, 0.1, 1e-15);  // LinkPlacement's 100 mm, not Placement's 500
  EXPECT_LT(CouplerPathError(Fcstd("linked.FCStd", linked)), 1e-12);
  // The rocker inside RockerPart at x = 100 mm, itself at the origin of the part.
  std::string nested = Replaced(
      FourBarDocument(), "<Object type=\"App::FeaturePython\" name=\"GroundedJoint\"/>",
      "<Object type=\"App::Part\" name=\"RockerPart\"/><Object type=\"App::FeaturePython\" name=\"GroundedJoint\"/>");
  nested =
      Replaced(nested, "<PropertyPlacement Px=\"100.0\"", "<PropertyPlacement Px=\"0\"", "<Object name=\"Rocker\">");
  nested = Replaced(
      nested, "<Object name=\"GroundedJoint\">",
      "<Object name=\"RockerPart\"><Properties Count=\"2\"><Property name=\"Label\" type=\"App::PropertyString\">"
      "<String value=\"rocker_part\"/></Property><Property name=\"Placement\" type=\"App::PropertyPlacement\">"
      "<PropertyPlacement Px=\"100\" Py=\"0\" Pz=\"0\" Q0=\"0\" Q1=\"0\" Q2=\"0\" Q3=\"1\"/></Property>"
      "</Properties></Object><Object name=\"GroundedJoint\">");
  nested = Replaced(nested, "\"Rocker.Vertex2\"", "\"RockerPart.Rocker.Vertex2\"");
  nested = Replaced(nested, "\"Rocker.Vertex1\"", "\"RockerPart.Rocker.Vertex1\"");
  const auto n = Import(nested, ForeignFormat::FreeCad, "a.FCStd:Document.xml");
  ASSERT_TRUE(n.ok()) << Errors(n);
  ASSERT_EQ(n.spec->bodies.size(), 3u);
  EXPECT_EQ(*n.spec->bodies[2].name, "rocker_part");
  EXPECT_NEAR(n.spec->bodies[2].position->c[0].number, 0.1, 1e-15);
  EXPECT_LT(CouplerPathError(Fcstd("nested.FCStd", nested)), 1e-12);
}

TEST(FreeCadImport, MalformedArchivesAndDocumentsAreRefused) {
  const std::string not_zip = TempFile("broken.FCStd", "this is not a zip");
  const auto a = importers::ImportFile(not_zip);
  EXPECT_NE(Errors(a).find("broken.FCStd: not a readable zip archive"), std::string::npos) << Errors(a);
  const std::string empty = Fcstd("other.FCStd", "");
  std::remove(empty.c_str());
  int code = 0;
  zip_t* z = zip_open(empty.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
  static const char kText[] = "x";
  zip_file_add(z, "GuiDocument.xml", zip_source_buffer(z, kText, 1, 0), 0);
  zip_close(z);
  EXPECT_NE(Errors(importers::ImportFile(empty)).find("no readable Document.xml"), std::string::npos);
  std::string doc = FourBarDocument();
  const auto ref = doc.find("<Sub value=\"Crank.Edge1\"/>");
  doc.replace(doc.find("name=\"Assembly\"", ref - 80), 15, "name=\"Nothing\"");
  const auto r = Import(doc, ForeignFormat::FreeCad, "b.FCStd:Document.xml");
  EXPECT_NE(Errors(r).find("Reference2: no object 'Nothing'"), std::string::npos) << Errors(r);
  const auto cli = mechkin_test::RunCli("check " + Fcstd("gears.FCStd", WithJointType(11)));
  EXPECT_EQ(cli.code, 1);
  EXPECT_NE(cli.out.find("gears.FCStd:Document.xml:"), std::string::npos) << cli.out;
}

// An unsupported joint: import, check and run exit 1 naming the place and the reason; no file is written.
TEST(FreeCadImport, CommandsExitOneAndWriteNothing) {
  const std::string gears = Fcstd("gears-cli.FCStd", WithJointType(11));
  const std::string out = TempFile("never-written-freecad.json", "") + ".x";
  const int line = LineOf(FourBarDocument(), "<Object name=\"Joint003\">");
  for (const std::string& cmd : {"import " + gears + " -o " + out, "check " + gears, "run " + gears + " --drive A=t"}) {
    const auto r = mechkin_test::RunCli(cmd);
    EXPECT_EQ(r.code, 1) << cmd << ": " << r.out;
    EXPECT_NE(r.out.find("gears-cli.FCStd:Document.xml:" + std::to_string(line) + ": "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Gears joint is not supported"), std::string::npos) << r.out;
  }
  EXPECT_FALSE(std::ifstream(out).good());
}

}  // namespace freecad_test
}  // namespace mechkin::import_test
