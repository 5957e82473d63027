// The double-wishbone suspension driven by wheel travel (a coordinate driver):
// camber and toe against an independent solution — the closure written in other
// unknowns (the two arms' hinge angles and the upright's turn about its kingpin
// axis), solved by a separate Newton iteration in this test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace suspension_test {

using V = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

struct Corner {
  V lower_pivot{0, 250, 150}, lower_axis{1, 0, 0}, upper_pivot{0, 350, 420}, upper_axis = V(1, 0, 0.08).normalized();
  V L{0, 650, 130}, U{10, 620, 450}, rack{-130, 300, 280}, S{-120, 640, 280}, W{0, 700, 300};
  V spin = V(0, std::cos(M_PI / 180), -std::sin(M_PI / 180));
};

M3 Rot(const V& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

// The upright's rotation for arm angles (φl, φu) and a turn ψ about the new kingpin
// axis: the smallest rotation taking U − L to U' − L', then ψ about U' − L'.
M3 Upright(const Corner& c, const V& x, V* Lp) {
  *Lp = c.lower_pivot + Rot(c.lower_axis, x[0]) * (c.L - c.lower_pivot);
  const V Up = c.upper_pivot + Rot(c.upper_axis, x[1]) * (c.U - c.upper_pivot);
  const V k0 = (c.U - c.L).normalized(), k1 = (Up - *Lp).normalized();
  const M3 R0 = Eigen::Quaterniond::FromTwoVectors(k0, k1).toRotationMatrix();
  return Rot(k1, x[2]) * R0;
}

V Residual(const Corner& c, const V& x, double travel) {
  V Lp;
  const M3 R = Upright(c, x, &Lp);
  const V Up = c.upper_pivot + Rot(c.upper_axis, x[1]) * (c.U - c.upper_pivot);
  const V Wp = Lp + R * (c.W - c.L), Sp = Lp + R * (c.S - c.L);
  return V((Up - Lp).norm() - (c.U - c.L).norm(), Wp.z() - c.W.z() - travel,
           (Sp - c.rack).norm() - (c.S - c.rack).norm());
}

// Newton with a central-difference Jacobian (it only steers; the residual decides).
V Solve(const Corner& c, V x, double travel) {
  for (int it = 0; it < 50; ++it) {
    const V r = Residual(c, x, travel);
    if (r.norm() < 1e-13) break;
    M3 J;
    for (int k = 0; k < 3; ++k) {
      V e = V::Zero();
      e[k] = 1e-7;
      J.col(k) = (Residual(c, x + e, travel) - Residual(c, x - e, travel)) / 2e-7;
    }
    x -= J.partialPivLu().solve(r);
  }
  EXPECT_LT(Residual(c, x, travel).norm(), 1e-11);
  return x;
}

TEST(Suspension, CamberAndToeOverTheTravelMatchAnIndependentSolution) {
  const nlohmann::json doc = testing_files::ReadJson("double-wishbone-suspension.json");
  TableOptions table;
  table.order = 1;
  const Motion m = RunMotion(testing_files::FromJson(doc), AnalysisOptions{}, table);
  ASSERT_TRUE(m.complete) << m.stop.message;
  const int camber = m.layout().Find("camber"), toe = m.layout().Find("toe"), bound = m.layout().Find("error_bound");
  const Corner c;
  V x = V::Zero();
  double worst = 0;
  for (int r = 0; r < m.rows(); ++r) {
    const double t = m.at(r, 0);
    x = Solve(c, x, 80 * std::sin(2 * M_PI * t));
    V Lp;
    const V s = Upright(c, x, &Lp) * c.spin;
    const double cam = std::atan2(s.z(), s.y()), to = std::atan2(-s.x(), s.y());
    worst = std::max({worst, std::abs(m.at(r, camber) * M_PI / 180 - cam), std::abs(m.at(r, toe) * M_PI / 180 - to)});
    EXPECT_NEAR(m.at(r, camber) * M_PI / 180, cam, 1e-9) << r;
    EXPECT_NEAR(m.at(r, toe) * M_PI / 180, to, 1e-9) << r;
    EXPECT_LT(m.at(r, bound), 1e-9) << r;  // well conditioned: no warning (run warns above 10 × tol)
  }
  EXPECT_LT(worst, 1e-9);
  char worst_text[32];
  std::snprintf(worst_text, sizeof worst_text, "%.3g", worst);
  RecordProperty("worst_rad", worst_text);
  // The geometry moves the wheel: camber gain and bump steer are not zero.
  double cmin = 1e9, cmax = -1e9;
  for (int r = 0; r < m.rows(); ++r) cmin = std::min(cmin, m.at(r, camber)), cmax = std::max(cmax, m.at(r, camber));
  EXPECT_GT(cmax - cmin, 1.0);
}

}  // namespace
}  // namespace mechkin
