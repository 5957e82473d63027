// Test helpers: the repository's mechanism files and test data as JSON or models.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "analysis/motion.hpp"
#include "analysis/load.hpp"

namespace mechkin::testing_files {

/// mechanisms/NAME as JSON.
inline nlohmann::json ReadJson(const std::string& name) {
  std::ifstream f(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/" + name);
  return nlohmann::json::parse(f);
}

/// tests/data/NAME as JSON.
inline nlohmann::json ReadTestData(const std::string& name) {
  std::ifstream f(std::string(MECHKIN_SOURCE_DIR) + "/tests/data/" + name);
  return nlohmann::json::parse(f);
}

/// A model from a JSON document; the test fails if the loader rejects it.
inline Model FromJson(const nlohmann::json& j) {
  LoadResult r = LoadMechanismText(j.dump(), "inline");
  EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  return r.ok() ? std::move(*r.model) : Model{};
}

/// The rows of a motion, one vector per row.
inline std::vector<std::vector<double>> RowsOf(const Motion& m) {
  std::vector<std::vector<double>> rows(m.rows());
  for (int r = 0; r < m.rows(); ++r) rows[r].assign(&m.values()[static_cast<size_t>(r) * m.cols()], &m.values()[static_cast<size_t>(r + 1) * m.cols()]);
  return rows;
}

/// The header cells ("crank.x [m]") of a motion.
inline std::vector<std::string> HeaderOf(const Motion& m) {
  std::vector<std::string> h;
  for (const auto& c : m.columns()) h.push_back(c.Header());
  return h;
}

/// A planar four-bar of revolutes about z (crank a from the origin, coupler b, rocker
/// c to the ground pivot at (d, 0)), upper assembly branch, crank at theta0_deg; the
/// crank turns 360°/s, output `rocker_angle`. Overconstrained by 3 (spatial revolutes).
inline nlohmann::json PlanarFourBar(double a, double b, double c, double d, double theta0_deg, int steps) {
  const double th = theta0_deg * M_PI / 180;
  const double Bx = a * std::cos(th), By = a * std::sin(th);
  const double dx = d - Bx, dy = -By, dist = std::hypot(dx, dy);
  const double al = (b * b - c * c + dist * dist) / (2 * dist), h = std::sqrt(b * b - al * al);
  const double Cx = Bx + (al * dx - h * dy) / dist, Cy = By + (al * dy + h * dx) / dist;
  using nlohmann::json;
  const json z = {0, 0, 1};
  return {{"mechkin", 1}, {"units", {{"length", "mm"}, {"angle", "deg"}}},
          {"bodies", {{{"name", "crank"}, {"position", {Bx / 2, By / 2, 0}}},
                      {{"name", "coupler"}, {"position", {(Bx + Cx) / 2, (By + Cy) / 2, 0}}},
                      {{"name", "rocker"}, {"position", {(Cx + d) / 2, Cy / 2, 0}}}}},
          {"joints", {{{"name", "A"}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "crank"}, {"origin", {0, 0, 0}}, {"axis", z}},
                      {{"name", "B"}, {"type", "revolute"}, {"body1", "crank"}, {"body2", "coupler"}, {"origin", {Bx, By, 0}}, {"axis", z}},
                      {{"name", "C"}, {"type", "revolute"}, {"body1", "coupler"}, {"body2", "rocker"}, {"origin", {Cx, Cy, 0}}, {"axis", z}},
                      {{"name", "D"}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "rocker"}, {"origin", {d, 0, 0}}, {"axis", z}}}},
          {"drivers", {{{"name", "motor"}, {"type", "rotation"}, {"joint", "A"}, {"function", "360*t"}}}},
          {"analysis", {{"start", 0}, {"end", 1}, {"steps", steps}}},
          {"outputs", {{{"name", "rocker_angle"}, {"type", "joint"}, {"joint", "D"}}}}};
}


}  // namespace mechkin::testing_files
