// The tooth force of a gear with a pitch radius in its bearings' reactions
// (constraints.md §3.11.1), against the statics of a spur pair on ground bearings:
// gear 2 carries a torque load τ(t) about z, gear 1 is driven at 1 rev/s, no
// inertia. Gear 2's moment balance about its axis gives the tangential tooth force
// τ/ρ₂, the pressure angle its radial (separating) part; each gear's force balance
// gives its bearing's reaction. Without pitch_radius the reactions stay as before
// (a coupler acts as torques: zero bearing force here).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace gear_tooth_force_test {

using nlohmann::json;
using testing_files::FromJson;

constexpr double kRho1 = 0.030, kRho2 = 0.060;  // m
double LoadAt(double t) { return 6 + 2 * std::sin(2 * M_PI * t); }           // N m on gear 2, about z
double LoadRate(double t) { return 4 * M_PI * std::cos(2 * M_PI * t); }

json Revolute(const std::string& name, const std::string& body, const json& origin) {
  return {{"name", name}, {"type", "revolute"}, {"body1", "ground"}, {"body2", body}, {"origin", origin}, {"axis", {0, 0, 1}}};
}

// Gear 1 at `o1`, gear 2 at `o2` (mm), θ₂ = ratio θ₁, the load on gear 2.
json GearPair(const json& o1, const json& o2, double ratio) {
  json j = {{"mechkin", 1}, {"name", "spur pair"}, {"units", {{"length", "mm"}, {"angle", "deg"}, {"force", "N"}, {"torque", "N*m"}}}};
  j["bodies"] = {{{"name", "gear1"}, {"position", o1}}, {{"name", "gear2"}, {"position", o2}}};
  j["joints"] = {Revolute("bearing1", "gear1", o1), Revolute("bearing2", "gear2", o2)};
  j["couplers"] = {{{"name", "mesh"}, {"type", "gear"}, {"joint1", "bearing1"}, {"joint2", "bearing2"}, {"ratio", ratio}}};
  j["drivers"] = {{{"name", "motor"}, {"type", "rotation"}, {"joint", "bearing1"}, {"function", "360*t"}}};
  j["loads"] = {{{"name", "brake"}, {"type", "torque"}, {"body", "gear2"}, {"components", {0, 0, "6 + 2*sin(2*pi*t)"}}}};
  j["analysis"] = {{"start", 0}, {"end", 1}, {"steps", 40}};
  return j;
}

Motion RunPair(const json& j) {
  TableOptions t;
  t.order = 3;
  t.si = true;
  t.forces = true;
  AnalysisOptions o;
  o.tolerance = 1e-12;
  Motion m = RunMotion(FromJson(j), o, t);
  EXPECT_TRUE(m.complete) << m.stop.message;
  return m;
}

std::vector<double> Col(const Motion& m, const std::string& name) {
  const int c = m.layout().Find(name);
  EXPECT_GE(c, 0) << name;
  return c >= 0 ? m.Column(c) : std::vector<double>(m.rows(), 0.0);
}

// The tooth force f on gear 1 at time t (or its rate), global axes, for a pitch
// point P with P − O₂ = arm2 · x: gear 2 takes −f at P, so its balance about z is
// −arm2 f_y + τ = 0; the radial part pushes gear 1 (external teeth, its axis on the
// −x side of P) towards its axis, |f_y| tan 20°.
Vec3 ToothForceOnGear1(double t, double arm2, bool rate) {
  const double fy = LoadAt(t) / arm2, fy_t = LoadRate(t) / arm2, tan20 = std::tan(20 * M_PI / 180);
  if (rate) return {-std::copysign(1.0, fy) * fy_t * tan20, fy_t, 0};
  return {-std::abs(fy) * tan20, fy, 0};
}

// Worst |reported − expected| over the run, relative to the largest expected force,
// for bearing1 = −f and bearing2 = +f, the forces and (with `rate`) their rates.
double WorstReactionError(const Motion& m, double arm2, bool rate, double* scale) {
  const auto t = Col(m, "t");
  const char* suffix = rate ? "_t" : "";
  double worst = 0;
  *scale = 0;
  for (int r = 0; r < m.rows(); ++r) {
    const Vec3 f = ToothForceOnGear1(t[r], arm2, rate);
    *scale = std::max(*scale, f.norm());
    for (int a = 0; a < 3; ++a) {
      const std::string ax = std::string(1, "xyz"[a]);
      worst = std::max(worst, std::abs(Col(m, "bearing1.f" + ax + suffix)[r] + f[a]));
      worst = std::max(worst, std::abs(Col(m, "bearing2.f" + ax + suffix)[r] - f[a]));
      // Spur gears in one plane: the moments about the joint origins are unchanged (0).
      worst = std::max(worst, std::abs(Col(m, "bearing1.m" + ax + suffix)[r]) / kRho1);
      worst = std::max(worst, std::abs(Col(m, "bearing2.m" + ax + suffix)[r]) / kRho1);
    }
    if (rate) continue;
    // In the gears' own (turning) joint frames: the same force, |(f, g)| = |f|, h = 0.
    for (const char* j : {"bearing1", "bearing2"}) {
      const std::string n = j;
      const double ff = Col(m, n + ".ff")[r], fg = Col(m, n + ".fg")[r], fh = Col(m, n + ".fh")[r];
      worst = std::max({worst, std::abs(std::hypot(ff, fg) - f.norm()), std::abs(fh)});
    }
  }
  return worst / *scale;
}

// External pair: ρ₁ = 30 mm, ratio −1/2 (ρ₂ = ρ₁/|r| = 60 mm), centres 90 mm apart
// on x; pitch point (30, 0, 0) mm, gear 2's arm −ρ₂ ((−ρ₂ x) × y = −ρ₂ z).
TEST(CouplersToothForce, ExternalSpurPairBearingsCarryTheToothForce) {
  json j = GearPair({0, 0, 0}, {90, 0, 0}, -0.5);
  const Motion plain = RunPair(j);
  j["couplers"][0]["pitch_radius"] = 30;
  const Motion teeth = RunPair(j);
  double scale = 0, scale_rate = 0;
  const double worst = WorstReactionError(teeth, -kRho2, false, &scale);
  const double worst_rate = WorstReactionError(teeth, -kRho2, true, &scale_rate);
  // Without pitch_radius the coupler acts as torques: no bearing force at all.
  double worst_plain = 0, worst_effort = 0;
  const auto t = Col(plain, "t"), e0 = Col(plain, "motor.effort"), e1 = Col(teeth, "motor.effort");
  for (int r = 0; r < plain.rows(); ++r) {
    for (const char* c : {"bearing1.fx", "bearing1.fy", "bearing2.fx", "bearing2.fy", "bearing2.fx_t"})
      worst_plain = std::max(worst_plain, std::abs(Col(plain, c)[r]) / scale);
    // The motor's torque is the same either way: τ ρ₁/ρ₂ (gear 1's balance).
    worst_effort = std::max({worst_effort, std::abs(e0[r] - LoadAt(t[r]) * kRho1 / kRho2) / LoadAt(t[r]),
                             std::abs(e1[r] - e0[r]) / LoadAt(t[r])});
  }
  std::printf("[measured] external pair: reactions vs ±tooth force %.2e, rates %.2e (of %.3g N, %.3g N/s); "
              "without pitch_radius bearing force %.2e; motor torque %.2e (relative)\n",
              worst, worst_rate, scale, scale_rate, worst_plain, worst_effort);
  EXPECT_GT(scale, 100);  // (τ / ρ₂ ≥ 4 N m / 0.06 m)
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(worst_rate, 1e-10);
  EXPECT_LT(worst_plain, 1e-10);
  EXPECT_LT(worst_effort, 1e-10);
  // The pressure angle tilts the line of action: 0 leaves only the tangential part.
  j["couplers"][0]["pressure_angle"] = 0;
  const Motion tangential = RunPair(j);
  const double fx = Col(tangential, "bearing2.fx")[5], fy = Col(tangential, "bearing2.fy")[5];
  EXPECT_LT(std::abs(fx), 1e-10 * std::abs(fy));
  EXPECT_NEAR(fy, Col(teeth, "bearing2.fy")[5], 1e-10 * std::abs(fy));
}

// Internal pair: a 30 mm pinion at (30, 0, 0) mm inside a 60 mm ring centred at the
// origin, ratio +1/2 (same sense); pitch point (60, 0, 0) mm on the far side of the
// pinion's axis from the ring's, gear 2's arm +ρ₂ ((ρ₂ x) × y = ρ₂ z).
TEST(CouplersToothForce, InternalPairPushesThePinionTowardsItsAxis) {
  json j = GearPair({30, 0, 0}, {0, 0, 0}, 0.5);
  j["couplers"][0]["pitch_radius"] = 30;
  const Motion teeth = RunPair(j);
  double scale = 0, scale_rate = 0;
  const double worst = WorstReactionError(teeth, kRho2, false, &scale);
  const double worst_rate = WorstReactionError(teeth, kRho2, true, &scale_rate);
  std::printf("[measured] internal pair: reactions vs ±tooth force %.2e, rates %.2e (of %.3g N)\n", worst, worst_rate,
              scale);
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(worst_rate, 1e-10);
}

// The pair on a carrier turning about z at ψ = 90 t deg (a ground revolute, driven),
// gear 1 driven relative to it, gear 2's bearing 10 mm up the axis from gear 1's
// (pitch) plane. No inertia: in the carrier's axes the statics are the ground case,
// so f = R(ψ)(−|τ|/ρ₂ tan φ, −τ/ρ₂, 0) and its rate Ṙf' + Rḟ'; bearing2's moment about
// its origin is (P − O₂) × f − τz = −0.01 m · z × f (the tooth force 10 mm below it).
TEST(CouplersToothForce, OnATurningCarrierWithAnAxialOffset) {
  json j = GearPair({20, 0, 0}, {110, 0, 10}, -0.5);
  j["bodies"].push_back({{"name", "carrier"}, {"position", {0, 0, 0}}});
  for (json& joint : j["joints"]) joint["body1"] = "carrier";
  j["joints"].push_back(Revolute("carrier_pin", "carrier", {0, 0, 0}));
  j["drivers"].push_back({{"name", "carrier_motor"}, {"type", "rotation"}, {"joint", "carrier_pin"}, {"function", "90*t"}});
  j["couplers"][0]["pitch_radius"] = 30;
  const Motion m = RunPair(j);
  const auto t = Col(m, "t");
  const double tan20 = std::tan(20 * M_PI / 180), psi_t = M_PI / 2;
  double worst = 0, scale = 0;
  for (int r = 0; r < m.rows(); ++r) {
    const double psi = psi_t * t[r], tau = LoadAt(t[r]), tau_t = LoadRate(t[r]);
    const Vec3 e(std::cos(psi), std::sin(psi), 0), tg(-std::sin(psi), std::cos(psi), 0);
    const Vec3 f = -tau / kRho2 * tan20 * e - tau / kRho2 * tg;
    const Vec3 f_t = -tau_t / kRho2 * tan20 * e - tau_t / kRho2 * tg + psi_t * (-tau / kRho2 * tan20 * tg + tau / kRho2 * e);
    const Vec3 m2 = -0.01 * Vec3::UnitZ().cross(f), m2_t = -0.01 * Vec3::UnitZ().cross(f_t);
    scale = std::max(scale, f.norm());
    for (int a = 0; a < 3; ++a) {
      const std::string ax = std::string(1, "xyz"[a]);
      worst = std::max({worst, std::abs(Col(m, "bearing1.f" + ax)[r] + f[a]), std::abs(Col(m, "bearing2.f" + ax)[r] - f[a]),
                        std::abs(Col(m, "bearing1.f" + ax + "_t")[r] + f_t[a]) / psi_t,
                        std::abs(Col(m, "bearing2.f" + ax + "_t")[r] - f_t[a]) / psi_t,
                        std::abs(Col(m, "bearing1.m" + ax)[r]) / kRho1,
                        std::abs(Col(m, "bearing2.m" + ax)[r] - m2[a]) / kRho1,
                        std::abs(Col(m, "bearing2.m" + ax + "_t")[r] - m2_t[a]) / (kRho1 * psi_t)});
    }
  }
  std::printf("[measured] turning carrier, 10 mm axial offset: reactions, moments and rates vs closed form %.2e "
              "(relative to %.3g N)\n", worst / scale, scale);
  EXPECT_GT(scale, 100);
  EXPECT_LT(worst / scale, 1e-10);
}

std::string FirstError(const json& j) {
  const LoadResult r = LoadMechanismText(j.dump(), "inline");
  return r.errors.empty() ? "" : r.errors[0].ToString();
}

TEST(CouplersToothForce, RejectsMeshesItCannotPlace) {
  json off = GearPair({0, 0, 0}, {85, 0, 0}, -0.5);
  off["couplers"][0]["pitch_radius"] = 30;
  const std::string centres = FirstError(off);
  EXPECT_NE(centres.find("/couplers/0/pitch_radius"), std::string::npos) << centres;
  EXPECT_NE(centres.find("need centres 90 apart"), std::string::npos) << centres;
  EXPECT_NE(centres.find("85"), std::string::npos) << centres;  // the axes' distance, and the fitting radius
  json slide = GearPair({0, 0, 0}, {90, 0, 0}, -0.5);
  slide["joints"][1]["type"] = "cylindrical";
  slide["couplers"][0]["pitch_radius"] = 30;
  const std::string cyl = FirstError(slide);
  EXPECT_NE(cyl.find("/couplers/0/pitch_radius"), std::string::npos) << cyl;
  EXPECT_NE(cyl.find("revolute bearings"), std::string::npos) << cyl;
  json angle_only = GearPair({0, 0, 0}, {90, 0, 0}, -0.5);
  angle_only["couplers"][0]["pressure_angle"] = 20;
  const std::string lone = FirstError(angle_only);
  EXPECT_NE(lone.find("/couplers/0/pressure_angle"), std::string::npos) << lone;
  json belt = GearPair({0, 0, 0}, {90, 0, 0}, -0.5);
  belt["couplers"][0]["type"] = "belt";
  belt["couplers"][0]["pitch_radius"] = 30;
  EXPECT_NE(FirstError(belt).find("pitch_radius"), std::string::npos) << FirstError(belt);
}

}  // namespace
}  // namespace mechkin
