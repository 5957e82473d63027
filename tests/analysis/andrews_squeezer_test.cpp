// Andrews' squeezer (Schiehlen's benchmark, Hairer & Wanner's "andrews" problem):
// seven bodies, ten revolutes, one freedom. The crank K1 turns about O by β; K2 hangs
// on it at F (relative angle Θ) and carries the point E where three more loops close:
// K3 from B (γ), K4–K5 from A (δ, Φ), K6–K7 from A (ε, Ω). The design pose is the
// problem's initial value (β₀ = −0.0617…, Θ = 0), the drive β₀ − π … β₀ + π.
//
// The move from the design pose to the start turns the crank back half a turn; Θ
// then grows by about π (K2 swings, the crank turns under it), so the joint column
// reads the right turn at t = 0.5 (β = β₀: Θ = 0) only if the move was followed.
// Reference: E from the circles |E − F| = d, |E − B| = ss, Θ = atan2(F − E) − β.
#include <gtest/gtest.h>

#include <cmath>

#include "test_files.hpp"

namespace mechkin {
namespace andrews_squeezer_test {

using nlohmann::json;

// The problem's data (m), and its initial angles (rad).
constexpr double xa = -0.06934, ya = -0.00227, xb = -0.03635, yb = 0.03273;
constexpr double d = 0.028, e = 0.02, zf = 0.02, zt = 0.04, rr = 0.007, ss = 0.035, u = 0.04;
constexpr double beta0 = -0.0617138900142764496358948458001, gamma0 = 0.455279819163070380255912382449,
                 phi0 = 0.222668390165885884674473185609, delta0 = 0.487364979543842550225598953530,
                 omega0 = -0.222668390165885884674473185609, eps0 = 1.23054744454982119249735015568;

json Point(double x, double y) { return json::array({1000 * x, 1000 * y, 0.0}); }

json Revolute(const std::string& name, const std::string& b1, const std::string& b2, double x, double y) {
  return {{"name", name}, {"type", "revolute"}, {"body1", b1}, {"body2", b2}, {"origin", Point(x, y)}, {"axis", {0, 0, 1}}};
}

json AndrewsSqueezer() {
  const double fx = rr * std::cos(beta0), fy = rr * std::sin(beta0);
  const double ex = fx - d * std::cos(beta0), ey = fy - d * std::sin(beta0);
  const double gx = xa + zt * std::cos(delta0), gy = ya + zt * std::sin(delta0);
  const double hx = xa + u * std::sin(eps0), hy = ya - u * std::cos(eps0);
  json bodies = json::array();
  const std::pair<const char*, json> at[] = {{"K1", Point(fx, fy)}, {"K2", Point(ex, ey)}, {"K3", Point(ex, ey)},
                                             {"K4", Point(gx, gy)}, {"K5", Point(ex, ey)}, {"K6", Point(hx, hy)},
                                             {"K7", Point(ex, ey)}};
  for (const auto& [name, p] : at) bodies.push_back({{"name", name}, {"position", p}});
  json joints = {Revolute("O", "ground", "K1", 0, 0),  Revolute("F", "K1", "K2", fx, fy),
                 Revolute("B", "ground", "K3", xb, yb), Revolute("E3", "K2", "K3", ex, ey),
                 Revolute("A4", "ground", "K4", xa, ya), Revolute("G", "K4", "K5", gx, gy),
                 Revolute("E5", "K2", "K5", ex, ey),   Revolute("A6", "ground", "K6", xa, ya),
                 Revolute("H", "K6", "K7", hx, hy),    Revolute("E7", "K2", "K7", ex, ey)};
  return {{"mechkin", 1},
          {"name", "Andrews' squeezer"},
          {"units", {{"length", "mm"}, {"angle", "deg"}}},
          {"bodies", bodies},
          {"joints", joints},
          {"drivers", {{{"name", "crank"}, {"type", "rotation"}, {"joint", "O"}, {"function", "-180 + 360*t"}}}},
          {"analysis", {{"start", 0}, {"end", 1}, {"steps", 360}}},
          {"outputs", {{{"name", "Theta"}, {"type", "joint"}, {"joint", "F"}}}}};
}

// Θ(β) from the two circles, on the design's side of the line F–B.
double ThetaClosedForm(double beta) {
  const double fx = rr * std::cos(beta), fy = rr * std::sin(beta);
  const double dx = xb - fx, dy = yb - fy, dist = std::hypot(dx, dy);
  const double along = (d * d - ss * ss + dist * dist) / (2 * dist), across = std::sqrt(d * d - along * along);
  const double mx = fx + along * dx / dist, my = fy + along * dy / dist;
  // The design's E lies to the left of F→B (checked at β₀ by the test below).
  const double ex = mx - across * dy / dist, ey = my + across * dx / dist;
  return std::atan2(fy - ey, fx - ex) - beta;
}

TEST(AndrewsSqueezer, DesignPoseIsTheProblemsInitialValue) {
  // The K3, K5 and K7 loops close at the drawn E (Hairer's g₁…g₆ to round-off).
  const double fx = rr * std::cos(beta0), fy = rr * std::sin(beta0);
  const double ex = fx - d * std::cos(beta0), ey = fy - d * std::sin(beta0);
  EXPECT_NEAR(ex - ss * std::sin(gamma0) - xb, 0, 1e-15);
  EXPECT_NEAR(ey + ss * std::cos(gamma0) - yb, 0, 1e-15);
  EXPECT_NEAR(ex - e * std::sin(phi0 + delta0) - zt * std::cos(delta0) - xa, 0, 1e-15);
  EXPECT_NEAR(ey + e * std::cos(phi0 + delta0) - zt * std::sin(delta0) - ya, 0, 1e-15);
  EXPECT_NEAR(ex - zf * std::cos(omega0 + eps0) - u * std::sin(eps0) - xa, 0, 1e-15);
  EXPECT_NEAR(ey - zf * std::sin(omega0 + eps0) + u * std::cos(eps0) - ya, 0, 1e-15);
  EXPECT_NEAR(std::remainder(ThetaClosedForm(beta0), 2 * M_PI), 0, 1e-12);
}

TEST(AndrewsSqueezer, ThetaKeepsItsTurnAcrossTheMoveToTheStart) {
  const Model m = testing_files::FromJson(AndrewsSqueezer());
  TableOptions table;
  table.si = true;
  table.order = 1;
  const Motion run = RunMotion(m, AnalysisOptions{}, table);
  ASSERT_TRUE(run.complete) << run.stop.message;
  ASSERT_EQ(run.rows(), 361);
  const int theta = run.layout().Find("Theta"), t = run.layout().Find("t");
  // At β = β₀ (t = 0.5) the design pose again: Θ = 0, not −2π.
  EXPECT_NEAR(run.at(180, t), 0.5, 1e-15);
  EXPECT_NEAR(run.at(180, theta), 0, 1e-9);
  // Every row against the closed form unwrapped outward from Θ(β₀) = 0; the crank's
  // turn takes one turn off Θ (K2 only swings), so the ends differ by −2π.
  double worst = 0;
  for (int dir : {1, -1}) {
    double reference = 0;
    for (int r = 180; r >= 0 && r <= 360; r += dir) {
      const double beta = beta0 + M_PI * (2 * run.at(r, t) - 1);
      reference += std::remainder(ThetaClosedForm(beta) - reference, 2 * M_PI);
      worst = std::max(worst, std::abs(run.at(r, theta) - reference));
    }
  }
  std::printf("[measured] Andrews' squeezer: worst |Theta - closed form| over the turn %.2e rad\n", worst);
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(run.at(360, theta) - run.at(0, theta), -2 * M_PI, 1e-9);
}

}  // namespace
}  // namespace mechkin
