// Clearance outputs and first contacts (issue 28, docs/format.md "Clearance"),
// against closed forms: two spheres on two cranks turning at different rates (the
// centre distance minus the radii, its rate, the first contact's root), a box on a
// slider passing a fixed box (the contact time of the faces, also when the contact
// happens strictly between two clear rows), and a four-bar's coupler passing a post
// (`check --clearance` and `expect min_clearance` against the segment–point distance).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/check_report.hpp"
#include "analysis/clearance_sweep.hpp"
#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace clearance_test {

using nlohmann::json;
using testing_files::FromJson;

// ---- Two spheres on two cranks ---------------------------------------------

constexpr double kA = 0.03, kB = 0.02, kD = 0.06, kR = 0.008;  // m
constexpr double kW1 = -2.0, kW2 = 1.5;                         // rad/s

// Crank 1 on (0, 0), crank 2 on (d, 0), both pointing +y at the design pose.
void Centres(double t, Vec3* p1, Vec3* p2) {
  *p1 = Vec3(-kA * std::sin(kW1 * t), kA * std::cos(kW1 * t), 0);
  *p2 = Vec3(kD - kB * std::sin(kW2 * t), kB * std::cos(kW2 * t), 0);
}
double SphereGap(double t) {
  Vec3 p1, p2;
  Centres(t, &p1, &p2);
  return (p2 - p1).norm() - 2 * kR;
}
double SphereGapRate(double t) {
  Vec3 p1, p2;
  Centres(t, &p1, &p2);
  const Vec3 v1(-kA * kW1 * std::cos(kW1 * t), -kA * kW1 * std::sin(kW1 * t), 0);
  const Vec3 v2(-kB * kW2 * std::cos(kW2 * t), -kB * kW2 * std::sin(kW2 * t), 0);
  return (p2 - p1).normalized().dot(v2 - v1);
}

// The root of f in [a, b] (f(a) > 0 ≥ f(b)) by bisection to 1e-14 s.
template <typename F>
double Root(F f, double a, double b) {
  while (b - a > 1e-14) {
    const double m = 0.5 * (a + b);
    (f(m) > 0 ? a : b) = m;
  }
  return 0.5 * (a + b);
}

json TwoCranks() {
  const json z = {0, 0, 1};
  return {{"mechkin", 1},
          {"units", {{"length", "m"}, {"angle", "rad"}}},
          {"bodies",
           {{{"name", "crank1"}, {"position", {0, 0, 0}},
             {"shape", {{"type", "sphere"}, {"radius", kR}, {"center", {0, kA, 0}}}}},
            {{"name", "crank2"}, {"position", {kD, 0, 0}},
             {"shapes", {{{"type", "sphere"}, {"radius", kR}, {"center", {0, kB, 0}}}}}}}},
          {"joints",
           {{{"name", "A"}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "crank1"}, {"origin", {0, 0, 0}}, {"axis", z}},
            {{"name", "B"}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "crank2"}, {"origin", {kD, 0, 0}}, {"axis", z}}}},
          {"drivers",
           {{{"name", "m1"}, {"type", "rotation"}, {"joint", "A"}, {"function", "-2*t"}},
            {{"name", "m2"}, {"type", "rotation"}, {"joint", "B"}, {"function", "1.5*t"}}}},
          {"analysis", {{"start", 0}, {"end", 1}, {"steps", 100}}},
          {"outputs", {{{"name", "gap"}, {"type", "clearance"}, {"body1", "crank1"}, {"body2", "crank2"}}}}};
}

TEST(Clearance, TwoSpheresOnCranksMatchTheClosedFormAndTheFirstContact) {
  const Model model = FromJson(TwoCranks());
  TableOptions table;
  const Motion run = RunMotion(model, AnalysisOptions{}, table);
  ASSERT_TRUE(run.complete) << run.stop.message;
  const int gap = run.layout().Find("gap"), rate = run.layout().Find("gap_t");
  const int p1x = run.layout().Find("gap.point1.x"), p2y = run.layout().Find("gap.point2.y");
  ASSERT_GE(gap, 0);
  ASSERT_EQ(rate, gap + 1);
  ASSERT_EQ(p1x, gap + 2);
  ASSERT_EQ(p2y, gap + 6);
  double worst = 0, worst_rate = 0, worst_point = 0;
  int before_contact = 0;
  for (int r = 0; r < run.rows(); ++r) {
    const double t = run.at(r, 0);
    if (SphereGap(t) <= 0) continue;  // penetration depth: EPA's, not a closed form
    ++before_contact;
    worst = std::max(worst, std::abs(run.at(r, gap) - SphereGap(t)));
    worst_rate = std::max(worst_rate, std::abs(run.at(r, rate) - SphereGapRate(t)));
    Vec3 c1, c2;
    Centres(t, &c1, &c2);
    const Vec3 closest1 = c1 + kR * (c2 - c1).normalized();
    worst_point = std::max(worst_point, (Vec3(run.at(r, p1x), run.at(r, p1x + 1), run.at(r, p1x + 2)) - closest1).norm());
  }
  std::printf("[measured] %d clear rows: clearance off the closed form by %.2e m, rate by %.2e m/s, point by %.2e m\n",
              before_contact, worst, worst_rate, worst_point);
  EXPECT_GT(before_contact, 50);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_rate, 1e-9);
  EXPECT_LT(worst_point, 1e-9);
  // The first contact: the closed form's root between the rows around it.
  ASSERT_EQ(run.report.contacts.size(), 1u);
  const ContactHit& hit = run.report.contacts[0];
  int first = 0;
  while (SphereGap(run.at(first, 0)) > 0) ++first;
  const double t0 = Root(SphereGap, run.at(first - 1, 0), run.at(first, 0));
  std::printf("[measured] first contact at %.12f s, closed form %.12f s: off by %.2e s\n", hit.t, t0, hit.t - t0);
  EXPECT_NEAR(hit.t, t0, 1e-9);
  EXPECT_EQ(hit.body1, 0);
  EXPECT_EQ(hit.body2, 1);
  EXPECT_NEAR(hit.driver_values[0], kW1 * t0, 1e-8);
  Vec3 c1, c2;
  Centres(t0, &c1, &c2);
  EXPECT_LT((hit.point - 0.5 * (c1 + c2)).norm(), 1e-8);
  // The default reports it and goes on; a note says where.
  ASSERT_FALSE(run.report.notes.empty());
  EXPECT_NE(run.report.notes.back().find("bodies `crank1` and `crank2` come into contact at t = 0.61"),
            std::string::npos)
      << run.report.notes.back();
}

TEST(Clearance, OnContactStopEndsTheRunAtTheContact) {
  const Model model = FromJson(TwoCranks());
  AnalysisOptions options;
  options.on_contact_stop = true;
  const Motion run = RunMotion(model, options, TableOptions{});
  ASSERT_FALSE(run.complete);
  EXPECT_EQ(run.report.stop, StopKind::Contact);
  ASSERT_EQ(run.report.contacts.size(), 1u);
  const double last_t = run.at(run.rows() - 1, 0);
  EXPECT_LT(last_t, run.report.contacts[0].t);
  EXPECT_GT(last_t + 0.01, run.report.contacts[0].t);
  EXPECT_GT(SphereGap(last_t), 0);
  EXPECT_NE(run.report.message.find("the run stops there after"), std::string::npos) << run.report.message;
}

// ---- A box on a slider passing a fixed box -----------------------------------

// Slider box of length sx along x at the slide v·t; ground box of length gx centred
// at X. The faces meet at t = (X − gx/2 − sx/2) / v.
json SliderPastBox(double v, double sx, double gx, double X, double end, int steps) {
  return {{"mechkin", 1},
          {"units", {{"length", "m"}, {"angle", "rad"}}},
          {"ground", {{"shapes", {{{"type", "box"}, {"size", {gx, 0.02, 0.02}}, {"center", {X, 0, 0}}}}}}},
          {"bodies",
           {{{"name", "slider"}, {"position", {0, 0, 0}}, {"shape", {{"type", "box"}, {"size", {sx, 0.02, 0.02}}}}}}},
          {"joints",
           {{{"name", "P"}, {"type", "prismatic"}, {"body1", "ground"}, {"body2", "slider"}, {"origin", {0, 0, 0}},
             {"axis", {1, 0, 0}}}}},
          {"drivers", {{{"name", "push"}, {"type", "translation"}, {"joint", "P"}, {"function", std::to_string(v) + "*t"}}}},
          {"analysis", {{"start", 0}, {"end", end}, {"steps", steps}}},
          {"outputs", {{{"type", "clearance"}, {"body1", "slider"}, {"body2", "ground"}}}}};
}

TEST(Clearance, BoxOnASliderTouchesTheFixedBoxAtTheClosedFormTime) {
  const double v = 0.1, sx = 0.02, gx = 0.02, X = 0.1033;
  const Motion run = RunMotion(FromJson(SliderPastBox(v, sx, gx, X, 1, 100)), AnalysisOptions{}, TableOptions{});
  const int gap = run.layout().Find("clearance_slider_ground");
  ASSERT_GE(gap, 0);
  double worst = 0;
  for (int r = 0; r < run.rows(); ++r) {
    const double t = run.at(r, 0), closed = X - gx / 2 - (v * t + sx / 2);
    if (closed > 0) worst = std::max(worst, std::abs(run.at(r, gap) - closed));
    if (closed > 0) {
      EXPECT_NEAR(run.at(r, gap + 1), -v, 1e-9) << t;
    }
  }
  std::printf("[measured] box-box clearance off the closed form by %.2e m\n", worst);
  EXPECT_LT(worst, 1e-9);
  ASSERT_EQ(run.report.contacts.size(), 1u);
  const double t0 = (X - gx / 2 - sx / 2) / v;
  std::printf("[measured] box contact at %.12f s, closed form %.12f s: off by %.2e s\n", run.report.contacts[0].t, t0,
              run.report.contacts[0].t - t0);
  EXPECT_NEAR(run.report.contacts[0].t, t0, 1e-9);
  EXPECT_NEAR(run.report.contacts[0].point.x(), X - gx / 2, 1e-8);
}

TEST(Clearance, ThinFastBoxTouchesStrictlyBetweenTwoClearRows) {
  const double v = 10, sx = 0.001, gx = 0.002, X = 0.5055;
  const Motion run = RunMotion(FromJson(SliderPastBox(v, sx, gx, X, 0.1, 10)), AnalysisOptions{}, TableOptions{});
  ASSERT_TRUE(run.complete) << run.stop.message;
  const int gap = run.layout().Find("clearance_slider_ground");
  for (int r = 0; r < run.rows(); ++r) EXPECT_GT(run.at(r, gap), 0.003) << "row " << r << " is clear";
  ASSERT_EQ(run.report.contacts.size(), 1u);
  const double t0 = (X - gx / 2 - sx / 2) / v;
  std::printf("[measured] thin box contact between rows at %.12f s, closed form %.12f s: off by %.2e s\n",
              run.report.contacts[0].t, t0, run.report.contacts[0].t - t0);
  EXPECT_NEAR(run.report.contacts[0].t, t0, 1e-9);
  EXPECT_GT(run.report.contacts[0].t, 0.05);
  EXPECT_LT(run.report.contacts[0].t, 0.06);
}

// The slider's box given as a convex hull of its 8 corners (and a point inside):
// the same clearances and contact as the box.
TEST(Clearance, ConvexHullOfABoxsCornersMeasuresLikeTheBox) {
  const double v = 0.1, sx = 0.02, gx = 0.02, X = 0.1033;
  json j = SliderPastBox(v, sx, gx, X, 1, 100);
  json corners = json::array({{0, 0, 0}});
  for (int k = 0; k < 8; ++k) corners.push_back({k & 1 ? sx / 2 : -sx / 2, k & 2 ? 0.01 : -0.01, k & 4 ? 0.01 : -0.01});
  j["bodies"][0]["shape"] = {{"type", "convex"}, {"points", corners}};
  const Motion run = RunMotion(FromJson(j), AnalysisOptions{}, TableOptions{});
  const int gap = run.layout().Find("clearance_slider_ground");
  double worst = 0;
  for (int r = 0; r < run.rows(); ++r) {
    const double t = run.at(r, 0), closed = X - gx / 2 - (v * t + sx / 2);
    if (closed > 0) worst = std::max(worst, std::abs(run.at(r, gap) - closed));
  }
  std::printf("[measured] convex hull of the box: clearance off the closed form by %.2e m\n", worst);
  EXPECT_LT(worst, 1e-9);
  ASSERT_EQ(run.report.contacts.size(), 1u);
  EXPECT_NEAR(run.report.contacts[0].t, (X - gx / 2 - sx / 2) / v, 1e-9);
}

// ---- A four-bar's coupler passing a post --------------------------------------

constexpr double kPostX = 50, kPostY = -20, kPostR = 5, kCapsuleR = 3;  // mm

json CouplerPastPost(std::optional<double> min_clearance) {
  json j = testing_files::PlanarFourBar(40, 120, 80, 100, 60, 72);
  const auto& B = j["joints"][1]["origin"];
  const auto& C = j["joints"][2]["origin"];
  const double ux = C[0].get<double>() - B[0].get<double>(), uy = C[1].get<double>() - B[1].get<double>();
  j["bodies"][1]["shape"] = {{"type", "capsule"}, {"radius", kCapsuleR}, {"length", 120}, {"axis", {ux, uy, 0}}};
  j["ground"] = {{"shapes", {{{"type", "sphere"}, {"radius", kPostR}, {"center", {kPostX, kPostY, 0}}}}}};
  if (min_clearance) j["expect"] = {{"min_clearance", *min_clearance}};
  return j;
}

// The post's clearance from the coupler's pose: distance from the post's centre to
// the coupler's segment (its direction u fixed in the body) minus both radii.
double PostClearance(const Motion& m, int row, const Vec3& u_local) {
  const int x = m.layout().Find("coupler.x"), e0 = m.layout().Find("coupler.e0");
  const int stride = m.layout().options().order + 1;
  const Vec3 r(m.at(row, x), m.at(row, x + stride), m.at(row, x + 2 * stride));
  const Vec4 p(m.at(row, e0), m.at(row, e0 + 1), m.at(row, e0 + 2), m.at(row, e0 + 3));
  const Vec3 u = CalcA(p) * u_local;
  const Vec3 a = r - 60 * u, d = 120 * u, q(kPostX, kPostY, 0);
  const double s = std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (q - a - s * d).norm() - kPostR - kCapsuleR;
}

TEST(Clearance, CheckNamesTheTightestPairAndWhereAndExpectFails) {
  const json j = CouplerPastPost(6.0);
  const Model model = FromJson(j);
  const Vec3 u = model.bodies[1].shape->axis;
  const Motion run = RunMotion(model, AnalysisOptions{}, TableOptions{});
  int best = 0;
  for (int r = 0; r < run.rows(); ++r)
    if (PostClearance(run, r, u) < PostClearance(run, best, u)) best = r;
  const LoadResult loaded = LoadMechanismText(j.dump(), "inline");
  const CheckReport report = CheckLoaded("inline", loaded);
  ASSERT_TRUE(report.clearance);
  const ClearanceSection& c = *report.clearance;
  ASSERT_EQ(c.pairs.size(), 1u);
  ASSERT_EQ(c.tightest, 0);
  EXPECT_EQ(c.pairs[0].body1, "ground");
  EXPECT_EQ(c.pairs[0].body2, "coupler");
  std::printf("[measured] tightest %.12f mm at t = %.6f s; closed form %.12f mm at t = %.6f s\n", c.pairs[0].clearance,
              c.pairs[0].t, PostClearance(run, best, u), run.at(best, 0));
  EXPECT_NEAR(c.pairs[0].clearance, PostClearance(run, best, u), 1e-7);
  EXPECT_DOUBLE_EQ(c.pairs[0].t, run.at(best, 0));
  ASSERT_EQ(report.expectations.size(), 1u);
  EXPECT_EQ(report.expectations[0].key, "min_clearance");
  EXPECT_FALSE(report.expectations[0].held);
  EXPECT_FALSE(report.ok());
  EXPECT_NE(report.expectations[0].where.find("`ground` and `coupler`"), std::string::npos);
  const CheckReport loose = CheckLoaded("inline", LoadMechanismText(CouplerPastPost(4.0).dump(), "inline"));
  ASSERT_EQ(loose.expectations.size(), 1u);
  EXPECT_TRUE(loose.expectations[0].held);
  EXPECT_TRUE(loose.ok());
}

}  // namespace
}  // namespace mechkin
