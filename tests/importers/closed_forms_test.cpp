// The test mechanisms in each format (issue 26, docs/import.md "Examples"):
// an offset slider-crank, Theo Jansen's leg and a Clavel Delta robot, written by
// tools/imported_examples.py as URDF, SDFormat and MJCF (mechanisms/imported/) and as a
// FreeCAD Document.xml (tests/data/import/, zipped here into an .FCStd). Each is
// imported, checked (mobility, redundant equations, idle freedoms) and run, and its
// joint points are compared with closed forms written here, independent of mechkin's
// solver: the piston position, successive circle–circle (triangle) constructions,
// the intersection of three spheres.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>

#include "import_test_util.hpp"

namespace mechkin::import_test {
namespace closed_forms_test {

using P3 = std::array<double, 3>;

// The four files of mechanism `name`: the text formats and the .FCStd made from its Document.xml.
std::vector<std::string> Files(const std::string& name) {
  std::vector<std::string> files;
  for (const char* ext : {".urdf", ".sdf", ".xml"}) files.push_back(Source("mechanisms/imported/" + name + ext));
  files.push_back(Fcstd(name + ".FCStd", ReadText(Source("tests/data/import/" + name + "-Document.xml"))));
  return files;
}

bool IsMjcf(const std::string& file) { return file.size() > 4 && file.substr(file.size() - 4) == ".xml"; }

// Largest distance, over the run, between the path of the body point at `p0` in the
// written pose and the closed form `at(t)`.
double PathError(const Table& t, const std::string& body, const P3& p0, const std::function<P3(double)>& at) {
  const auto path = PointPath(t, body, p0.data());
  double worst = 0;
  for (size_t k = 0; k < path.size(); ++k) {
    const P3 c = at(t.at("t")[k]);
    worst = std::max(worst, std::hypot(path[k][0] - c[0], path[k][1] - c[1], path[k][2] - c[2]));
  }
  return worst;
}

// ---- the offset slider-crank: crank 40, rod 120, offset 10 mm, crank at 30 deg

const double kR = 0.04, kL = 0.12, kE = 0.01, kTheta0 = M_PI / 6;

P3 Piston(double theta) {
  return {kR * std::cos(theta) + std::sqrt(kL * kL - std::pow(kE - kR * std::sin(theta), 2)), kE, 0};
}

TEST(ClosedFormImport, OffsetSliderCrankPistonInEveryFormat) {
  // Its URDF (Files()[0]) is written by hand: the loop by a second parent.
  for (const std::string& f : Files("offset-slider-crank")) {
    const auto report = CheckReport(f);
    EXPECT_EQ(report["mobility"]["mobility"], 1) << f;
    // R R R P in 3-D: 3 of the planar loop's 6 equations repeat; MJCF closes the loop
    // with a spherical <connect>: 1.
    EXPECT_EQ(report["mobility"]["redundant"], IsMjcf(f) ? 1 : 3) << f;
    const Table t = RunTable(f + " --drive bearing=2*pi*t --span 0:1:36 --tol 1e-14");
    ASSERT_EQ(t.at("t").size(), 37u) << f;
    const double err = PathError(t, "slider", Piston(kTheta0), [](double s) { return Piston(kTheta0 + 2 * M_PI * s); });
    EXPECT_LT(err, 1e-12) << f;
    std::printf("[ measured ] slider-crank %s: piston error %.3g m\n", f.c_str(), err);
  }
}

// ---- Jansen's leg: Jansen's numbers (mm); O the crank's centre, Y the pivot at (-a, -l)

struct Jansen {
  P3 X, W, U, V, T, S;
};

// The point at `rp` from P and `rq` from Q, to the left of P→Q (side +1) or the right (−1).
P3 CirclePoint(const P3& P, double rp, const P3& Q, double rq, int side) {
  const double dx = Q[0] - P[0], dy = Q[1] - P[1], d = std::hypot(dx, dy);
  const double a = (rp * rp - rq * rq + d * d) / (2 * d), h = std::sqrt(rp * rp - a * a);
  const double ex = dx / d, ey = dy / d;
  return {P[0] + a * ex - side * h * ey, P[1] + a * ey + side * h * ex, 0};
}

Jansen JansenAt(double theta) {
  const double a = 38e-3, b = 41.5e-3, c = 39.3e-3, d = 40.1e-3, e = 55.8e-3, f = 39.4e-3, g = 36.7e-3, h = 65.7e-3,
               i = 49e-3, j = 50e-3, k = 61.9e-3, l = 7.8e-3, m = 15e-3;
  const P3 Y{-a, -l, 0};
  Jansen p;
  p.X = {m * std::cos(theta), m * std::sin(theta), 0};
  p.W = CirclePoint(Y, b, p.X, j, +1);    // b from Y, j from the crank pin
  p.U = CirclePoint(Y, d, p.W, e, +1);    // the triangle b d e
  p.V = CirclePoint(Y, c, p.X, k, -1);    // c from Y, k from the crank pin
  p.T = CirclePoint(p.U, f, p.V, g, -1);  // f from U, g from V
  p.S = CirclePoint(p.T, h, p.V, i, -1);  // the foot: the triangle g h i
  return p;
}

TEST(ClosedFormImport, JansenLegJointsAndFootInEveryFormat) {
  const Jansen p0 = JansenAt(1.0);
  // Each joint point on a body it moves with.
  const std::vector<std::tuple<const char*, const char*, P3 Jansen::*>> points = {
      {"X", "crank", &Jansen::X}, {"W", "triangle_bde", &Jansen::W}, {"U", "triangle_bde", &Jansen::U},
      {"V", "rod_c", &Jansen::V}, {"T", "rod_f", &Jansen::T},        {"S", "triangle_ghi", &Jansen::S}};
  for (const std::string& f : Files("jansen-leg")) {
    const auto report = CheckReport(f);
    EXPECT_EQ(report["mobility"]["mobility"], 1) << f;
    // Three independent planar loops of revolutes: 3 redundant equations each; MJCF's
    // spherical <connect> closures leave one each.
    EXPECT_EQ(report["mobility"]["redundant"], IsMjcf(f) ? 3 : 9) << f;
    EXPECT_EQ(report["mobility"]["idle"].size(), 0u) << f;
    const Table t = RunTable(f + " --drive O=2*pi*t --span 0:1:36 --tol 1e-14");
    ASSERT_EQ(t.at("t").size(), 37u) << f;
    double worst = 0;
    for (const auto& [name, body, member] : points) {
      const double err =
          PathError(t, body, p0.*member, [m = member](double s) { return JansenAt(1.0 + 2 * M_PI * s).*m; });
      EXPECT_LT(err, 1e-12) << f << ": " << name;
      worst = std::max(worst, err);
    }
    std::printf("[ measured ] Jansen %s: largest joint/foot error %.3g m\n", f.c_str(), worst);
  }
}

// ---- the Delta: base radius 0.2, arm 0.2, forearm 0.45, platform radius 0.05 m

const double kBase = 0.2, kArm = 0.2, kForearm = 0.45, kPlatform = 0.05;
const double kWritten[3] = {0.5, 0.3, 0.6};

// The platform centre for arm angles `th` (down from the base plane): the lower point
// at kForearm from the three elbows shifted by the platform's offsets (trilateration).
P3 DeltaPlatform(const double th[3]) {
  P3 C[3];
  for (int k = 0; k < 3; ++k) {
    const double phi = 2 * M_PI * k / 3, r = kBase + kArm * std::cos(th[k]) - kPlatform;
    C[k] = {r * std::cos(phi), r * std::sin(phi), -kArm * std::sin(th[k])};
  }
  auto sub = [](const P3& a, const P3& b) { return P3{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
  auto dot = [](const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  auto scale = [](const P3& a, double s) { return P3{a[0] * s, a[1] * s, a[2] * s}; };
  const P3 d10 = sub(C[1], C[0]), d20 = sub(C[2], C[0]);
  const double d = std::sqrt(dot(d10, d10));
  const P3 ex = scale(d10, 1 / d);
  const double i = dot(ex, d20);
  P3 ey = sub(d20, scale(ex, i));
  ey = scale(ey, 1 / std::sqrt(dot(ey, ey)));
  const P3 ez{ex[1] * ey[2] - ex[2] * ey[1], ex[2] * ey[0] - ex[0] * ey[2], ex[0] * ey[1] - ex[1] * ey[0]};
  const double j = dot(ey, d20), x = d / 2, y = (i * i + j * j) / (2 * j) - i * x / j;
  const double z = std::sqrt(kForearm * kForearm - x * x - y * y);
  P3 p{};
  for (int c = 0; c < 3; ++c) p[c] = C[0][c] + x * ex[c] + y * ey[c];
  const double s = ez[2] > 0 ? -z : z;  // the lower of the two points
  for (int c = 0; c < 3; ++c) p[c] += s * ez[c];
  return p;
}

// The arm angles at time s of the run's drives.
P3 DeltaAt(double s) {
  const double th[3] = {kWritten[0] + 0.2 * std::sin(2 * M_PI * s), kWritten[1] - 0.15 * std::sin(2 * M_PI * s),
                        kWritten[2] + 0.1 * std::sin(4 * M_PI * s)};
  return DeltaPlatform(th);
}

TEST(ClosedFormImport, DeltaPlatformInEveryFormat) {
  const P3 p0 = DeltaPlatform(kWritten);
  const std::string drives =
      " --drive 'shoulder_1=0.2*sin(2*pi*t)' --drive 'shoulder_2=-0.15*sin(2*pi*t)' --drive "
      "'shoulder_3=0.1*sin(4*pi*t)'";
  for (const std::string& f : Files("delta")) {
    const auto report = CheckReport(f);
    // Three arms; each forearm rod universal–spherical (no spin of its own), the
    // parallelograms keep the platform's orientation with six independent distances.
    EXPECT_EQ(report["mobility"]["mobility"], 3) << f << report.dump();
    EXPECT_EQ(report["mobility"]["redundant"], 0) << f;
    EXPECT_EQ(report["mobility"]["idle"].size(), 0u) << f;
    const Table t = RunTable(f + drives + " --span 0:1:24 --tol 1e-14");
    ASSERT_EQ(t.at("t").size(), 25u) << f;
    const double err = PathError(t, "platform", p0, DeltaAt);
    EXPECT_LT(err, 1e-12) << f;
    // The platform keeps its orientation (the parallelograms).
    double tilt = 0;
    for (size_t k = 0; k < t.at("t").size(); ++k) {
      const Frame a = PoseAt(t, "platform", 0), b = PoseAt(t, "platform", k);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) tilt = std::max(tilt, std::abs(a.R[r][c] - b.R[r][c]));
    }
    EXPECT_LT(tilt, 1e-12) << f;
    std::printf("[ measured ] Delta %s: platform error %.3g m, orientation change %.3g\n", f.c_str(), err, tilt);
  }
}

// The same Delta with spherical joints at both ends of every rod: each rod spins idle
// about its own axis — six idle freedoms in M = 9, a model mechkin calls under-driven.
TEST(ClosedFormImport, DeltaWithSphericalRodEndsHasSixIdleSpins) {
  const auto report = CheckReport(Source("tests/data/import/delta-ss.xml"));
  EXPECT_EQ(report["mobility"]["mobility"], 9) << report.dump();
  EXPECT_EQ(report["mobility"]["redundant"], 0);
  ASSERT_EQ(report["mobility"]["idle"].size(), 6u);
  for (const auto& idle : report["mobility"]["idle"])
    EXPECT_EQ(idle["bodies"].get<std::string>().rfind("rod_", 0), 0u) << idle.dump();
}

}  // namespace closed_forms_test
}  // namespace mechkin::import_test
