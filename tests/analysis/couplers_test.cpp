// Couplers between joint coordinates (constraints.md §3.11) on the bundled examples,
// against closed forms: the Willis equation of a planetary train at every order and
// after 10⁴ input turns, a rack and pinion's travel and torque, a differential, a
// crank driven through a gear pair against the same crank driven directly (virtual
// work), and the energy balance of every example given mass properties.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace couplers_test {

using nlohmann::json;
using testing_files::FromJson;
using testing_files::ReadJson;

Motion RunTable(const Model& m, int order, bool forces, double tol = 1e-10) {
  TableOptions t;
  t.order = order;
  t.si = true;
  t.forces = forces;
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

const char* kSuffix[] = {"", "_t", "_tt", "_ttt", "_tttt"};
constexpr double kZs = 24, kZp = 18, kZr = 60;

// θ_s = 2π t, θ_r = −π t / 2 (the file's drivers, SI): the carrier by Willis, the
// planet (relative to the carrier) from the sun mesh, at derivative order k.
double SunAt(double t, int k) { return k == 0 ? 2 * M_PI * t : k == 1 ? 2 * M_PI : 0; }
double RingAt(double t, int k) { return k == 0 ? -M_PI / 2 * t : k == 1 ? -M_PI / 2 : 0; }
double CarrierAt(double t, int k) { return (kZs * SunAt(t, k) + kZr * RingAt(t, k)) / (kZs + kZr); }
double PlanetAt(double t, int k) { return -kZs / kZp * (SunAt(t, k) - CarrierAt(t, k)); }

TEST(Couplers, PlanetaryCarrierFollowsWillisAtEveryOrder) {
  const Model m = FromJson(ReadJson("planetary-gear-train.json"));
  const Motion run = RunTable(m, 4, false);
  ASSERT_GT(run.rows(), 100);
  const auto t = Col(run, "t");
  double worst_carrier = 0, worst_planet = 0;
  for (int k = 0; k <= 4; ++k) {
    const auto c = Col(run, std::string("carrier_angle") + kSuffix[k]);
    const auto p = Col(run, std::string("planet_spin") + kSuffix[k]);
    for (int r = 0; r < run.rows(); ++r) {
      worst_carrier = std::max(worst_carrier, std::abs(c[r] - CarrierAt(t[r], k)) / (1 + std::abs(CarrierAt(t[r], k))));
      worst_planet = std::max(worst_planet, std::abs(p[r] - PlanetAt(t[r], k)) / (1 + std::abs(PlanetAt(t[r], k))));
    }
  }
  std::printf("[measured] Willis, orders 0-4: carrier %.2e, planet %.2e (relative)\n", worst_carrier, worst_planet);
  EXPECT_LT(worst_carrier, 1e-12);
  EXPECT_LT(worst_planet, 1e-12);
}

// 10⁴ sun revolutions (10⁴ s at 1 rev/s, 1/8 turn per step): the joint coordinates
// count whole turns, so the carrier and the planets end within 1e-9 rad of the
// closed form (≈ 6700 rad and 75000 rad).
TEST(Couplers, PlanetaryTenThousandTurnsWithoutDrift) {
  json j = ReadJson("planetary-gear-train.json");
  j["analysis"] = {{"start", 0}, {"end", 10000}, {"steps", 80000}};
  j["outputs"].push_back({{"name", "planet3_spin"}, {"type", "joint"}, {"joint", "planet3_pin"}});
  const Model m = FromJson(j);
  TableOptions table;
  table.order = 1;
  table.si = true;
  table.all_bodies = false;
  AnalysisOptions o;
  o.tolerance = 1e-10;
  const Motion run = RunMotion(m, o, table);
  ASSERT_TRUE(run.complete) << run.stop.message;
  const int last = run.rows() - 1;
  const double t = run.at(last, run.layout().Find("t"));
  ASSERT_DOUBLE_EQ(t, 10000);
  std::printf("[measured] after 1e4 turns: carrier %.2e rad, planet %.2e rad, planet3 %.2e rad\n",
              std::abs(run.at(last, run.layout().Find("carrier_angle")) - CarrierAt(t, 0)),
              std::abs(run.at(last, run.layout().Find("planet_spin")) - PlanetAt(t, 0)),
              std::abs(run.at(last, run.layout().Find("planet3_spin")) - PlanetAt(t, 0)));
  EXPECT_NEAR(run.at(last, run.layout().Find("carrier_angle")), CarrierAt(t, 0), 1e-9);
  EXPECT_NEAR(run.at(last, run.layout().Find("planet_spin")), PlanetAt(t, 0), 1e-9);
  EXPECT_NEAR(run.at(last, run.layout().Find("planet3_spin")), PlanetAt(t, 0), 1e-9);
  EXPECT_NEAR(run.at(last, run.layout().Find("carrier_angle_t")), CarrierAt(t, 1), 1e-12);
}

// Rack travel = pitch radius × steering angle at every row and order; with the road
// force F = 500 N on the rack and no inertia, the steering wheel's torque is −F ρ
// (virtual work: τ δθ + F ρ δθ = 0).
TEST(Couplers, RackTravelIsPitchRadiusTimesSteeringAngle) {
  const Model m = FromJson(ReadJson("rack-and-pinion-steering.json"));
  const Motion run = RunTable(m, 3, true);
  const double rho = 0.008, F = 500;
  const auto t = Col(run, "t");
  double worst_travel = 0, worst_torque = 0, swing = 0;
  for (int k = 0; k <= 3; ++k) {
    const auto s = Col(run, std::string("rack_travel") + kSuffix[k]);
    for (int r = 0; r < run.rows(); ++r) {
      // The steering angle from the driver 90° sin(πt), in rad, and its derivatives.
      const double w = M_PI, a = M_PI / 2, ph = w * t[r] + k * M_PI / 2;
      const double theta_k = a * std::pow(w, k) * std::sin(ph);
      worst_travel = std::max(worst_travel, std::abs(s[r] - rho * theta_k) / (rho * a * std::pow(w, k)));
      if (k == 0) swing = std::max(swing, std::abs(s[r]));
    }
  }
  const auto tau = Col(run, "steering_wheel.effort");
  for (double v : tau) worst_torque = std::max(worst_torque, std::abs(v - (-F * rho)));
  std::printf("[measured] rack travel - rho*theta (orders 0-3, relative) %.2e; wheel torque + F rho %.2e N m\n",
              worst_travel, worst_torque);
  EXPECT_LT(worst_travel, 1e-12);
  EXPECT_LT(worst_torque, 1e-10);
  EXPECT_NEAR(swing, rho * M_PI / 2, 1e-9);  // the rack really travels ρ·90°
  // The coupler's own outputs: the tooth force on the rack's coordinate (−F, holding
  // the road force), the torque on the pinion's (F ρ), and the power it takes from
  // the pinion, −F ρ θ̇, which the rack's coordinate receives.
  const auto q1 = Col(run, "steering_gear.effort1"), q2 = Col(run, "steering_gear.effort2");
  const auto power = Col(run, "steering_gear.power"), rate = Col(run, "steering_gear.power_t");
  double worst_effort = 0, worst_power = 0, worst_rate = 0;
  for (int r = 0; r < run.rows(); ++r) {
    const double thd = M_PI / 2 * M_PI * std::cos(M_PI * t[r]), thdd = -M_PI / 2 * M_PI * M_PI * std::sin(M_PI * t[r]);
    worst_effort = std::max({worst_effort, std::abs(q2[r] + F), std::abs(q1[r] - F * rho)});
    worst_power = std::max(worst_power, std::abs(power[r] + F * rho * thd));
    worst_rate = std::max(worst_rate, std::abs(rate[r] + F * rho * thdd));
  }
  std::printf("[measured] tooth force / pinion torque %.2e, power %.2e, power rate %.2e\n", worst_effort, worst_power,
              worst_rate);
  EXPECT_LT(worst_effort, 1e-9);
  EXPECT_LT(worst_power, 1e-9);
  EXPECT_LT(worst_rate, 1e-8);
}

// θ_left + θ_right = 2 θ_case: the right axle against 2θ_case − θ_left at every order.
TEST(Couplers, DifferentialRightAxleAgainstClosedForm) {
  const Model m = FromJson(ReadJson("open-differential.json"));
  const Motion run = RunTable(m, 4, false);
  const auto t = Col(run, "t");
  double worst = 0;
  for (int k = 0; k <= 4; ++k) {
    const auto right = Col(run, std::string("right_angle") + kSuffix[k]);
    for (int r = 0; r < run.rows(); ++r) {
      // θ_case = 2π t, θ_left = 2π t − (π/18) sin(π t).
      const double wc = k == 0 ? 2 * M_PI * t[r] : k == 1 ? 2 * M_PI : 0;
      const double lag = M_PI / 18 * std::pow(M_PI, k) * std::sin(M_PI * t[r] + k * M_PI / 2);
      const double want = 2 * wc - (wc - lag);
      worst = std::max(worst, std::abs(right[r] - want) / (1 + std::abs(want)));
    }
  }
  std::printf("[measured] differential right axle, orders 0-4: %.2e\n", worst);
  EXPECT_LT(worst, 1e-12);
}

json Inertia(double mass, const json& center, double I) {
  return {{"mass", mass}, {"center", center}, {"moments", {{I, 0, 0}, {0, I, 0}, {0, 0, I}}}};
}

// The geared crank with mass on the crank and slider, gravity and a slider force,
// against the same crank driven directly by θ_c = r θ_m: virtual work through the
// mesh gives τ_motor = r τ_crank at every instant.
TEST(Couplers, EffortThroughGearPairMatchesVirtualWork) {
  json geared = ReadJson("geared-slider-crank.json");
  geared["units"]["mass"] = "kg";
  geared["gravity"] = {0, -9810, 0};
  geared["bodies"][1]["inertia"] = Inertia(1.5, {10, 5, 0}, 400);
  geared["bodies"][2]["inertia"] = Inertia(0.8, geared["bodies"][2]["position"], 100);
  geared["loads"] = {{{"name", "gas"}, {"type", "force"}, {"body", "slider"}, {"point", geared["bodies"][2]["position"]},
                      {"components", {"-2e5*sin(2*pi*t)", 0, 0}}}};
  json direct = geared;
  direct.erase("couplers");
  direct["bodies"].erase(0);
  direct["joints"].erase(0);
  direct["drivers"] = {{{"name", "crank_motor"}, {"type", "rotation"}, {"joint", "crank_bearing"}, {"function", "-0.25*1440*t"}}};
  const Motion a = RunTable(FromJson(geared), 3, true), b = RunTable(FromJson(direct), 3, true);
  ASSERT_EQ(a.rows(), b.rows());
  const auto tm = Col(a, "motor.effort"), tc = Col(b, "crank_motor.effort");
  const auto pm = Col(a, "motor.power"), pc = Col(b, "crank_motor.power");
  double worst = 0, scale = 0, worst_power = 0;
  for (int r = 0; r < a.rows(); ++r) scale = std::max(scale, std::abs(tm[r]));
  for (int r = 0; r < a.rows(); ++r) {
    worst = std::max(worst, std::abs(tm[r] - (-0.25) * tc[r]) / scale);
    worst_power = std::max(worst_power, std::abs(pm[r] - pc[r]) / (scale * 1440 * M_PI / 180));
  }
  std::printf("[measured] geared vs direct crank: motor torque - r*crank torque %.2e (of %.3g N m), power %.2e\n",
              worst, scale, worst_power);
  EXPECT_GT(scale, 1e-3);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_power, 1e-9);
}

// Every new example, given mass properties and gravity: the couplers do no work,
// so driver power + load power − d(T + V)/dt stays at round-off (relative 1e-10).
TEST(Couplers, EnergyBalancesOnEveryCouplerExampleGivenInertia) {
  for (const char* file : {"planetary-gear-train.json", "rack-and-pinion-steering.json", "open-differential.json",
                           "geared-slider-crank.json"}) {
    json j = ReadJson(file);
    j["units"]["mass"] = "kg";
    j["gravity"] = {0.3, -2000.0, -9000.0};
    int k = 0;
    for (auto& b : j["bodies"]) {
      const json p = b["position"];
      b["inertia"] = {{"mass", 1.0 + k},
                      {"center", {p[0].get<double>() + 10.0 * k, p[1].get<double>() + 3.0, p[2].get<double>() - 20.0}},
                      {"moments", {{200.0 + k, 10.0, 0.0}, {10.0, 300.0, 20.0}, {0.0, 20.0, 400.0}}}};
      ++k;
    }
    const Model model = FromJson(j);
    const Motion m = RunTable(model, 3, true, 1e-12);
    double flow = 0, balance = 0;
    const auto t = Col(m, "t"), T = Col(m, "kinetic_energy"), V = Col(m, "potential_energy");
    for (int r = 0; r < m.rows(); ++r) {
      double p = 0;
      for (const auto& d : model.drivers) p += std::abs(m.at(r, m.layout().Find(d.name + ".power")));
      flow = std::max(flow, p);
      if (r > 0) flow = std::max({flow, std::abs((T[r] - T[r - 1]) / (t[r] - t[r - 1])), std::abs((V[r] - V[r - 1]) / (t[r] - t[r - 1]))});
      balance = std::max(balance, std::abs(m.at(r, m.layout().Find("energy_balance"))));
    }
    std::printf("[measured] %s: energy balance %.2e of flow %.3g\n", file, balance / flow, flow);
    EXPECT_GT(flow, 0) << file;
    EXPECT_LE(balance, 1e-10 * flow) << file << " (largest energy flow " << flow << ")";
  }
}

}  // namespace
}  // namespace mechkin
