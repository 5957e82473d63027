#include <gtest/gtest.h>

#include "analysis/load.hpp"

namespace mechkin {
namespace units_test {

TEST(Units, LengthFactors) {
  EXPECT_EQ(*LengthUnitToSi("m"), 1.0);
  EXPECT_EQ(*LengthUnitToSi("mm"), 1e-3);
  EXPECT_EQ(*LengthUnitToSi("cm"), 1e-2);
  EXPECT_EQ(*LengthUnitToSi("in"), 0.0254);
  EXPECT_FALSE(LengthUnitToSi("ft").has_value());
}

TEST(Units, AngleFactors) {
  EXPECT_EQ(*AngleUnitToSi("rad"), 1.0);
  EXPECT_DOUBLE_EQ(*AngleUnitToSi("deg") * 180.0, M_PI);
  EXPECT_FALSE(AngleUnitToSi("grad").has_value());
}

TEST(Units, ForceAndTorqueFactors) {
  EXPECT_EQ(*ForceUnitToSi("N"), 1.0);
  EXPECT_EQ(*ForceUnitToSi("kN"), 1e3);
  EXPECT_EQ(*ForceUnitToSi("mN"), 1e-3);
  EXPECT_DOUBLE_EQ(*ForceUnitToSi("lbf"), 0.45359237 * 9.80665);  // exact by definition
  EXPECT_FALSE(ForceUnitToSi("kgf").has_value());
  EXPECT_EQ(*TorqueUnitToSi("N*m"), 1.0);
  EXPECT_EQ(*TorqueUnitToSi("N*mm"), 1e-3);
  EXPECT_EQ(*TorqueUnitToSi("kN*m"), 1e3);
  EXPECT_DOUBLE_EQ(*TorqueUnitToSi("lbf*in"), 0.45359237 * 9.80665 * 0.0254);
  EXPECT_DOUBLE_EQ(*TorqueUnitToSi("lbf*ft"), 0.45359237 * 9.80665 * 0.3048);
  EXPECT_FALSE(TorqueUnitToSi("Nm").has_value());
}

// Named force and torque units: loads, stiffness (force / length), damping and
// preload to SI; without the keys, the derived units as before.
TEST(Units, NamedForceUnitsConvertLoadsAndSprings) {
  const std::string base = R"({"mechkin": 1, "units": {"length": "mm", "mass": "kg" UNITS},
    "bodies": [{"name": "b", "position": [10, 0, 0]}],
    "joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "b", "origin": [0, 0, 0], "axis": [0, 0, 1]}],
    "loads": [{"name": "f", "type": "force", "body": "b", "point": [10, 0, 0], "components": [2, 0, 0]},
              {"name": "m", "type": "torque", "body": "b", "components": [0, 0, 3]},
              {"name": "s", "type": "spring", "body1": "ground", "point1": [0, 5, 0], "body2": "b", "point2": [10, 0, 0],
               "stiffness": 4, "damping": 6, "preload": 7}]})";
  auto load = [&](const std::string& units) {
    std::string text = base;
    text.replace(text.find("UNITS"), 5, units);
    const LoadResult r = LoadMechanismText(text, "inline");
    EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
    return *r.model;
  };
  const Model derived = load(""), named = load(R"(, "force": "kN", "torque": "N*m")"), force = load(R"(, "force": "N")");
  EXPECT_DOUBLE_EQ(derived.loads[0].components[0].Eval(0).c[0], 2e-3);  // kg·mm/s²
  EXPECT_DOUBLE_EQ(derived.loads[1].components[2].Eval(0).c[0], 3e-6);  // kg·mm²/s²
  EXPECT_EQ(derived.loads[2].stiffness, 4.0);                           // kg/s² = N/m
  EXPECT_DOUBLE_EQ(named.loads[0].components[0].Eval(0).c[0], 2e3);
  EXPECT_DOUBLE_EQ(named.loads[1].components[2].Eval(0).c[0], 3.0);
  EXPECT_DOUBLE_EQ(named.loads[2].stiffness, 4e6);  // kN/mm
  EXPECT_DOUBLE_EQ(named.loads[2].damping, 6e6);
  EXPECT_DOUBLE_EQ(named.loads[2].preload, 7e3);
  EXPECT_DOUBLE_EQ(force.loads[1].components[2].Eval(0).c[0], 3e-3);  // N·mm
  EXPECT_DOUBLE_EQ(force.loads[2].stiffness, 4e3);                     // N/mm
  EXPECT_EQ(force.units.TorqueName(), "N*mm");
}

// The same geometry written in inches and degrees loads to the same SI model.
TEST(Units, FileInInchesAndDegreesIsConvertedToSi) {
  const std::string text = R"({"mechkin": 1, "units": {"length": "in", "angle": "deg"},
    "bodies": [{"name": "b", "position": [10, 0, 0], "orientation": {"axis": [0, 0, 1], "angle": 90}}],
    "joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "b", "origin": [0, 0, 0], "axis": [0, 0, 1]}],
    "drivers": [{"name": "d", "type": "rotation", "joint": "j", "function": "90*t"}]})";
  const LoadResult r = LoadMechanismText(text, "inline");
  ASSERT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  const Model& m = *r.model;
  EXPECT_NEAR(m.bodies[0].position.x(), 0.254, 1e-15);
  // 90° about z: e0 = cos 45°, e3 = sin 45°.
  EXPECT_NEAR(m.bodies[0].euler[0], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(m.bodies[0].euler[3], std::sqrt(0.5), 1e-15);
  // Driver value at t = 1: 90 deg = π/2 rad, rate π/2 rad/s.
  const Jet f = m.drivers[0].function.Eval(1.0);
  EXPECT_NEAR(f.c[0], M_PI / 2, 1e-15);
  EXPECT_NEAR(f.Derivative(1), M_PI / 2, 1e-15);
}

}  // namespace
}  // namespace mechkin
