// MJCF import (issue 26, docs/import.md): the four-bar of mechanisms/planar-four-bar.json
// closed by a <connect> equality imports to the mobility and redundant equations of the
// same mechanism written natively (C spherical) and runs the native motion; angles,
// orientation forms, default classes, ref, couplings, welds, several joints in a body;
// every malformed or unsupported element named with file:line, the element and the reason.
#include <gtest/gtest.h>

#include <cmath>

#include "import_test_util.hpp"

namespace mechkin::import_test {
namespace mjcf_test {

using importers::ForeignFormat;

const double kC[3] = {0.13388096599604965, 0.07247123666099901, 0};
const double kTracer[3] = {0.0769404829980248, 0.0735561264061878, 0};

std::string FourBarXml() { return Source("mechanisms/imported/four-bar.xml"); }

// mechanisms/planar-four-bar.json with joint C spherical: the native twin of the MJCF file.
std::string NativeWithSphericalC() {
  auto j = nlohmann::json::parse(ReadText(Source("mechanisms/planar-four-bar.json")));
  j["joints"][2]["type"] = "spherical";
  j["joints"][2].erase("axis");
  // In the MJCF file's order: the tree joints A, B, D, then the equality C (rank is taken in file order).
  const auto c = j["joints"][2];
  j["joints"].erase(2);
  j["joints"].push_back(c);
  j["expect"] = nlohmann::json::object();
  return TempFile("four-bar-spherical-c.json", j.dump());
}

// Both runs solved to 1e-14 of the size: the paths agree to 1e-12 of the 0.1 m frame.
void ExpectNativeMotion(const std::string& run_args, double tol = 1e-13) {
  const Table native = RunTable(Source("mechanisms/planar-four-bar.json") + " --tol 1e-14");
  const Table imported = RunTable(run_args + " --tol 1e-14");
  ASSERT_FALSE(imported.empty());
  ASSERT_EQ(imported.at("t").size(), 361u);
  EXPECT_LT(PathDistance(PointPath(imported, "coupler", kC), PointPath(native, "coupler", kC)), tol);
  EXPECT_LT(PathDistance(PointPath(imported, "coupler", kTracer), PointPath(native, "coupler", kTracer)), tol);
  EXPECT_LT(PathDistance(PointPath(imported, "rocker", kC), PointPath(native, "rocker", kC)), tol);
}

TEST(MjcfImport, ConnectClosesTheFourBar) {
  const auto r = importers::ImportFile(FourBarXml());
  ASSERT_TRUE(r.ok()) << Errors(r);
  ASSERT_EQ(r.spec->bodies.size(), 3u);
  ASSERT_EQ(r.spec->joints.size(), 4u);
  EXPECT_EQ(*r.spec->joints[2].name, "D");
  EXPECT_EQ(*r.spec->joints[3].name, "C");
  EXPECT_EQ(*r.spec->joints[3].type, "spherical");
  EXPECT_EQ(*r.spec->joints[3].body1, "coupler");
  EXPECT_EQ(*r.spec->joints[3].body2, "rocker");
}

TEST(MjcfImport, FourBarChecksLikeTheNativeTwin) {
  const auto native = CheckReport(NativeWithSphericalC());
  const auto imported = CheckReport(FourBarXml());
  ASSERT_TRUE(imported.value("valid", false)) << imported.dump();
  EXPECT_EQ(imported["mobility"]["mobility"], 1);
  EXPECT_EQ(imported["mobility"]["redundant"], 1);  // the connect's out-of-plane equation
  EXPECT_EQ(native["mobility"]["redundant"], 1);
  ASSERT_EQ(imported["mobility"]["redundant_equations"].size(), 1u);
  EXPECT_EQ(imported["mobility"]["redundant_equations"][0]["equation"],
            native["mobility"]["redundant_equations"][0]["equation"]);
}

TEST(MjcfImport, FourBarRunsLikeTheNativeFile) { ExpectNativeMotion(FourBarXml() + " --drive A=2*pi*t"); }

TEST(MjcfImport, WrittenFileRunsTheSame) {
  const std::string out = TempFile("four-bar-from-mjcf.json", "");
  ASSERT_EQ(Stdout("import " + FourBarXml() + " --drive A=2*pi*t --span 0:1:360 -o " + out).code, 0);
  EXPECT_EQ(CheckReport(out)["mobility"]["mobility"], 1);
  ExpectNativeMotion(out);
}

// The same four-bar in radians, with quat, axisangle and an extrinsic euler sequence.
TEST(MjcfImport, AngleUnitsAndOrientationFormsGiveTheSamePoses) {
  std::string text = ReadText(FourBarXml());
  const auto degree = importers::ImportText(text, ForeignFormat::Mjcf, "deg.xml");
  ASSERT_TRUE(degree.ok()) << Errors(degree);
  const double phi = 0.3207220116342564 - M_PI / 3, dc = std::atan2(0.07247123666099901, 0.03388096599604965);
  auto replace = [&](const std::string& a, const std::string& b) {
    const auto k = text.find(a);
    ASSERT_NE(k, std::string::npos) << a;
    text.replace(k, a.size(), b);
  };
  replace("angle=\"degree\"", "angle=\"radian\" eulerseq=\"ZYX\"");
  char buf[200];
  std::snprintf(buf, sizeof buf, "quat=\"%.17g 0 0 %.17g\"", 2 * std::cos(M_PI / 6), 2 * std::sin(M_PI / 6));
  replace("euler=\"0 0 60\"", buf);  // not normalised
  std::snprintf(buf, sizeof buf, "axisangle=\"0 0 2 %.17g\"", phi);
  const auto e1 = text.find("euler=\"0 0 -41");
  ASSERT_NE(e1, std::string::npos);
  text.replace(e1, text.find('"', e1 + 7) + 1 - e1, buf);
  std::snprintf(buf, sizeof buf, "euler=\"%.17g 0 0\"", dc);  // ZYX: the first angle about z
  const auto e2 = text.find("euler=\"0 0 ");
  ASSERT_NE(e2, std::string::npos);
  text.replace(e2, text.find('"', e2 + 7) + 1 - e2, buf);
  const auto radian = importers::ImportText(text, ForeignFormat::Mjcf, "rad.xml");
  ASSERT_TRUE(radian.ok()) << Errors(radian) << text;
  for (size_t b = 0; b < 3; ++b)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(radian.spec->bodies[b].orientation->matrix[i][k].number,
                    degree.spec->bodies[b].orientation->matrix[i][k].number, 1e-14)
            << "body " << b;
}

const char* kFeatures = R"(<mujoco model="features">
  <default>
    <joint axis="0 0 1"/>
    <default class="slider">
      <joint type="slide" axis="1 0 0"/>
      <default class="yslider"><joint axis="0 1 0"/></default>
    </default>
  </default>
  <worldbody>
    <site name="s0" pos="0 0 1"/>
    <body name="a" childclass="slider">
      <joint name="ja" range="-0.1 0.2"/>
      <body name="b" pos="0 0 0">
        <joint name="jb" class="yslider"/>
      </body>
    </body>
    <body name="h" pos="1 0 0">
      <joint name="jh" ref="30" range="-10 50"/>
      <joint name="jh2" axis="1 0 0"/>
      <inertial pos="0 0 0" mass="3" diaginertia="1 2 3"/>
      <site name="s1" pos="0 0 1"/>
    </body>
    <body name="f" pos="2 0 0"><joint name="jf" type="ball"/></body>
    <body name="w" pos="3 0 0"><joint name="jw" type="ball"/></body>
  </worldbody>
  <equality>
    <joint joint1="jb" joint2="ja" polycoef="0.1 2 0 0 0"/>
    <weld body1="w" body2="f"/>
    <connect site1="s0" site2="s1"/>
  </equality>
</mujoco>
)";

TEST(MjcfImport, DefaultsRefCouplingWeldSitesSeveralJoints) {
  const auto r = Import(kFeatures, ForeignFormat::Mjcf, "features.xml");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const MechanismSpec& s = *r.spec;
  std::map<std::string, const JointSpec*> joint;
  for (const JointSpec& j : s.joints) joint[*j.name] = &j;
  ASSERT_EQ(joint.count("ja") + joint.count("jb") + joint.count("jh") + joint.count("jh2"), 4u);
  EXPECT_EQ(*joint["ja"]->type, "prismatic");  // the body's childclass
  EXPECT_EQ(*joint["jb"]->type, "prismatic");  // its own class, inheriting the type
  auto marker_axis = [&](const JointSpec* j) {
    for (const BodySpec& b : s.bodies)
      if (*b.name == *j->body2)
        for (const MarkerSpec& m : b.markers)
          if (m.name == *j->marker2) return std::array<double, 3>{m.axis->c[0].number, m.axis->c[1].number, m.axis->c[2].number};
    return std::array<double, 3>{0, 0, 0};
  };
  EXPECT_NEAR(marker_axis(joint["ja"])[0], 1, 1e-15);
  EXPECT_NEAR(marker_axis(joint["jb"])[1], 1, 1e-15);
  EXPECT_NEAR(marker_axis(joint["jh"])[2], 1, 1e-15);  // the main class
  EXPECT_NEAR((*joint["ja"]->limits)[1].number, 0.2, 1e-15);
  // ref 30°: the written pose is q = 30°, so the limits from it are −40° and +20°.
  EXPECT_NEAR((*joint["jh"]->limits)[0].number, -40 * M_PI / 180, 1e-14);
  EXPECT_NEAR((*joint["jh"]->limits)[1].number, 20 * M_PI / 180, 1e-14);
  // Two joints in h: world → h__jh (massless) → h.
  EXPECT_EQ(*joint["jh"]->body2, "h__jh");
  EXPECT_EQ(*joint["jh2"]->body1, "h__jh");
  EXPECT_EQ(*joint["jh2"]->body2, "h");
  // The weld makes w part of f: one body on two ball joints.
  for (const BodySpec& body : s.bodies) EXPECT_NE(*body.name, "w");
  EXPECT_EQ(*joint["jw"]->body2, "f");
  EXPECT_EQ(*joint["jw"]->type, "spherical");
  ASSERT_EQ(s.couplers.size(), 1u);
  EXPECT_EQ(s.couplers[0].joints, (std::vector<std::string>{"jb", "ja"}));
  EXPECT_EQ(s.couplers[0].coefficients[1].number, -2);
  EXPECT_EQ(s.couplers[0].constant->number, 0.1);
}

struct BadCase {
  const char* what;
  std::string body;  // inside <mujoco>
  int line;
  const char* element;
  const char* reason;
};

TEST(MjcfImport, MalformedAndUnsupportedNameFileLineElementReason) {
  const std::string b = "  <worldbody>\n    <body name=\"a\">\n";  // lines 2-3
  const std::string e = "    </body>\n  </worldbody>\n";
  const std::string two = b + "      <joint name=\"j\"/>\n" + e + "  <worldbody><body name=\"c\"><joint name=\"k\"/></body></worldbody>\n";
  const std::vector<BadCase> cases = {
      {"not XML", b + "      <joint name=\"j\">\n" + e, 4, "", "not well-formed XML: XML_ERROR_MISMATCHED_ELEMENT"},
      {"free joint", b + "      <freejoint/>\n" + e, 4, "<freejoint>", "a free joint (6 freedoms) is not supported"},
      {"free type", b + "      <joint name=\"j\" type=\"free\"/>\n" + e, 4, "<joint name=\"j\">", "free joint"},
      {"unknown type", b + "      <joint name=\"j\" type=\"helix\"/>\n" + e, 4, "<joint name=\"j\">", "unknown joint type 'helix'"},
      {"unknown class", b + "      <joint name=\"j\" class=\"nope\"/>\n" + e, 4, "<joint name=\"j\">", "unknown default class 'nope'"},
      {"include", "  <include file=\"x.xml\"/>\n", 2, "<include>", "<include> is not supported"},
      {"frame", b + "      <frame/>\n" + e, 4, "<frame>", "<frame> is not supported"},
      {"tendon equality", two + "  <equality><tendon tendon1=\"t\"/></equality>\n", 8, "<tendon>", "equality <tendon> is not supported"},
      {"nonlinear", two + "  <equality><joint joint1=\"j\" joint2=\"k\" polycoef=\"0 1 1 0 0\"/></equality>\n", 8, "<joint joint1=\"j\">", "nonlinear polycoef"},
      {"lock", two + "  <equality><joint joint1=\"j\"/></equality>\n", 8, "<joint joint1=\"j\">", "without joint2 locks joint 'j'"},
      {"connect body", two + "  <equality><connect body1=\"zz\" anchor=\"0 0 0\"/></equality>\n", 8, "<connect body1=\"zz\">", "body 'zz' is not defined"},
      {"connect anchor", two + "  <equality><connect body1=\"a\" body2=\"c\"/></equality>\n", 8, "<connect body1=\"a\">", "attribute 'anchor' is missing"},
      {"euler count", "  <worldbody>\n    <body name=\"a\" euler=\"1 2\"/>\n  </worldbody>\n", 3, "<body name=\"a\">", "must be 3 numbers"},
      {"two orientations", "  <worldbody>\n    <body name=\"a\" euler=\"1 2 3\" quat=\"1 0 0 0\"/>\n  </worldbody>\n", 3, "<body name=\"a\">", "more than one orientation"},
      {"relpose", two + "  <equality><weld body1=\"a\" body2=\"c\" relpose=\"1 0 0 1 0 0 0\"/></equality>\n", 8, "<weld body1=\"a\">", "relpose differs"},
      {"global", "  <compiler coordinate=\"global\"/>\n", 2, "<compiler>", "coordinate=\"global\" is not supported"},
      {"eulerseq", "  <compiler eulerseq=\"xyw\"/>\n", 2, "<compiler>", "expected three of x y z"},
      {"world joint", "  <worldbody>\n    <joint name=\"j\"/>\n  </worldbody>\n", 3, "<joint name=\"j\">", "a joint directly in <worldbody>"},
      {"limited", b + "      <joint name=\"j\" limited=\"true\"/>\n" + e, 4, "<joint name=\"j\">", "limited=\"true\" without a range"},
      {"axis", b + "      <joint name=\"j\" axis=\"0 0 0\"/>\n" + e, 4, "<joint name=\"j\">", "the joint axis is the zero vector"},
  };
  for (const BadCase& c : cases) {
    const auto r = Import("<mujoco model=\"m\">\n" + c.body + "</mujoco>\n", ForeignFormat::Mjcf, "bad.xml");
    EXPECT_FALSE(r.ok()) << c.what;
    const std::string all = Errors(r);
    const std::string place = "bad.xml:" + std::to_string(c.line) + ": " + c.element;
    EXPECT_NE(all.find(place), std::string::npos) << c.what << ": " << all;
    EXPECT_NE(all.find(c.reason), std::string::npos) << c.what << ": " << all;
  }
}

TEST(MjcfImport, CommandsExitOneAndWriteNothing) {
  const std::string bad = TempFile("bad.xml", "<mujoco>\n  <worldbody>\n    <body name=\"a\">\n      <freejoint/>\n"
                                              "    </body>\n  </worldbody>\n</mujoco>\n");
  const std::string out = TempFile("never-written-mjcf.json", "") + ".x";
  for (const std::string& cmd : {"import " + bad + " -o " + out, "check " + bad, "run " + bad + " --drive j=t"}) {
    const auto r = mechkin_test::RunCli(cmd);
    EXPECT_EQ(r.code, 1) << cmd << ": " << r.out;
    EXPECT_NE(r.out.find("bad.xml:4: <freejoint>: a free joint (6 freedoms) is not supported"), std::string::npos)
        << r.out;
  }
  EXPECT_FALSE(std::ifstream(out).good());
}

}  // namespace
}  // namespace mechkin::import_test
