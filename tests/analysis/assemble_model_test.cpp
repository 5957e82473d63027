// Assembly from dimensions (issue 22) and branch hints (issue 23 item 7):
// mechanisms written with markers only (no body positions) are placed by compile's
// spanning tree and closed by the assembly; their driven motion is checked against
// closed forms (Freudenstein, the slider-crank's x(θ), the Stephenson six-bar loop
// by loop, the spatial RSSR).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "analysis/check_report.hpp"
#include "analysis/load.hpp"
#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace assemble_model_test {

using nlohmann::json;

json Marker(double x, double y, double z, json axis = {0, 0, 1}, json x_axis = nullptr) {
  json m = {{"point", {x, y, z}}, {"axis", axis}};
  if (!x_axis.is_null()) m["x_axis"] = x_axis;
  return m;
}

json Rev(const std::string& name, const std::string& b1, const std::string& m1, const std::string& b2,
         const std::string& m2, const std::string& type = "revolute") {
  return {{"name", name}, {"type", type}, {"body1", b1}, {"marker1", m1}, {"body2", b2}, {"marker2", m2}};
}

json Header(int steps) {
  return {{"mechkin", 1}, {"units", {{"length", "m"}, {"angle", "rad"}}},
          {"analysis", {{"start", 0}, {"end", 1}, {"steps", steps}}}};
}

// Planar four-bar by link lengths only: crank a on ground pivot O, coupler b, rocker c
// on ground pivot D = (d, 0); the crank drawn at th0 (ground marker's x axis), turning
// once per second; output: the rocker tip.
json FourBarByLengths(double a, double b, double c, double d, double th0) {
  json doc = Header(36);
  doc["ground"] = {{"markers", {{"O", Marker(0, 0, 0, {0, 0, 1}, {std::cos(th0), std::sin(th0), 0})},
                                {"D", Marker(d, 0, 0)}}}};
  doc["bodies"] = {{{"name", "crank"}, {"markers", {{"bearing", Marker(0, 0, 0)}, {"pin", Marker(a, 0, 0)}}}},
                   {{"name", "coupler"}, {"markers", {{"p", Marker(0, 0, 0)}, {"q", Marker(b, 0, 0)}}}},
                   {{"name", "rocker"}, {"markers", {{"pivot", Marker(0, 0, 0)}, {"tip", Marker(c, 0, 0)}}}}};
  doc["joints"] = {Rev("crank_bearing", "ground", "O", "crank", "bearing"), Rev("crank_pin", "crank", "pin", "coupler", "p"),
                   Rev("rocker_pin", "coupler", "q", "rocker", "tip"), Rev("rocker_bearing", "ground", "D", "rocker", "pivot")};
  doc["drivers"] = {{{"name", "motor"}, {"type", "rotation"}, {"joint", "crank_bearing"}, {"function", "2*pi*t"}}};
  doc["outputs"] = {{{"name", "tip"}, {"type", "point"}, {"body", "rocker"}, {"marker", "tip"}}};
  return doc;
}

// Freudenstein: K1 cos φ − K2 cos θ + K3 = cos(θ − φ), K1 = d/a, K2 = d/c,
// K3 = (a² − b² + c² + d²)/(2ac); φ = atan2(Q, P) ± acos(R/√(P² + Q²)).
double Freudenstein(double a, double b, double c, double d, double th, int branch) {
  const double K1 = d / a, K2 = d / c, K3 = (a * a - b * b + c * c + d * d) / (2 * a * c);
  const double P = K1 - std::cos(th), Q = -std::sin(th), R = K2 * std::cos(th) - K3;
  return std::atan2(Q, P) + branch * std::acos(R / std::hypot(P, Q));
}

Motion RunDoc(const json& doc) {
  const Model m = testing_files::FromJson(doc);
  return RunMotion(m, AnalysisOptions{}, TableOptions{});
}

double AngleGap(double x, double y) { return std::abs(std::remainder(x - y, 2 * M_PI)); }

// The branch (±1) whose closed form the first row matches; every row must match it.
template <class F>
void ExpectOneBranch(const Motion& m, F error_of_branch, double tol) {
  ASSERT_TRUE(m.complete) << m.stop.message;
  const int branch = error_of_branch(0, 1) < error_of_branch(0, -1) ? 1 : -1;
  for (int r = 0; r < m.rows(); ++r) EXPECT_LT(error_of_branch(r, branch), tol) << "row " << r << " branch " << branch;
}

TEST(AssembleModel, FourBarByLengthsFollowsFreudenstein) {
  const double a = 0.1, b = 0.35, c = 0.3, d = 0.4, th0 = 1.0;
  const Motion m = RunDoc(FourBarByLengths(a, b, c, d, th0));
  const int x = m.layout().Find("tip.x"), y = m.layout().Find("tip.y");
  ASSERT_GE(x, 0);
  ExpectOneBranch(m, [&](int r, int branch) {
    const double phi = Freudenstein(a, b, c, d, th0 + 2 * M_PI * m.at(r, 0), branch);
    return std::hypot(m.at(r, x) - (d + c * std::cos(phi)), m.at(r, y) - c * std::sin(phi));
  }, 1e-9);
}

TEST(AssembleModel, SliderCrankByLengthsFollowsItsClosedForm) {
  const double a = 0.05, l = 0.2, e = 0.02, th0 = 0.5;
  json doc = Header(36);
  const json x_dir = {1, 0, 0}, y_dir = {0, 1, 0};
  doc["ground"] = {{"markers", {{"O", Marker(0, 0, 0, {0, 0, 1}, {std::cos(th0), std::sin(th0), 0})},
                                {"guide", Marker(0, e, 0, x_dir, y_dir)}}}};
  doc["bodies"] = {{{"name", "crank"}, {"markers", {{"bearing", Marker(0, 0, 0)}, {"pin", Marker(a, 0, 0)}}}},
                   {{"name", "rod"}, {"markers", {{"big", Marker(0, 0, 0)}, {"small", Marker(l, 0, 0)}}}},
                   {{"name", "slider"}, {"markers", {{"guide", Marker(0, 0, 0, x_dir, y_dir)}, {"pin", Marker(0, 0, 0)}}}}};
  doc["joints"] = {Rev("O", "ground", "O", "crank", "bearing"), Rev("P", "crank", "pin", "rod", "big"),
                   Rev("Q", "rod", "small", "slider", "pin"), Rev("S", "ground", "guide", "slider", "guide", "prismatic")};
  doc["drivers"] = {{{"name", "motor"}, {"type", "rotation"}, {"joint", "O"}, {"function", "2*pi*t"}}};
  doc["outputs"] = {{{"name", "piston"}, {"type", "point"}, {"body", "slider"}, {"marker", "pin"}}};
  const Motion m = RunDoc(doc);
  const int x = m.layout().Find("piston.x"), y = m.layout().Find("piston.y");
  ExpectOneBranch(m, [&](int r, int branch) {
    const double th = th0 + 2 * M_PI * m.at(r, 0), s = a * std::sin(th) - e;
    const double expect = a * std::cos(th) + branch * std::sqrt(l * l - s * s);
    return std::max(std::abs(m.at(r, x) - expect), std::abs(m.at(r, y) - e));
  }, 1e-9);
}

// Stephenson six-bar (two ternary links not jointed to each other): ground pivots O
// and D carry the ternary T1 (crank: B, P) and the ternary T2 (rocker: C, Q); the
// binary b4 joins B–C (a four-bar), the dyad b2–b3 joins P and Q through the joint E.
// Closed form loop by loop: Freudenstein for T2, then E on two circles.
TEST(AssembleModel, StephensonSixBarFollowsItsLoops) {
  const double a = 0.1, b = 0.35, c = 0.3, d = 0.4, th0 = 0.7, l2 = 0.4, l3 = 0.4;
  const Vec3 P(0.05, 0.08, 0), Q(0.15, 0.2, 0);
  json doc = FourBarByLengths(a, b, c, d, th0);
  doc["bodies"][0]["markers"]["P"] = Marker(P.x(), P.y(), 0);
  doc["bodies"][2]["markers"]["Q"] = Marker(Q.x(), Q.y(), 0);
  doc["bodies"].push_back({{"name", "b2"}, {"markers", {{"p", Marker(0, 0, 0)}, {"e", Marker(l2, 0, 0)}}}});
  doc["bodies"].push_back({{"name", "b3"}, {"markers", {{"q", Marker(0, 0, 0)}, {"e", Marker(l3, 0, 0)}}}});
  doc["joints"].push_back(Rev("P", "crank", "P", "b2", "p"));
  doc["joints"].push_back(Rev("Q", "rocker", "Q", "b3", "q"));
  doc["joints"].push_back(Rev("E", "b2", "e", "b3", "e"));
  doc["outputs"].push_back({{"name", "E"}, {"type", "point"}, {"body", "b2"}, {"marker", "e"}});
  const Model model = testing_files::FromJson(doc);
  ASSERT_TRUE(model.assembly && model.assembly->assembled);
  EXPECT_EQ(model.assembly->loops.size(), 2u);
  const Motion m = RunMotion(model, AnalysisOptions{}, TableOptions{});
  const int tx = m.layout().Find("tip.x"), ty = m.layout().Find("tip.y");
  const int ex = m.layout().Find("E.x"), ey = m.layout().Find("E.y");
  auto rot = [](double t, const Vec3& v) { return Vec3(std::cos(t) * v.x() - std::sin(t) * v.y(), std::sin(t) * v.x() + std::cos(t) * v.y(), 0); };
  int four_bar = 0;
  ExpectOneBranch(m, [&](int r, int branch) {
    const double th = th0 + 2 * M_PI * m.at(r, 0);
    const double phi = Freudenstein(a, b, c, d, th, branch);
    return std::hypot(m.at(r, tx) - (d + c * std::cos(phi)), m.at(r, ty) - c * std::sin(phi));
  }, 1e-9);
  four_bar = std::hypot(m.at(0, tx) - (d + c * std::cos(Freudenstein(a, b, c, d, th0, 1))),
                        m.at(0, ty) - c * std::sin(Freudenstein(a, b, c, d, th0, 1))) < 1e-6 ? 1 : -1;
  ExpectOneBranch(m, [&](int r, int branch) {
    const double th = th0 + 2 * M_PI * m.at(r, 0);
    const double phi = Freudenstein(a, b, c, d, th, four_bar);
    const Vec3 p = rot(th, P), q = Vec3(d, 0, 0) + rot(phi, Q);
    const double dist = (q - p).norm(), al = (l2 * l2 - l3 * l3 + dist * dist) / (2 * dist);
    const double h = branch * std::sqrt(l2 * l2 - al * al);
    const Vec3 u = (q - p) / dist, n(-u.y(), u.x(), 0);
    const Vec3 e = p + al * u + h * n;
    return std::hypot(m.at(r, ex) - e.x(), m.at(r, ey) - e.y());
  }, 1e-9);
}

// Spatial RSSR: crank a about z at the origin, rocker c about x through (e, 0, h),
// a distance link b between their pins: (a cos θ − e)² + (a sin θ − c cos φ)² +
// (h + c sin φ)² = b², i.e. A cos φ + B sin φ = C.
TEST(AssembleModel, SpatialRssrFollowsItsClosedForm) {
  const double a = 0.1, c = 0.25, e = 0.3, h = 0.2, b = 0.45, th0 = 0.4;
  json doc = Header(36);
  const json x_dir = {1, 0, 0}, y_dir = {0, 1, 0};
  doc["ground"] = {{"markers", {{"O", Marker(0, 0, 0, {0, 0, 1}, {std::cos(th0), std::sin(th0), 0})},
                                {"R", Marker(e, 0, h, x_dir, y_dir)}}}};
  doc["bodies"] = {{{"name", "crank"}, {"markers", {{"bearing", Marker(0, 0, 0)}, {"pin", Marker(a, 0, 0)}}}},
                   {{"name", "rocker"}, {"markers", {{"pivot", Marker(0, 0, 0, x_dir, y_dir)}, {"pin", Marker(0, c, 0)}}}}};
  doc["joints"] = {Rev("crank_bearing", "ground", "O", "crank", "bearing"),
                   Rev("rocker_bearing", "ground", "R", "rocker", "pivot"),
                   {{"name", "link"}, {"type", "distance"}, {"body1", "crank"}, {"marker1", "pin"}, {"body2", "rocker"},
                    {"marker2", "pin"}, {"length", b}}};
  doc["drivers"] = {{{"name", "motor"}, {"type", "rotation"}, {"joint", "crank_bearing"}, {"function", "2*pi*t"}}};
  doc["outputs"] = {{{"name", "pin"}, {"type", "point"}, {"body", "rocker"}, {"marker", "pin"}}};
  const Motion m = RunDoc(doc);
  const int y = m.layout().Find("pin.y"), z = m.layout().Find("pin.z"), x = m.layout().Find("pin.x");
  ExpectOneBranch(m, [&](int r, int branch) {
    const double th = th0 + 2 * M_PI * m.at(r, 0);
    const double A = -2 * a * c * std::sin(th), B = 2 * h * c;
    const double C = b * b - c * c - h * h - (a * std::cos(th) - e) * (a * std::cos(th) - e) - a * a * std::sin(th) * std::sin(th);
    const double phi = std::atan2(B, A) + branch * std::acos(C / std::hypot(A, B));
    return std::max({std::abs(m.at(r, x) - e), std::abs(m.at(r, y) - c * std::cos(phi)),
                     std::abs(m.at(r, z) - (h + c * std::sin(phi)))});
  }, 1e-9);
}

// The issue's crossed four-bar (crank 0.1, coupler 0.35, rocker 0.3, frame 0.4 m,
// drawn open at 0.6 rad), in the global form and by markers.
constexpr double kA = 0.1, kB = 0.35, kC = 0.3, kD = 0.4, kTh0 = 0.6;

json IssueFourBar() {
  json doc = testing_files::PlanarFourBar(kA * 1000, kB * 1000, kC * 1000, kD * 1000, kTh0 * 180 / M_PI, 36);
  doc["joints"][3]["name"] = "rocker_bearing";
  doc["outputs"] = {{{"name", "tip"}, {"type", "point"}, {"body", "rocker"}, {"point", {kD * 1000, 0, 0}}}};
  return doc;
}

// Rocker angle (global) on branch ±1 with the crank at θ.
double RockerAngle(double th, int branch) { return Freudenstein(kA, kB, kC, kD, th, branch); }

// The branch the global form is drawn on: its joint C's point.
int DrawnBranch() {
  const json c = IssueFourBar()["joints"][2]["origin"];
  const double drawn = std::atan2(c[1].get<double>(), c[0].get<double>() - kD * 1000);
  return AngleGap(drawn, RockerAngle(kTh0, 1)) < AngleGap(drawn, RockerAngle(kTh0, -1)) ? 1 : -1;
}

// The coupler–rocker pin on the branch not drawn, every row to 1e-9 of the closed form.
void ExpectCrossed(const Motion& m, double scale, const std::string& pin_x, const std::string& pin_y) {
  ASSERT_TRUE(m.complete) << m.stop.message;
  const int x = m.layout().Find(pin_x), y = m.layout().Find(pin_y);
  ASSERT_GE(x, 0);
  const int drawn = DrawnBranch();
  for (int r = 0; r < m.rows(); ++r) {
    const double th = kTh0 + 2 * M_PI * m.at(r, 0), phi = RockerAngle(th, -drawn);
    EXPECT_LT(std::hypot(m.at(r, x) / scale - (kD + kC * std::cos(phi)), m.at(r, y) / scale - kC * std::sin(phi)), 1e-9)
        << "row " << r;
  }
}

json WithRockerPinOutput(json doc) {
  // Rocker tip: in the global form the rocker joint C's point on the rocker.
  doc["outputs"] = {{{"name", "pin"}, {"type", "point"}, {"body", "rocker"}, {"point", doc["joints"][2]["origin"]}}};
  return doc;
}

double CrossedHintDegrees() {
  const int drawn = DrawnBranch();
  return (RockerAngle(kTh0, -drawn) - RockerAngle(kTh0, drawn)) * 180 / M_PI;
}

TEST(BranchHints, CrossedFourBarFromAHintOffBy0_9Degrees) {
  json doc = WithRockerPinOutput(IssueFourBar());
  doc["analysis"]["branch"] = {{"joints", {{"rocker_bearing", CrossedHintDegrees() + 0.9}}}};
  ExpectCrossed(RunDoc(doc), 1000, "pin.x", "pin.y");
}

TEST(BranchHints, CrossedFourBarFromFlip) {
  json doc = WithRockerPinOutput(IssueFourBar());
  doc["analysis"]["branch"] = {{"flip", {"rocker_bearing"}}};
  ExpectCrossed(RunDoc(doc), 1000, "pin.x", "pin.y");
}

TEST(BranchHints, FlipOfAnUnknownJointIsAnError) {
  json doc = IssueFourBar();
  doc["analysis"]["branch"] = {{"flip", {"rocker_bearings"}}};
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors[0].pointer, "/analysis/branch/flip/0");
  EXPECT_NE(r.errors[0].fix.find("rocker_bearing"), std::string::npos);
}

// By markers: the rocker's joint coordinate is its absolute angle (its markers' x
// axes are the ground's x and the rocker's pivot→tip), so the crossed hint is the
// crossed closed form's rocker angle itself (0.9° off).
TEST(BranchHints, CrossedFourBarByMarkersFromAHintAndFromFlip) {
  for (int form = 0; form < 2; ++form) {
    json doc = FourBarByLengths(kA, kB, kC, kD, kTh0);
    const Model probe = testing_files::FromJson(doc);
    // Which branch the plain assembly took: the hint/flip asks for the other.
    const Vec3 tip = probe.bodies[2].position + CalcA(probe.bodies[2].euler) * Vec3(kC, 0, 0);
    const double tip_angle = std::atan2(tip.y(), tip.x() - kD);
    const int plain = AngleGap(tip_angle, RockerAngle(kTh0, 1)) < AngleGap(tip_angle, RockerAngle(kTh0, -1)) ? 1 : -1;
    if (form == 0) doc["analysis"]["branch"] = {{"joints", {{"rocker_bearing", RockerAngle(kTh0, -plain) + 0.9 * M_PI / 180}}}};
    else doc["analysis"]["branch"] = {{"flip", {"rocker_bearing"}}};
    const Motion m = RunDoc(doc);
    ASSERT_TRUE(m.complete) << m.stop.message;
    const int x = m.layout().Find("tip.x"), y = m.layout().Find("tip.y");
    for (int r = 0; r < m.rows(); ++r) {
      const double phi = RockerAngle(kTh0 + 2 * M_PI * m.at(r, 0), -plain);
      EXPECT_LT(std::hypot(m.at(r, x) - (kD + kC * std::cos(phi)), m.at(r, y) - kC * std::sin(phi)), 1e-9)
          << (form ? "flip" : "hint") << " row " << r;
    }
  }
}

// A sketch 20 % off every position (and every angle) lands on the pose of the
// exact positions: every body within 1e-9.
TEST(AssembleModel, SketchTwentyPercentOffAssemblesToTheSamePose) {
  const double a = 0.1, b = 0.35, c = 0.3, d = 0.4, th0 = 1.0;
  const double phi = Freudenstein(a, b, c, d, th0, 1);
  const Vec3 B(a * std::cos(th0), a * std::sin(th0), 0), C(d + c * std::cos(phi), c * std::sin(phi), 0);
  const double coupler = std::atan2(C.y() - B.y(), C.x() - B.x());
  const std::vector<std::pair<Vec3, double>> exact = {{Vec3::Zero(), th0}, {B, coupler}, {Vec3(d, 0, 0), phi}};
  auto with_sketch = [&](double f) {
    json doc = FourBarByLengths(a, b, c, d, th0);
    for (int k = 0; k < 3; ++k) {
      doc["bodies"][k]["position"] = {f * exact[k].first.x(), f * exact[k].first.y(), 0};
      doc["bodies"][k]["orientation"] = {{"axis", {0, 0, 1}}, {"angle", f * exact[k].second}};
    }
    return testing_files::FromJson(doc);
  };
  const Model at_exact = with_sketch(1.0), at_sketch = with_sketch(1.2);
  ASSERT_TRUE(at_sketch.assembly && at_sketch.assembly->assembled);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT((at_exact.bodies[k].position - exact[k].first).norm(), 1e-9) << k;
    EXPECT_LT((at_sketch.bodies[k].position - at_exact.bodies[k].position).norm(), 1e-9) << k;
    EXPECT_LT((at_sketch.bodies[k].euler - at_exact.bodies[k].euler).norm(), 1e-9) << k;
  }
  EXPECT_GT(at_sketch.assembly->loops[0].error_before, 0.01);
  EXPECT_LT(at_sketch.assembly->loops[0].error_after, 1e-10);
}

TEST(AssembleModel, ALoopThatCannotCloseIsRefusedWithItsShortfall) {
  json doc = FourBarByLengths(40, 120, 80, 260, 0.5);
  doc["units"]["length"] = "mm";
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.errors.size(), 1u);
  const Diagnostic& e = r.errors[0];
  EXPECT_EQ(e.pointer, "/joints/2");  // rocker_pin closes the loop (the tree: crank, rocker, then coupler)
  EXPECT_NE(e.message.find("crank\u2013coupler\u2013rocker cannot close"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("the links reach 240.0 mm, the pivots are 260.0 mm apart"), std::string::npos) << e.message;
  for (const char* joint : {"crank_bearing", "crank_pin", "rocker_pin", "rocker_bearing"})
    EXPECT_NE(e.message.find(joint), std::string::npos) << joint << ": " << e.message;
  EXPECT_FALSE(e.fix.empty());
}

// The check report's assembly section: present for a file placed by markers only.
TEST(AssembleModel, CheckReportsTheAssembly) {
  const CheckReport with = CheckLoaded("inline", LoadMechanismText(FourBarByLengths(0.1, 0.35, 0.3, 0.4, 1).dump(), "inline"));
  ASSERT_TRUE(with.valid);
  ASSERT_TRUE(with.assembly.has_value());
  ASSERT_EQ(with.assembly->loops.size(), 1u);
  EXPECT_EQ(with.assembly->loops[0].joint, "rocker_pin");
  EXPECT_GT(with.assembly->loops[0].error_before, 1e-3);
  EXPECT_LT(with.assembly->loops[0].error_after, 1e-10);
  EXPECT_EQ(with.assembly->moves.size(), 3u);
  const CheckReport without = CheckLoaded("inline", LoadMechanismText(IssueFourBar().dump(), "inline"));
  EXPECT_FALSE(without.assembly.has_value());
}

// A chain of parallelogram windows (rocker k, length 1, on the ground pivot (k, 0),
// coupler k, length 1, from rocker k−1's tip to rocker k's; rocker 0 driven), 2N + 1
// bodies by markers only, every coupler starting 0.2 rad off level: the sparse path
// closes every loop.
TEST(AssembleModel, MarkerChainOfThousandsOfBodiesAssembles) {
  const int n = std::getenv("CHAIN_N") ? std::atoi(std::getenv("CHAIN_N")) : 1200;
  json doc = Header(10);
  json ground = json::object(), bodies = json::array(), joints = json::array();
  for (int k = 0; k <= n; ++k) {
    const std::string r = "rocker" + std::to_string(k);
    ground["P" + std::to_string(k)] = Marker(k, 0, 0, {0, 0, 1}, {std::cos(1.2), std::sin(1.2), 0});
    // The tip's frame 0.2 rad above ground's x: each coupler starts tilted (its window open).
    bodies.push_back({{"name", r}, {"markers", {{"pivot", Marker(0, 0, 0)},
                                                {"tip", Marker(1, 0, 0, {0, 0, 1}, {std::cos(-1.0), std::sin(-1.0), 0})}}}});
    joints.push_back(Rev("G" + std::to_string(k), "ground", "P" + std::to_string(k), r, "pivot"));
    if (k == 0) continue;
    const std::string c = "coupler" + std::to_string(k);
    bodies.push_back({{"name", c}, {"markers", {{"a", Marker(0, 0, 0)}, {"b", Marker(1, 0, 0)}}}});
    joints.push_back(Rev("A" + std::to_string(k), "rocker" + std::to_string(k - 1), "tip", c, "a"));
    joints.push_back(Rev("B" + std::to_string(k), c, "b", r, "tip"));
  }
  doc["ground"] = {{"markers", ground}};
  doc["bodies"] = bodies;
  doc["joints"] = joints;
  doc["drivers"] = {{{"name", "motor"}, {"type", "rotation"}, {"joint", "G0"}, {"function", "0.1*t"}}};
  const LoadResult r = LoadMechanismText(doc.dump(), "chain");
  ASSERT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  const Model& m = *r.model;
  ASSERT_EQ(m.num_bodies(), 2 * n + 1);
  ASSERT_EQ(m.assembly->loops.size(), static_cast<size_t>(n));
  for (const AssemblyLoop& loop : m.assembly->loops) ASSERT_LT(loop.error_after, 1e-9);
  // Every coupler spans 1 between its rockers' tips at the assembled pose
  // (bodies: rocker0, then rocker k at 2k − 1 and coupler k at 2k).
  auto tip = [&](int k) {
    const Body& b = m.bodies[k == 0 ? 0 : 2 * k - 1];
    return Vec3(b.position + CalcA(b.euler) * Vec3(1, 0, 0));
  };
  for (int k = 1; k <= n; ++k) ASSERT_NEAR((tip(k) - tip(k - 1)).norm(), 1.0, 1e-9) << k;
}

}  // namespace
}  // namespace mechkin

namespace mechkin {
namespace assemble_model_test {

// mechanisms/four-bar-by-lengths.json (the bundled planar four-bar by its link
// lengths and a rocker hint): it assembles onto the bundled file's pose — the
// rocker's pin at the global form's joint C.
TEST(AssembleModel, FourBarByLengthsFileLandsOnTheBundledPose) {
  const Model by_lengths = testing_files::FromJson(testing_files::ReadJson("four-bar-by-lengths.json"));
  const nlohmann::json global = testing_files::ReadJson("planar-four-bar.json");
  const Body& rocker = by_lengths.bodies[2];
  const Vec3 pin = rocker.position + CalcA(rocker.euler) * Vec3(0.080, 0, 0);  // the rocker's "pin" marker (80 mm)
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(pin[k] * 1000, global["joints"][2]["origin"][k].get<double>(), 1e-8) << k;
}

}  // namespace
}  // namespace mechkin

namespace mechkin {
namespace assemble_model_test {

// Every variant compiles and assembles again: with_parameters on the crank length
// gives a newly closed pose whose crank pin lies at the new length and whose rocker
// pin satisfies Freudenstein for that length (the open branch, hint kept).
TEST(AssembleModel, WithParametersAssemblesEachVariant) {
  const Model base = testing_files::FromJson(testing_files::ReadJson("four-bar-by-lengths.json"));
  for (double crank : {30.0, 45.0, 50.0}) {
    const LoadResult r = WithParameters(base, {{"crank", crank}});
    ASSERT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
    const Model& m = *r.model;
    ASSERT_TRUE(m.assembly && m.assembly->assembled);
    EXPECT_LT(m.assembly->loops[0].error_after, 1e-12);
    const Body& rocker = m.bodies[2];
    const Vec3 pin = (rocker.position + CalcA(rocker.euler) * Vec3(0.080, 0, 0)) * 1000;  // mm
    const double phi = std::atan2(pin.y(), pin.x() - 100), th = M_PI / 3;
    const double K1 = 100 / crank, K2 = 100 / 80.0, K3 = (crank * crank - 120 * 120 + 80 * 80 + 100 * 100) / (2 * crank * 80);
    EXPECT_NEAR(K1 * std::cos(phi) - K2 * std::cos(th) + K3, std::cos(th - phi), 1e-9) << crank;
    EXPECT_GT(pin.y(), 0) << crank;  // the hinted (upper, open) branch
  }
}

}  // namespace
}  // namespace mechkin
