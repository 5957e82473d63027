// The piston-driven slider-crank approaching its dead centre (the toggle), shared by
// the accuracy and error-bound tests.
#pragma once

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace mechkin::testing_files {

// Crank a, rod b, no offset, crank pin at (bx, by) in the design pose; the piston is
// driven so that the crank angle is θ(t) = θ0·cos(πt/2) exactly (θ0 = atan2(by, bx)):
// the dead centre θ = 0 at t = 1.   x(θ) = a cos θ + sqrt(b² − a² sin² θ)
struct Geometry {
  const char* unit;
  double a, b, bx, by;
};

// The closed form describes the mechanism the file stores only if the file's numbers
// are the closed form's: crank 34, rod 50, pin (16, 30), slider at 56 (a Pythagorean
// pair), in units of 1/64 m, so every coordinate, every body-fixed vector and every
// length is a double exactly, and metres need no conversion.
constexpr Geometry kExact{"m", 34.0 / 64, 50.0 / 64, 16.0 / 64, 30.0 / 64};
// Crank 20 mm, rod 50 mm at 60°: the pin (10, 17.32…) and the conversion to metres
// round every coordinate, which moves the exact answer itself.
constexpr Geometry kRounded{"mm", 20, 50, 10, 10 * 1.7320508075688772};

inline nlohmann::json PistonDrivenSliderCrank(const Geometry& g, double end, int steps) {
  const double th0 = std::atan2(g.by, g.bx), cx = g.bx + std::sqrt(g.b * g.b - g.by * g.by);
  char fn[320];
  std::snprintf(fn, sizeof fn, "%.17g*cos(%.17g*cos(pi*t/2)) + sqrt(%.17g - %.17g*sin(%.17g*cos(pi*t/2))^2) - %.17g",
                g.a, th0, g.b * g.b, g.a * g.a, th0, cx);
  return {{"mechkin", 1}, {"units", {{"length", g.unit}, {"angle", "deg"}}},
          {"bodies", {{{"name", "crank"}, {"position", {g.bx / 2, g.by / 2, 0}}},
                      {{"name", "rod"}, {"position", {(g.bx + cx) / 2, g.by / 2, 0}}},
                      {{"name", "slider"}, {"position", {cx, 0, 0}}}}},
          {"joints", {{{"name", "A"}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "crank"}, {"origin", {0, 0, 0}}, {"axis", {0, 0, 1}}},
                      {{"name", "B"}, {"type", "revolute"}, {"body1", "crank"}, {"body2", "rod"}, {"origin", {g.bx, g.by, 0}}, {"axis", {0, 0, 1}}},
                      {{"name", "C"}, {"type", "revolute"}, {"body1", "rod"}, {"body2", "slider"}, {"origin", {cx, 0, 0}}, {"axis", {0, 0, 1}}},
                      {{"name", "P"}, {"type", "prismatic"}, {"body1", "ground"}, {"body2", "slider"}, {"origin", {cx, 0, 0}}, {"axis", {1, 0, 0}}}}},
          {"drivers", {{{"name", "piston"}, {"type", "translation"}, {"joint", "P"}, {"function", fn}}}},
          {"outputs", {{{"name", "crank_angle"}, {"type", "joint"}, {"joint", "A"}}}},
          {"analysis", {{"start", 0}, {"end", end}, {"steps", steps}}}};
}

}  // namespace mechkin::testing_files
