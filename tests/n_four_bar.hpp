// The IFToMM A02 N-four-bar, shared by the tests that run it (singular positions,
// error bounds, the CLI's note): a crank and N rockers of length 1 on ground pivots 1
// apart along x, couplers of length 1 joining consecutive tips — N parallelogram
// windows, each sharing its left rocker with the window before (the crank is the
// first). θ is the crank angle from +y; every window's factor of det Φ_q is −cos θ:
// at θ = −90° the driven motion passes uniquely, at +90° the parallelogram branch
// crosses N folded ones.
#pragma once

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

namespace mechkin::testing_files {

/// Drawn on the parallelogram branch at crank angle theta0 (deg, from +y), driven by
/// rate·t deg over [0, 1] s in `steps` rows. Bodies: crank, rocker1 … rockerN (0 … N),
/// then coupler1 … couplerN (N + 1 … 2N), each coupler's frame at its left tip.
inline nlohmann::json NFourBar(int n, double theta0_deg, double rate_deg, int steps) {
  const double th = theta0_deg * M_PI / 180, ex = -std::sin(th), ey = std::cos(th);
  auto point = [](double x, double y) { return nlohmann::json::array({x, y, 0.0}); };
  nlohmann::json j = {{"mechkin", 1}, {"name", "N-four-bar"}, {"units", {{"length", "m"}, {"angle", "deg"}}}};
  auto rocker = [](int i) { return i == 0 ? std::string("crank") : "rocker" + std::to_string(i); };
  j["bodies"] = nlohmann::json::array();
  j["joints"] = nlohmann::json::array();
  for (int i = 0; i <= n; ++i) {
    j["bodies"].push_back({{"name", rocker(i)}, {"position", point(i, 0)}});
    j["joints"].push_back({{"name", "pivot" + std::to_string(i)}, {"type", "revolute"}, {"body1", "ground"},
                           {"body2", rocker(i)}, {"origin", point(i, 0)}, {"axis", {0, 0, 1}}});
  }
  for (int i = 1; i <= n; ++i) {
    const std::string c = "coupler" + std::to_string(i);
    j["bodies"].push_back({{"name", c}, {"position", point(i - 1 + ex, ey)}});
    j["joints"].push_back({{"name", "left" + std::to_string(i)}, {"type", "revolute"}, {"body1", rocker(i - 1)},
                           {"body2", c}, {"origin", point(i - 1 + ex, ey)}, {"axis", {0, 0, 1}}});
    j["joints"].push_back({{"name", "right" + std::to_string(i)}, {"type", "revolute"}, {"body1", c},
                           {"body2", rocker(i)}, {"origin", point(i + ex, ey)}, {"axis", {0, 0, 1}}});
  }
  char fn[64];
  std::snprintf(fn, sizeof fn, "%.17g*t", rate_deg);
  j["drivers"] = {{{"name", "crank"}, {"type", "rotation"}, {"joint", "pivot0"}, {"function", fn}}};
  j["analysis"] = {{"start", 0}, {"end", 1}, {"steps", steps}};
  return j;
}

}  // namespace mechkin::testing_files
