// URDF import (issue 26, docs/import.md): the four-bar of mechanisms/planar-four-bar.json
// written in URDF's loop conventions imports to the same mobility, redundant equations
// and motion as the native file; mimic, limits, inertials, fixed joints; every
// malformed or unsupported element named with file:line, the element and the reason.
#include <gtest/gtest.h>

#include <cmath>

#include "import_test_util.hpp"

namespace mechkin::import_test {
namespace urdf_test {

using importers::ForeignFormat;

const double kC[3] = {0.13388096599604965, 0.07247123666099901, 0};  // joint C at the design pose (m)
const double kTracer[3] = {0.0769404829980248, 0.0735561264061878, 0};  // a coupler point off the line BC

std::string FourBarUrdf() { return Source("mechanisms/imported/four-bar.urdf"); }

// The URDF four-bar with its joint D replaced by `closure` (the tree A, B, C kept).
std::string FourBarWith(const std::string& closure) {
  std::string text = ReadText(FourBarUrdf());
  const auto d = text.find("  <joint name=\"D\"");
  const auto end = text.find("</joint>", d) + std::string("</joint>\n").size();
  return text.substr(0, d) + closure + text.substr(end);
}

// Joint C's path (closed form): the open branch of the crank-rocker, crank 60° + 360° t.
std::vector<std::array<double, 3>> ClosedFormC(const std::vector<double>& t) {
  const double a = 0.04, b = 0.12, c = 0.08, d = 0.10;
  std::vector<std::array<double, 3>> path;
  for (double s : t) {
    const double th = M_PI / 3 + 2 * M_PI * s;
    const double bx = a * std::cos(th), by = a * std::sin(th);
    const double e = std::hypot(bx - d, by), beta = std::atan2(by, bx - d);
    const double psi = std::acos((c * c + e * e - b * b) / (2 * c * e));
    path.push_back({d + c * std::cos(beta - psi), c * std::sin(beta - psi), 0});
  }
  return path;
}

// Both runs solved to 1e-14 of the size: the paths agree to 1e-12 of the 0.1 m frame.
void ExpectNativeMotion(const std::string& run_args, double tol = 1e-13) {
  const Table native = RunTable(Source("mechanisms/planar-four-bar.json") + " --tol 1e-14");
  const Table imported = RunTable(run_args + " --tol 1e-14");
  ASSERT_FALSE(imported.empty());
  ASSERT_EQ(imported.at("t").size(), 361u);
  EXPECT_LT(PathDistance(PointPath(imported, "coupler", kC), PointPath(native, "coupler", kC)), tol);
  EXPECT_LT(PathDistance(PointPath(imported, "coupler", kTracer), PointPath(native, "coupler", kTracer)), tol);
  EXPECT_LT(PathDistance(PointPath(imported, "coupler", kC), ClosedFormC(imported.at("t"))), tol);
}

TEST(UrdfImport, SecondParentIsKeptAsTheLoopClosingJoint) {
  const auto r = importers::ImportFile(FourBarUrdf());
  ASSERT_TRUE(r.ok()) << Errors(r);
  ASSERT_EQ(r.spec->bodies.size(), 3u);
  EXPECT_EQ(*r.spec->bodies[0].name, "crank");
  EXPECT_EQ(*r.spec->bodies[2].name, "rocker");
  ASSERT_EQ(r.spec->joints.size(), 4u);  // every joint kept
  EXPECT_EQ(*r.spec->joints[3].name, "D");
  EXPECT_EQ(*r.spec->joints[3].body1, "ground");
  EXPECT_EQ(*r.spec->joints[3].body2, "rocker");
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].ToString().find("four-bar.urdf:29: <joint name=\"D\">"), std::string::npos)
      << r.warnings[0].ToString();
  EXPECT_NE(r.warnings[0].message.find("second-parent convention"), std::string::npos);
  EXPECT_EQ(*r.spec->units->length, "m");
}

TEST(UrdfImport, FourBarChecksLikeTheNativeFile) {
  const auto native = CheckReport(Source("mechanisms/planar-four-bar.json"));
  const auto imported = CheckReport(FourBarUrdf());
  ASSERT_TRUE(imported.value("valid", false)) << imported.dump();
  EXPECT_EQ(imported["mobility"]["mobility"], 1);
  EXPECT_EQ(imported["mobility"]["redundant"], 3);
  EXPECT_EQ(imported["mobility"]["redundant_equations"], native["mobility"]["redundant_equations"]);
  EXPECT_EQ(imported["joints"], native["joints"]);
}

TEST(UrdfImport, FourBarRunsLikeTheNativeFile) { ExpectNativeMotion(FourBarUrdf() + " --drive A=2*pi*t"); }

TEST(UrdfImport, WrittenFileChecksAndRunsTheSame) {
  const std::string out = TempFile("four-bar-from-urdf.json", "");
  const auto r = Stdout("import " + FourBarUrdf() + " --drive A=2*pi*t -o " + out);
  ASSERT_EQ(r.code, 0);
  const std::string text = ReadText(out);
  EXPECT_NE(text.find("\"marker1\""), std::string::npos);
  EXPECT_NE(text.find("\"units\": {\"length\": \"m\", \"angle\": \"rad\", \"mass\": \"kg\"}"), std::string::npos) << text;
  const auto report = CheckReport(out);
  EXPECT_EQ(report["mobility"]["mobility"], 1);
  EXPECT_EQ(report["mobility"]["redundant"], 3);
  ExpectNativeMotion(out);
}

TEST(UrdfImport, LoopJointExtensionOpenAtZeroIsAssembled) {
  // The rocker drawn 5° off at C: the loop joint's two frames 7 mm apart at q = 0.
  std::string text = FourBarWith(
      "  <loop_joint name=\"D\" type=\"continuous\">\n    <link1 link=\"base\" xyz=\"0.1 0 0\" rpy=\"0 0 0\"/>\n"
      "    <link2 link=\"rocker\" xyz=\"0.08 0 0\" rpy=\"0 0 0\"/>\n    <axis xyz=\"0 0 1\"/>\n  </loop_joint>\n");
  const std::string drawn = "rpy=\"0 0 -2.328837092221133\"";
  const auto rpy = text.find(drawn);
  ASSERT_NE(rpy, std::string::npos);
  text.replace(rpy, drawn.size(), "rpy=\"0 0 -2.24\"");
  const std::string path = TempFile("loop-joint.urdf", text);
  const auto report = CheckReport(path);
  EXPECT_EQ(report["mobility"]["mobility"], 1) << report.dump();
  EXPECT_EQ(report["mobility"]["redundant"], 3);
  ExpectNativeMotion(path + " --drive A=2*pi*t");
}

TEST(UrdfImport, GazeboJointClosesTheLoop) {
  const std::string path = TempFile(
      "gazebo.urdf", FourBarWith("  <gazebo>\n    <joint name=\"D\" type=\"revolute\">\n      <parent>base</parent>"
                                 "<child>rocker</child>\n      <pose>0.08 0 0 0 0 0</pose>\n"
                                 "      <axis><xyz>0 0 1</xyz></axis>\n    </joint>\n  </gazebo>\n"));
  const auto r = importers::ImportFile(path);
  ASSERT_TRUE(r.ok()) << Errors(r);
  ASSERT_EQ(r.spec->joints.size(), 4u);
  EXPECT_EQ(CheckReport(path)["mobility"]["redundant"], 3);
  ExpectNativeMotion(path + " --drive A=2*pi*t");
}

TEST(UrdfImport, ClosingLinkPairIsASphericalClosure) {
  const std::string path = TempFile(
      "closing.urdf",
      FourBarWith("  <link name=\"closing_D_1\"/>\n  <link name=\"closing_D_2\"/>\n"
                  "  <joint name=\"f1\" type=\"fixed\"><parent link=\"base\"/><child link=\"closing_D_1\"/>"
                  "<origin xyz=\"0.1 0 0\"/></joint>\n"
                  "  <joint name=\"f2\" type=\"fixed\"><parent link=\"rocker\"/><child link=\"closing_D_2\"/>"
                  "<origin xyz=\"0.08 0 0\"/></joint>\n"));
  const auto r = importers::ImportFile(path);
  ASSERT_TRUE(r.ok()) << Errors(r);
  EXPECT_EQ(r.spec->bodies.size(), 3u);  // the closing links are welded into base and rocker
  ASSERT_EQ(r.spec->joints.size(), 4u);
  EXPECT_EQ(*r.spec->joints[3].type, "spherical");
  const auto report = CheckReport(path);
  EXPECT_EQ(report["mobility"]["mobility"], 1);
  EXPECT_EQ(report["mobility"]["redundant"], 1);  // R-R-R-S in a plane: the closure's out-of-plane equation
  ExpectNativeMotion(path + " --drive A=2*pi*t");
}

const char* kChain = R"(<robot name="arm">
  <link name="base"/>
  <link name="l1">
    <inertial><origin xyz="0.1 0 0" rpy="0 0 1.5707963267948966"/><mass value="2"/>
      <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/></inertial>
  </link>
  <link name="l2"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="tool"><inertial><origin xyz="0.5 0 0"/><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="slider"/>
  <link name="free"/>
  <link name="plate"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="2" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/>
    <limit effort="1" velocity="1"/><mimic joint="j1" multiplier="2" offset="0.5"/></joint>
  <joint name="weld" type="fixed"><parent link="l2"/><child link="tool"/><origin xyz="1 0 0"/></joint>
  <joint name="j3" type="prismatic"><parent link="base"/><child link="slider"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.3" effort="1" velocity="1"/></joint>
  <joint name="float" type="floating"><parent link="base"/><child link="free"/></joint>
  <joint name="flat" type="planar"><parent link="base"/><child link="plate"/><axis xyz="0 0 1"/></joint>
</robot>
)";

TEST(UrdfImport, LimitsMimicInertialFixedFloatingPlanar) {
  const auto r = Import(kChain, ForeignFormat::Urdf, "arm.urdf");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const MechanismSpec& s = *r.spec;
  ASSERT_EQ(s.bodies.size(), 5u);  // l1, l2 (with tool), slider, free, plate
  EXPECT_EQ(*s.bodies[1].name, "l2");
  ASSERT_EQ(s.joints.size(), 4u);  // j1, j2, j3, flat: the fixed joint welds, the floating one frees
  EXPECT_EQ((*s.joints[0].limits)[0].number, -1);
  EXPECT_EQ((*s.joints[0].limits)[1].number, 2);
  EXPECT_FALSE(s.joints[1].limits.has_value());  // <limit> without lower/upper: not a lock
  EXPECT_EQ(*s.joints[2].type, "prismatic");
  EXPECT_EQ((*s.joints[2].limits)[1].number, 0.3);
  EXPECT_EQ(*s.joints[3].type, "planar");
  ASSERT_EQ(s.couplers.size(), 1u);  // mimic: q2 − 2 q1 = 0.5
  EXPECT_EQ(s.couplers[0].joints, (std::vector<std::string>{"j2", "j1"}));
  EXPECT_EQ(s.couplers[0].coefficients[1].number, -2);
  EXPECT_EQ(s.couplers[0].constant->number, 0.5);
  // l1's inertia turned 90° about z: diag(1, 2, 3) → diag(2, 1, 3), centre at (0.1, 0, 0).
  const InertiaSpec& in = *s.bodies[0].inertia;
  EXPECT_NEAR((*in.moments)[0].c[0].number, 2, 1e-12);
  EXPECT_NEAR((*in.moments)[1].c[1].number, 1, 1e-12);
  EXPECT_NEAR(in.center->c[0].number, 0.1, 1e-15);
  // l2 + tool: 2 kg at x = 1.75 (l2's centre at 1, the tool's 0.5 beyond the tool at 2);
  // Izz = 0.1 + 0.1 + 2 · 1 kg · 0.75² (parallel axes).
  const InertiaSpec& merged = *s.bodies[1].inertia;
  EXPECT_EQ(merged.mass->number, 2);
  EXPECT_NEAR(merged.center->c[0].number, 1.75, 1e-15);
  EXPECT_NEAR((*merged.moments)[2].c[2].number, 0.2 + 2 * 0.5625, 1e-12);
  bool floating_named = false;
  for (const auto& w : r.warnings) floating_named |= w.ToString().find("arm.urdf:19: <joint name=\"float\">") == 0;
  EXPECT_TRUE(floating_named);
  const std::string file = TempFile("arm.urdf", kChain);
  EXPECT_TRUE(CheckReport(file).value("valid", false));
}

struct BadCase {
  const char* what;
  std::string text;
  int line;
  const char* element;
  const char* reason;
};

std::string Robot(const std::string& body) {
  return "<robot name=\"r\">\n  <link name=\"a\"/>\n  <link name=\"b\"/>\n" + body + "</robot>\n";
}
std::string J(const std::string& attrs, const std::string& inner) {
  return "  <joint " + attrs + ">" + inner + "</joint>\n";
}
const std::string kAB = "<parent link=\"a\"/><child link=\"b\"/>";

TEST(UrdfImport, MalformedAndUnsupportedNameFileLineElementReason) {
  const std::vector<BadCase> cases = {
      {"not XML", "<robot name=\"r\">\n<link name=\"a\">\n</robot>\n", 2, "", "not well-formed XML: XML_ERROR_MISMATCHED_ELEMENT"},
      {"unknown type", Robot(J("name=\"j\" type=\"helical\"", kAB)), 4, "<joint name=\"j\">", "unknown joint type 'helical'"},
      {"no child", Robot(J("name=\"j\" type=\"revolute\"", "<parent link=\"a\"/>")), 4, "<joint name=\"j\">", "needs <parent link> and <child link>"},
      {"undefined link", Robot(J("name=\"j\" type=\"fixed\"", "<parent link=\"a\"/><child link=\"c\"/>")), 4, "<joint name=\"j\">", "link 'c' is not defined"},
      {"zero axis", Robot(J("name=\"j\" type=\"revolute\"", kAB + "<axis xyz=\"0 0 0\"/>")), 4, "<axis>", "zero vector"},
      {"short origin", Robot(J("name=\"j\" type=\"revolute\"", kAB + "<origin xyz=\"1 2\"/>")), 4, "<origin>", "must be 3 numbers"},
      {"limits swapped", Robot(J("name=\"j\" type=\"revolute\"", kAB + "<limit lower=\"1\" upper=\"0\"/>")), 4, "<limit>", "is above upper limit"},
      {"mimic of nothing", Robot(J("name=\"j\" type=\"revolute\"", kAB + "<mimic joint=\"zz\"/>")), 4, "<mimic joint=\"zz\">", "names joint 'zz'"},
      {"no root", Robot(J("name=\"j\" type=\"fixed\"", kAB) + J("name=\"k\" type=\"fixed\"", "<parent link=\"b\"/><child link=\"a\"/>")), 2, "<link name=\"a\">", "cycle of parent joints"},
      {"duplicate joint", "<robot name=\"r\">\n  <link name=\"a\"/>\n  <link name=\"b\"/>\n  <link name=\"c\"/>\n" + J("name=\"j\" type=\"fixed\"", kAB) + J("name=\"j\" type=\"fixed\"", "<parent link=\"a\"/><child link=\"c\"/>") + "</robot>", 6, "<joint name=\"j\">", "a second joint named 'j'"},
      {"loop type", Robot(J("name=\"j\" type=\"fixed\"", kAB) + "  <loop_joint name=\"L\" type=\"screw\"><link1 link=\"a\"/><link2 link=\"b\"/></loop_joint>\n"), 5, "<loop_joint name=\"L\">", "unsupported loop joint type 'screw'"},
      {"inertial", "<robot name=\"r\">\n  <link name=\"a\"><inertial><mass value=\"1\"/></inertial></link>\n</robot>\n", 2, "<inertial>", "needs <mass value> and <inertia"},
      {"welded twice", Robot(J("name=\"j\" type=\"fixed\"", kAB) + "  <loop_joint name=\"L\" type=\"revolute\"><link1 link=\"a\"/><link2 link=\"b\"/></loop_joint>\n"), 5, "<loop_joint name=\"L\">", "already make one rigid body"},
      {"wrong root", "<sdf version=\"1.7\"/>", 1, "<sdf>", "root element of a URDF file is <robot>"},
  };
  for (const BadCase& c : cases) {
    const auto r = Import(c.text, ForeignFormat::Urdf, "bad.urdf");
    EXPECT_FALSE(r.ok()) << c.what;
    const std::string all = Errors(r);
    const std::string place = "bad.urdf:" + std::to_string(c.line) + ": " + c.element;
    EXPECT_NE(all.find(place), std::string::npos) << c.what << ": " << all;
    EXPECT_NE(all.find(c.reason), std::string::npos) << c.what << ": " << all;
  }
}

TEST(UrdfImport, CommandsExitOneAndWriteNothing) {
  const std::string bad = TempFile("bad.urdf", Robot(J("name=\"j\" type=\"helical\"", kAB)));
  const std::string out = TempFile("never-written.json", "") + ".x";
  for (const std::string& cmd : {"import " + bad + " -o " + out, "check " + bad, "run " + bad + " --drive j=t",
                                 "view " + bad + " -o " + out + ".html"}) {
    const auto r = mechkin_test::RunCli(cmd);
    EXPECT_EQ(r.code, 1) << cmd << ": " << r.out;
    EXPECT_NE(r.out.find("bad.urdf:4: <joint name=\"j\">: unknown joint type 'helical'"), std::string::npos) << r.out;
  }
  EXPECT_FALSE(std::ifstream(out).good());
  const auto drive = mechkin_test::RunCli("run " + FourBarUrdf() + " --drive Z=t");
  EXPECT_EQ(drive.code, 1);
  EXPECT_NE(drive.out.find("--drive Z: no moving joint named 'Z'"), std::string::npos) << drive.out;
  const auto native = mechkin_test::RunCli("run " + Source("mechanisms/planar-four-bar.json") + " --drive A=t");
  EXPECT_EQ(native.code, 1);
  EXPECT_NE(native.out.find("--drive and --span are for imported"), std::string::npos) << native.out;
}

TEST(UrdfImport, ViewAcceptsTheUrdfFile) {
  const std::string page = TempFile("four-bar-urdf.html", "");
  const auto r = mechkin_test::RunCli("view " + FourBarUrdf() + " --drive A=2*pi*t -o " + page);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_GT(ReadText(page).size(), 1000u);
}

TEST(ImportDetection, ExtensionAndContent) {
  using importers::DetectForeignFormat;
  EXPECT_EQ(DetectForeignFormat("a.urdf", "<?xml version=\"1.0\"?>\n<robot name=\"x\">"), ForeignFormat::Urdf);
  EXPECT_EQ(DetectForeignFormat("a.xml", "<!-- c --><mujoco model=\"m\">"), ForeignFormat::Mjcf);
  EXPECT_EQ(DetectForeignFormat("model.sdf", "<sdf version=\"1.7\">"), ForeignFormat::Sdf);
  EXPECT_EQ(DetectForeignFormat("noext", "<robot>"), ForeignFormat::Urdf);
  EXPECT_EQ(DetectForeignFormat("m.json", "{\"mechkin\": 1}"), ForeignFormat::None);
  EXPECT_EQ(DetectForeignFormat("a.FCStd", "PK\x03\x04"), ForeignFormat::FreeCad);
}

}  // namespace
}  // namespace mechkin::import_test

namespace mechkin::import_test {
namespace urdf_test {

// The mimic coupling holds along a run: l2's turn from the ground is θ1 + θ2 with
// θ2 = 2 θ1 + 0.5 — assembled from the written pose (θ2 = 0), then driven θ1 = t.
TEST(UrdfImport, MimicCouplingHoldsAlongTheRun) {
  const std::string path = TempFile("mimic.urdf", R"(<robot name="mimic">
  <link name="base"/><link name="l1"/><link name="l2"/>
  <joint name="j1" type="continuous"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/>
    <mimic joint="j1" multiplier="2" offset="0.5"/></joint>
</robot>
)");
  const auto report = CheckReport(path);
  EXPECT_EQ(report["mobility"]["mobility"], 1) << report.dump();
  const Table t = RunTable(path + " --drive j1=t --span 0:1:20");
  ASSERT_EQ(t.at("t").size(), 21u);
  double worst = 0;
  for (size_t k = 0; k < t.at("t").size(); ++k) {
    const double want = 3 * t.at("t")[k] + 0.5;  // θ1 + θ2
    const double e0 = t.at("l2.e0")[k], e3 = t.at("l2.e3")[k];
    worst = std::max(worst, std::abs(std::remainder(2 * std::atan2(e3, e0) - want, 2 * M_PI)));
    worst = std::max(worst, std::abs(t.at("l1.e3")[k] - std::sin(t.at("t")[k] / 2)));
  }
  EXPECT_LT(worst, 1e-10);
}

// Never a crash: every prefix of the bundled test files is imported (an error or a spec).
TEST(ImportRobustness, EveryPrefixOfTheFourBarsImportsOrFails) {
  for (const auto& [file, format] : {std::pair{"four-bar.urdf", ForeignFormat::Urdf},
                                     std::pair{"four-bar.xml", ForeignFormat::Mjcf},
                                     std::pair{"four-bar.sdf", ForeignFormat::Sdf}}) {
    const std::string text = ReadText(Source(std::string("mechanisms/imported/") + file));
    for (size_t n = 0; n < text.size(); ++n) {
      const auto r = Import(text.substr(0, n), format, file);
      EXPECT_TRUE(r.ok() || !r.errors.empty()) << n;
      for (const auto& e : r.errors) EXPECT_FALSE(e.message.empty());
    }
  }
}

}  // namespace
}  // namespace mechkin::import_test

namespace mechkin::import_test {
namespace urdf_test {

std::string SliderCrankUrdf() { return Source("mechanisms/imported/offset-slider-crank.urdf"); }

// The slider-crank: the native file's redundant equations, the piston's closed form
// x = a cos θ + √(b² − (a sin θ − e)²), and the guide's limits stop a run that leaves them.
TEST(UrdfImport, SliderCrankMatchesNativeClosedFormAndLimits) {
  const auto native = CheckReport(Source("mechanisms/offset-slider-crank.json"));
  const auto imported = CheckReport(SliderCrankUrdf());
  EXPECT_EQ(imported["mobility"]["redundant_equations"], native["mobility"]["redundant_equations"]);
  EXPECT_EQ(imported["mobility"]["mobility"], 1);
  const Table t = RunTable(SliderCrankUrdf() + " --drive bearing=2*pi*t");
  ASSERT_EQ(t.at("t").size(), 361u);
  double worst = 0;
  for (size_t k = 0; k < t.at("t").size(); ++k) {
    const double th = M_PI / 6 + 2 * M_PI * t.at("t")[k], a = 0.04, b = 0.12, e = 0.01;
    const double x = a * std::cos(th) + std::sqrt(b * b - (a * std::sin(th) - e) * (a * std::sin(th) - e));
    worst = std::max({worst, std::abs(t.at("slider.x")[k] - x), std::abs(t.at("slider.y")[k] - e)});
  }
  EXPECT_LT(worst, 1e-12);
  const auto r = importers::ImportFile(SliderCrankUrdf());
  ASSERT_TRUE(r.ok()) << Errors(r);
  EXPECT_NEAR(r.spec->bodies[1].inertia->mass->number, 0.3, 0);
  // Narrower limits: the slide from the design pose reaches −0.05 m on the way in.
  std::string text = ReadText(SliderCrankUrdf());
  text.replace(text.find("lower=\"-0.1\""), 12, "lower=\"-0.05\"");
  const auto stop = mechkin_test::RunCli("run " + TempFile("limited.urdf", text) + " --drive bearing=2*pi*t -o /dev/null");
  EXPECT_EQ(stop.code, 1);
  EXPECT_NE(stop.out.find("joint `guide` reaches its lower limit"), std::string::npos) << stop.out;
}

}  // namespace
}  // namespace mechkin::import_test

namespace mechkin::import_test {
namespace urdf_test {

TEST(UrdfImport, RunWithoutDriveNamesTheJoints) {
  const auto r = mechkin_test::RunCli("run " + FourBarUrdf());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("an imported file drives no joint: give --drive JOINT=FUNCTION"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("joints: A, B, C, D"), std::string::npos) << r.out;
  const auto span = mechkin_test::RunCli("run " + FourBarUrdf() + " --drive A=t --span 1:0:10");
  EXPECT_EQ(span.code, 2);
  EXPECT_NE(span.out.find("--span '1:0:10': expected START:END:STEPS"), std::string::npos) << span.out;
}

}  // namespace
}  // namespace mechkin::import_test
