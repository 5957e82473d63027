// Inverse dynamics along the prescribed motion against independent references:
// a planar slider-crank's closed-form kinematics with the energy method and a
// hand-written Newton–Euler solution, virtual work for a four-bar held against
// gravity, the statics of a Stewart platform (Jᵀf = W), finite differences of
// the efforts and reactions in time, and the energy balance of every bundled
// mechanism given mass properties.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace forces_test {

using nlohmann::json;
using testing_files::FromJson;
using testing_files::ReadJson;

constexpr double kA = 0.1, kB = 0.3, kTheta0 = M_PI / 6, kOmega = 2 * M_PI, kG = 9.81;
constexpr double kMc = 1.5, kMr = 2.0, kMs = 0.8, kIc = 0.004, kIr = 0.02;

Motion RunForces(const Model& m, int order = 3, bool si = true, double tol = 1e-10) {
  TableOptions t;
  t.order = order;
  t.si = si;
  t.forces = true;
  AnalysisOptions o;
  o.tolerance = tol;
  Motion motion = RunMotion(m, o, t);
  EXPECT_TRUE(motion.complete) << motion.stop.message;
  return motion;
}

std::vector<double> Col(const Motion& m, const std::string& name) {
  const int c = m.layout().Find(name);
  EXPECT_GE(c, 0) << name;
  return c >= 0 ? m.Column(c) : std::vector<double>(m.rows(), 0.0);
}

json Inertia(double mass, const Eigen::Vector3d& center, double I) {
  return {{"mass", mass}, {"center", {center.x(), center.y(), center.z()}}, {"moments", {{I, 0, 0}, {0, I, 0}, {0, 0, I}}}};
}

// Planar slider-crank R-S-U-P (no redundancy), crank a, rod b, zero offset, drawn
// at θ0 = 30°; crank 1 rev/s; gravity −y; gas force −200 sin(2πt) N on the slider.
json PlanarSliderCrank(const std::string& gas = "-200*sin(2*pi*t)") {
  const Eigen::Vector3d P(kA * std::cos(kTheta0), kA * std::sin(kTheta0), 0);
  const Eigen::Vector3d W(P.x() + std::sqrt(kB * kB - P.y() * P.y()), 0, 0);
  auto v = [](const Eigen::Vector3d& x) { return json::array({x.x(), x.y(), x.z()}); };
  return {{"mechkin", 1},
          {"units", {{"length", "m"}, {"angle", "deg"}, {"mass", "kg"}}},
          {"gravity", {0, -kG, 0}},
          {"bodies",
           {{{"name", "crank"}, {"position", {0, 0, 0}}, {"inertia", Inertia(kMc, P / 2, kIc)}},
            {{"name", "rod"}, {"position", v(P)}, {"inertia", Inertia(kMr, (P + W) / 2, kIr)}},
            {{"name", "slider"}, {"position", v(W)}, {"inertia", Inertia(kMs, W, 0.001)}}}},
          {"joints",
           {{{"name", "bearing"}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "crank"}, {"origin", {0, 0, 0}}, {"axis", {0, 0, 1}}},
            {{"name", "pin"}, {"type", "spherical"}, {"body1", "crank"}, {"body2", "rod"}, {"origin", v(P)}},
            {{"name", "wrist"}, {"type", "universal"}, {"body1", "rod"}, {"body2", "slider"}, {"origin", v(W)},
             {"axis1", {0, 0, 1}}, {"axis2", {0, 1, 0}}},
            {{"name", "guide"}, {"type", "prismatic"}, {"body1", "ground"}, {"body2", "slider"}, {"origin", v(W)}, {"axis", {1, 0, 0}}}}},
          {"drivers", {{{"name", "motor"}, {"type", "rotation"}, {"joint", "bearing"}, {"function", "360*t"}}}},
          {"loads", {{{"name", "gas"}, {"type", "force"}, {"body", "slider"}, {"point", v(W)}, {"components", {gas, 0, 0}}}}},
          {"analysis", {{"start", 0}, {"end", 1}, {"steps", 360}}}};
}

// Closed-form planar kinematics and the two independent references at time t.
struct Reference {
  double torque;               // energy method: T θ̇ = dE/dt − P_gas
  Eigen::Vector2d pin, wrist;  // Newton–Euler: force crank→rod, rod→slider
};

Reference ClosedForm(double t, double gas) {
  const double th = kTheta0 + kOmega * t, w = kOmega;
  const double sphi = -kA * std::sin(th) / kB, cphi = std::sqrt(1 - sphi * sphi);
  const double phid = -kA * std::cos(th) * w / (kB * cphi);
  const double phidd = (kA * std::sin(th) * w * w + kB * sphi * phid * phid) / (kB * cphi);
  const Eigen::Vector2d P(kA * std::cos(th), kA * std::sin(th)), vP(-kA * std::sin(th) * w, kA * std::cos(th) * w),
      aP = -w * w * P;
  const Eigen::Vector2d e(cphi, sphi), ed(-sphi * phid, cphi * phid), edd(-cphi * phid * phid - sphi * phidd, -sphi * phid * phid + cphi * phidd);
  const Eigen::Vector2d G = P + kB / 2 * e, vG = vP + kB / 2 * ed, aG = aP + kB / 2 * edd;
  const Eigen::Vector2d W = P + kB * e, vW = vP + kB * ed, aW = aP + kB * edd;
  const Eigen::Vector2d vC = vP / 2, aC = aP / 2;
  // dE/dt: kinetic (Σ m v·a + I ω α) and gravity (Σ m g ẏ).
  const double dE = kMc * vC.dot(aC) + kMr * vG.dot(aG) + kMs * vW.dot(aW) + kIr * phid * phidd +
                    kG * (kMc * vC.y() + kMr * vG.y() + kMs * vW.y());
  Reference r;
  r.torque = (dE - gas * vW.x()) / w;
  // Slider x: R_wx = m_s a_x − F_gas. Unknowns [Rcx, Rcy, Rwy, N]: rod x, rod y,
  // rod moment about G, slider y.
  const double Rwx = kMs * aW.x() - gas;
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  Eigen::Matrix4d M;
  Eigen::Vector4d rhs;
  const Eigen::Vector2d gp = P - G, gw = W - G;
  M << 1, 0, 0, 0, 0, 1, -1, 0, -gp.y(), gp.x(), -gw.x(), 0, 0, 0, 1, 1;
  rhs << kMr * aG.x() + Rwx, kMr * aG.y() + kMr * kG, kIr * phidd + cross(gw, Eigen::Vector2d(Rwx, 0)), kMs * kG;
  const Eigen::Vector4d x = M.fullPivLu().solve(rhs);
  r.pin = {x[0], x[1]};
  r.wrist = {Rwx, x[2]};
  return r;
}

double Scale(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s = std::max(s, std::abs(x));
  return s;
}

TEST(Forces, SliderCrankTorqueAndPinReactionsMatchClosedForms) {
  const Motion m = RunForces(FromJson(PlanarSliderCrank()));
  const auto t = Col(m, "t"), T = Col(m, "motor.effort");
  const auto pfx = Col(m, "pin.fx"), pfy = Col(m, "pin.fy"), wfx = Col(m, "wrist.fx"), wfy = Col(m, "wrist.fy");
  ASSERT_GE(t.size(), 100u);
  const double sT = Scale(T), sF = std::max(Scale(pfx), Scale(wfx));
  for (size_t k = 0; k < t.size(); ++k) {
    const Reference r = ClosedForm(t[k], -200 * std::sin(2 * M_PI * t[k]));
    EXPECT_NEAR(T[k], r.torque, 1e-9 * sT) << "t = " << t[k];
    EXPECT_NEAR(pfx[k], r.pin.x(), 1e-9 * sF);
    EXPECT_NEAR(pfy[k], r.pin.y(), 1e-9 * sF);
    EXPECT_NEAR(wfx[k], r.wrist.x(), 1e-9 * sF);
    EXPECT_NEAR(wfy[k], r.wrist.y(), 1e-9 * sF);
  }
  // What the joints cannot carry: the spherical no moment, the revolute no moment about its axis.
  EXPECT_LT(Scale(Col(m, "pin.mx")) + Scale(Col(m, "pin.my")) + Scale(Col(m, "pin.mz")), 1e-9 * sF * kA);
  EXPECT_LT(Scale(Col(m, "bearing.mh")), 1e-9 * sT);
  EXPECT_LT(Scale(Col(m, "guide.fh")), 1e-9 * sF);
}

TEST(Forces, EffortAndReactionRatesMatchDifferencesInTime) {
  json j = PlanarSliderCrank();
  j["analysis"] = {{"start", 0.2}, {"end", 0.2002}, {"steps", 20}};  // h = 1e-5 s
  const Motion m = RunForces(FromJson(j));
  const auto t = Col(m, "t");
  for (const char* name : {"motor.effort", "pin.fx", "pin.fy", "wrist.fx", "wrist.mx", "guide.mz"}) {
    const auto v = Col(m, name), v1 = Col(m, std::string(name) + "_t");
    const double scale = std::max(Scale(v1), 1e-3 * Scale(v) + 1e-12);
    for (size_t k = 1; k + 1 < t.size(); ++k)
      EXPECT_NEAR((v[k + 1] - v[k - 1]) / (t[k + 1] - t[k - 1]), v1[k], 1e-6 * scale) << name << " at " << t[k];
  }
  // And against the derivative of the closed-form torque (a central difference of the formula).
  const auto T1 = Col(m, "motor.effort_t");
  for (size_t k = 0; k < t.size(); k += 5) {
    const double h = 1e-6, a = t[k] + h, b = t[k] - h;
    const double d = (ClosedForm(a, -200 * std::sin(2 * M_PI * a)).torque - ClosedForm(b, -200 * std::sin(2 * M_PI * b)).torque) / (2 * h);
    EXPECT_NEAR(T1[k], d, 1e-6 * Scale(T1));
  }
}

// The potential of gravity, −Σ m g·r_c, with the centres at the body origins.
double Potential(const Motion& m, int row, const Model& model) {
  double V = 0;
  for (const Body& b : model.bodies) {
    const Eigen::Vector3d r(m.at(row, m.layout().Find(b.name + ".x")), m.at(row, m.layout().Find(b.name + ".y")),
                            m.at(row, m.layout().Find(b.name + ".z")));
    V -= b.inertia->mass * model.gravity.dot(r);
  }
  return V;
}

TEST(Forces, FourBarHeldAgainstGravityNeedsTheVirtualWorkTorque) {
  // Statics: a constant driver holds the crank at 40°; the bundled four-bar is
  // overconstrained (planar, all revolutes), the driver torque is still unique.
  json j = ReadJson("planar-four-bar.json");
  j["units"]["mass"] = "kg";
  j["gravity"] = {0, -9810, 0};  // mm/s²
  for (auto& b : j["bodies"]) b["inertia"] = Inertia(1.0 + b["position"][0].get<double>() / 100, Eigen::Vector3d(b["position"][0], b["position"][1], b["position"][2]), 500);
  auto held = [&](double deg) {
    json k = j;
    k["drivers"][0]["function"] = std::to_string(deg);
    k["analysis"] = {{"start", 0}, {"end", 1}, {"steps", 2}};
    return k;
  };
  const Model model = FromJson(held(40));
  const Motion m = RunForces(model, 3, true);
  // dV/dθ by Richardson-extrapolated central differences of tightly solved poses.
  auto diff = [&](double h) {
    const Motion plus = RunForces(FromJson(held(40 + h)), 3, true, 1e-14);
    const Motion minus = RunForces(FromJson(held(40 - h)), 3, true, 1e-14);
    return (Potential(plus, 0, model) - Potential(minus, 0, model)) / (2 * h * M_PI / 180);
  };
  const double dV = (4 * diff(0.005) - diff(0.01)) / 3;
  EXPECT_NEAR(Col(m, "motor.effort")[0], dV, 1e-8 * std::abs(dV));
  EXPECT_NEAR(Col(m, "motor.effort")[1], dV, 1e-8 * std::abs(dV));  // held: the same at every row
  EXPECT_LT(std::abs(Col(m, "kinetic_energy")[1]), 1e-20);
}

TEST(Forces, StewartPlatformCarryingAWeightMatchesJTransposeF) {
  json j = ReadJson("stewart-platform.json");
  const Model kin = FromJson(j);
  for (size_t d = 0; d < kin.drivers.size(); ++d)
    j["drivers"][d]["function"] = std::to_string(kin.drivers[d].function.Eval(0).c[0]);  // held (SI m = file m)
  const Eigen::Vector3d c(0.01, -0.02, 0.62);
  j["bodies"][0]["inertia"] = Inertia(250, c, 8);
  j["gravity"] = {0, 0, -9.81};
  j["analysis"] = {{"start", 0}, {"end", 1}, {"steps", 2}};
  const Model model = FromJson(j);
  const Motion m = RunForces(model);
  // Platform pose at row 0, legs' unit vectors u_i (base → platform), then
  // Σ f_i u_i = −W and Σ (p_i − c) × f_i u_i = 0 as a 6×6 system.
  const Eigen::Vector3d r(m.at(0, m.layout().Find("platform.x")), m.at(0, m.layout().Find("platform.y")), m.at(0, m.layout().Find("platform.z")));
  const Vec4 p(m.at(0, m.layout().Find("platform.e0")), m.at(0, m.layout().Find("platform.e1")),
               m.at(0, m.layout().Find("platform.e2")), m.at(0, m.layout().Find("platform.e3")));
  const Mat3 A = CalcA(p);
  const Eigen::Vector3d cg = r + A * model.bodies[0].inertia->center;
  Eigen::Matrix<double, 6, 6> Jt;
  for (int i = 0; i < 6; ++i) {
    const Driver& d = model.drivers[i];
    const Eigen::Vector3d base = d.point1, top = r + A * d.point2, u = (top - base).normalized();
    Jt.col(i) << u, (top - cg).cross(u);
  }
  Eigen::Matrix<double, 6, 1> wrench;
  wrench << -250 * model.gravity, Eigen::Vector3d::Zero();
  const Eigen::Matrix<double, 6, 1> f = Jt.fullPivLu().solve(wrench);
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(Col(m, model.drivers[i].name + ".effort")[0], f[i], 1e-9 * f.cwiseAbs().maxCoeff()) << "leg " << i;
}

TEST(Forces, EnergyBalancesOnEveryBundledMechanismGivenInertia) {
  int checked = 0;
  for (const char* file : {"bennett-linkage.json", "bricard-mechanism.json", "cylindrical-spindle.json", "five-bar.json",
                           "hooke-joint-30deg.json", "offset-slider-crank.json", "planar-four-bar.json",
                           "planar-xy-table.json", "r-ss-r-distance-link.json", "screw-jack.json",
                           "spatial-four-bar-rusr.json", "spatial-slider-crank.json", "stewart-platform.json"}) {
    json j = ReadJson(file);
    j["gravity"] = {0.3, -2.0, -9.0};
    int k = 0;
    for (auto& b : j["bodies"]) {
      const Eigen::Vector3d p(b["position"][0], b["position"][1], b["position"][2]);
      b["inertia"] = {{"mass", 1.0 + k},
                      {"center", {p.x() + 0.01 * k, p.y(), p.z() - 0.02}},
                      {"moments", {{2.0 + k, 0.1, 0.0}, {0.1, 3.0, 0.2}, {0.0, 0.2, 4.0}}}};
      ++k;
    }
    const Model model = FromJson(j);
    // At tol 1e-12: with redundant equations the minimum-norm multipliers of the
    // set-aside rows meet velocities that satisfy those rows only to the tolerance.
    const Motion m = RunForces(model, 3, true, 1e-12);
    // Relative to the size of the energy flows: driver power and the rates of the
    // kinetic and potential energy (from differences of their columns).
    double flow = 0, balance = 0;
    const auto t = Col(m, "t"), T = Col(m, "kinetic_energy"), V = Col(m, "potential_energy");
    for (int r = 0; r < m.rows(); ++r) {
      double p = 0;
      for (const auto& d : model.drivers) p += std::abs(m.at(r, m.layout().Find(d.name + ".power")));
      flow = std::max(flow, p);
      if (r > 0) flow = std::max({flow, std::abs((T[r] - T[r - 1]) / (t[r] - t[r - 1])), std::abs((V[r] - V[r - 1]) / (t[r] - t[r - 1]))});
      balance = std::max(balance, std::abs(m.at(r, m.layout().Find("energy_balance"))));
    }
    EXPECT_LE(balance, 1e-10 * flow) << file << " (largest energy flow " << flow << ")";
    ++checked;
  }
  EXPECT_EQ(checked, 13);
}

// The four-bar with spatial revolutes (3 redundant equations) against its
// R-U-S-R version: the same motion and masses, so the same driver torque; the
// redundant version names its indeterminate reaction components.
TEST(Forces, OverconstrainedFourBarNamesIndeterminateReactionsAndKeepsTheTorque) {
  json rrrr = ReadJson("planar-four-bar.json");
  rrrr["units"]["mass"] = "kg";
  rrrr["gravity"] = {0, -9810, 0};
  for (auto& b : rrrr["bodies"]) b["inertia"] = Inertia(1.2, Eigen::Vector3d(b["position"][0], b["position"][1], 0), 900);
  json rusr = rrrr;
  const Eigen::Vector3d B(rrrr["joints"][1]["origin"][0], rrrr["joints"][1]["origin"][1], 0);
  const Eigen::Vector3d C(rrrr["joints"][2]["origin"][0], rrrr["joints"][2]["origin"][1], 0);
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ().cross(C - B).normalized();
  rusr["joints"][1] = {{"name", "B"}, {"type", "universal"}, {"body1", "crank"}, {"body2", "coupler"},
                       {"origin", {B.x(), B.y(), 0}}, {"axis1", {0, 0, 1}}, {"axis2", {n.x(), n.y(), n.z()}}};
  rusr["joints"][2] = {{"name", "C"}, {"type", "spherical"}, {"body1", "coupler"}, {"body2", "rocker"}, {"origin", {C.x(), C.y(), 0}}};
  TableOptions t;
  t.order = 3;
  t.forces = true;
  const Motion a = RunMotion(FromJson(rrrr), AnalysisOptions{}, t), b = RunMotion(FromJson(rusr), AnalysisOptions{}, t);
  ASSERT_TRUE(a.complete && b.complete);
  const auto Ta = Col(a, "motor.effort"), Tb = Col(b, "motor.effort");
  for (size_t k = 0; k < Ta.size(); ++k) EXPECT_NEAR(Ta[k], Tb[k], 1e-9 * Scale(Tb));
  EXPECT_TRUE(b.report.indeterminate_reactions.empty());
  ASSERT_FALSE(a.report.indeterminate_reactions.empty());
  std::string all;
  for (const auto& s : a.report.indeterminate_reactions) all += s + "\n";
  // Out-of-plane force and the in-plane moments of the revolutes share the load.
  EXPECT_NE(all.find("joint `"), std::string::npos) << all;
  EXPECT_NE(all.find("rotation about"), std::string::npos) << all;
  EXPECT_EQ(all.find("motor"), std::string::npos) << "driver efforts are determinate:\n" << all;
  // The in-plane (determinate) reaction force at C agrees between the two versions.
  const auto fa = Col(a, "C.fx"), fb = Col(b, "C.fx");
  for (size_t k = 0; k < fa.size(); ++k) EXPECT_NEAR(fa[k], fb[k], 1e-8 * Scale(fb));
}

}  // namespace
}  // namespace mechkin
