#include <gtest/gtest.h>

#include "analysis/load.hpp"

namespace mechkin {
namespace {

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
