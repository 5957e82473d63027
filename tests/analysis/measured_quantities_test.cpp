// The quantities engineers measure (issue "Say what engineers measure"), each
// against an independent reference: the Hooke joint's speed ratio in closed form,
// a four-bar's transmission angle by the law of cosines, a 6R arm's tool pose by
// Denavit–Hartenberg forward kinematics, a coordinate driver against the joint
// translation driver it generalizes.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace measured_quantities_test {

using nlohmann::json;

Motion RunDoc(const json& doc, int order, double tolerance = 1e-10) {
  TableOptions table;
  table.order = order;
  AnalysisOptions options;
  options.tolerance = tolerance;
  Motion m = RunMotion(testing_files::FromJson(doc), options, table);
  EXPECT_TRUE(m.complete) << m.stop.message;
  return m;
}

int Col(const Motion& m, const std::string& name) {
  const int c = m.layout().Find(name);
  EXPECT_GE(c, 0) << name;
  return c;
}

// Input yoke perpendicular to the shafts' plane at θ = 0, so the in-plane angle is
// θ + 90°: ω_out/ω_in = cos β / (1 − sin²β cos²(θ + 90°)).
TEST(MeasuredQuantities, HookeJointVelocityRatio) {
  json doc = testing_files::ReadJson("hooke-joint-30deg.json");
  doc["outputs"].push_back({{"name", "ratio"}, {"type", "velocity_ratio"}, {"output", "output_angle"}, {"input", "motor"}});
  const Motion m = RunDoc(doc, 2);
  const double beta = M_PI / 6;
  const int c = Col(m, "ratio"), ct = Col(m, "ratio_t");
  for (int r = 0; r < m.rows(); ++r) {
    const double th = 2 * M_PI * m.at(r, 0) + M_PI / 2;
    const double den = 1 - std::sin(beta) * std::sin(beta) * std::cos(th) * std::cos(th);
    EXPECT_NEAR(m.at(r, c), std::cos(beta) / den, 1e-12) << r;
    // d/dt of the ratio: −cos β sin²β sin 2θ θ̇ / den², θ̇ = 2π.
    const double rate = -std::cos(beta) * std::sin(beta) * std::sin(beta) * std::sin(2 * th) * 2 * M_PI / (den * den);
    EXPECT_NEAR(m.at(r, ct), rate, 1e-10) << r;
  }
}

TEST(MeasuredQuantities, FourBarTransmissionAngle) {
  const double a = 40, b = 120, c = 80, d = 100;
  json doc = testing_files::PlanarFourBar(a, b, c, d, 60, 72);
  // Vectors B→C on the coupler and D→C on the rocker, at the design pose.
  const json joints = doc["joints"];
  const double Bx = joints[1]["origin"][0], By = joints[1]["origin"][1];
  const double Cx = joints[2]["origin"][0], Cy = joints[2]["origin"][1];
  doc["outputs"].push_back({{"name", "mu"}, {"type", "angle"}, {"body1", "coupler"}, {"vector1", {Cx - Bx, Cy - By, 0}},
                            {"body2", "rocker"}, {"vector2", {Cx - d, Cy, 0}}});
  const Motion m = RunDoc(doc, 1);
  const int mu = Col(m, "mu");
  for (int r = 0; r < m.rows(); ++r) {
    const double th = (60 + 360 * m.at(r, 0)) * M_PI / 180;
    const double e2 = std::pow(a * std::cos(th) - d, 2) + std::pow(a * std::sin(th), 2);
    EXPECT_NEAR(m.at(r, mu) * M_PI / 180, std::acos((b * b + c * c - e2) / (2 * b * c)), 1e-10) << r;
  }
}

// ---- 6R arm against Denavit–Hartenberg forward kinematics --------------------------

struct DH { double d, a, alpha; };
const DH kArm[6] = {{0.4, 0.05, M_PI / 2}, {0, 0.35, 0}, {0, 0.05, M_PI / 2},
                    {0.3, 0, -M_PI / 2}, {0, 0, M_PI / 2}, {0.08, 0, 0}};
const double kTheta0[6] = {0.3, 0.9, -0.4, 0.5, 0.7, -0.2};   // rad, the design pose
const double kAmp[6] = {40, -30, 25, 60, -45, 90};            // deg, joint motions amp·sin(2πt)
const Vec3 kTool(0.02, -0.01, 0.05);                            // in link 6's DH frame

Eigen::Matrix4d Link(const DH& p, double th) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  const double ct = std::cos(th), st = std::sin(th), ca = std::cos(p.alpha), sa = std::sin(p.alpha);
  T << ct, -st * ca, st * sa, p.a * ct, st, ct * ca, -ct * sa, p.a * st, 0, sa, ca, p.d, 0, 0, 0, 1;
  return T;
}

// Frames 0..6 at joint angles q (frame i−1's z is joint i's axis).
std::vector<Eigen::Matrix4d> Frames(const double* q) {
  std::vector<Eigen::Matrix4d> T(7, Eigen::Matrix4d::Identity());
  for (int i = 0; i < 6; ++i) T[i + 1] = T[i] * Link(kArm[i], q[i]);
  return T;
}

void JointAngles(double t, double* q) {
  for (int i = 0; i < 6; ++i) q[i] = kTheta0[i] + kAmp[i] * M_PI / 180 * std::sin(2 * M_PI * t);
}

json ArmFile() {
  const auto T = Frames(kTheta0);
  json bodies = json::array(), joints = json::array(), drivers = json::array();
  auto vec = [](const Eigen::Vector3d& v) { return json{v.x(), v.y(), v.z()}; };
  for (int i = 0; i < 6; ++i) {
    const std::string link = "link" + std::to_string(i + 1), prev = i ? "link" + std::to_string(i) : "ground";
    bodies.push_back({{"name", link}, {"position", vec(T[i + 1].block<3, 1>(0, 3))}});
    joints.push_back({{"name", "q" + std::to_string(i + 1)}, {"type", "revolute"}, {"body1", prev}, {"body2", link},
                      {"origin", vec(T[i].block<3, 1>(0, 3))}, {"axis", vec(T[i].block<3, 1>(0, 2))}});
    char f[64];
    std::snprintf(f, sizeof f, "%.17g*sin(2*pi*t)", kAmp[i] * M_PI / 180);  // the file is in rad
    drivers.push_back({{"name", "m" + std::to_string(i + 1)}, {"type", "rotation"}, {"joint", "q" + std::to_string(i + 1)},
                       {"function", f}});
  }
  const Eigen::Vector3d tool = (T[6] * kTool.homogeneous()).head<3>();
  return {{"mechkin", 1}, {"units", {{"length", "m"}, {"angle", "rad"}}}, {"bodies", bodies}, {"joints", joints},
          {"drivers", drivers}, {"analysis", {{"start", 0}, {"end", 1}, {"steps", 40}}},
          {"outputs", {{{"name", "tool"}, {"type", "point"}, {"body", "link6"}, {"point", vec(tool)}},
                       {{"name", "tool_in_link1"}, {"type", "point"}, {"body", "link6"}, {"point", vec(tool)}, {"frame", "link1"}},
                       {{"name", "ypr"}, {"type", "orientation"}, {"body", "link6"}, {"sequence", "ZYX"}},
                       {{"name", "q6"}, {"type", "orientation"}, {"body", "link6"}, {"sequence", "euler-parameters"}}}}};
}

// The link-6 body frame is global at the design pose: its orientation is
// R6(q) R6(q0)ᵀ; ZYX angles of R = Rz(α) Ry(β) Rx(γ) read from the closed forms.
Vec3 YawPitchRoll(const Eigen::Matrix3d& R) {
  return {std::atan2(R(1, 0), R(0, 0)), -std::asin(R(2, 0)), std::atan2(R(2, 1), R(2, 2))};
}

TEST(MeasuredQuantities, SixRArmMatchesDenavitHartenberg) {
  // --tol 1e-12: the default 1e-10 leaves 1.4e-12 rad in the angles, the acceptance asks 1e-12.
  const Motion m = RunDoc(ArmFile(), 1, 1e-12);
  const Eigen::Matrix3d R0 = Frames(kTheta0)[6].block<3, 3>(0, 0);
  const int tool = Col(m, "tool.x"), in1 = Col(m, "tool_in_link1.x"), ypr = Col(m, "ypr.angle1"), e0 = Col(m, "q6.e0");
  const int lock = Col(m, "ypr.gimbal_lock");
  const Eigen::Vector3d tool_local = kTool;
  for (int r = 0; r < m.rows(); ++r) {
    const double t = m.at(r, 0);
    double q[6];
    JointAngles(t, q);
    const auto T = Frames(q);
    const Eigen::Vector3d p = (T[6] * tool_local.homogeneous()).head<3>();
    // Body link1: origin o1(q), axes global at the design, so its rotation is R1(q) R1(q0)ᵀ.
    const Eigen::Matrix3d A1 = T[1].block<3, 3>(0, 0) * Frames(kTheta0)[1].block<3, 3>(0, 0).transpose();
    const Eigen::Vector3d p1 = A1.transpose() * (p - T[1].block<3, 1>(0, 3));
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(m.at(r, tool + 2 * a), p[a], 1e-12) << r;   // x, x_t, y, ...
      EXPECT_NEAR(m.at(r, in1 + 2 * a), p1[a], 1e-12) << r;
    }
    const Eigen::Matrix3d R = T[6].block<3, 3>(0, 0) * R0.transpose();
    const Vec3 ang = YawPitchRoll(R);
    EXPECT_EQ(m.at(r, lock), 0);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(std::remainder(m.at(r, ypr + 2 * a) - ang[a], 2 * M_PI), 0, 1e-12) << r;
    // The angles recompose the matrix (the convention, independently of the formulas).
    const Eigen::Matrix3d back = (Eigen::AngleAxisd(m.at(r, ypr), Vec3::UnitZ()) *
                                  Eigen::AngleAxisd(m.at(r, ypr + 2), Vec3::UnitY()) *
                                  Eigen::AngleAxisd(m.at(r, ypr + 4), Vec3::UnitX())).toRotationMatrix();
    EXPECT_LT((back - R).norm(), 1e-12) << r;
    const Eigen::Quaterniond qr(R);
    const double sign = qr.w() * m.at(r, e0) >= 0 ? 1 : -1;
    EXPECT_NEAR(m.at(r, e0), sign * qr.w(), 1e-12);
    EXPECT_NEAR(m.at(r, e0 + 2), sign * qr.x(), 1e-12);
    // Derivatives: central differences of the closed form in t (h = 1e-5: error ~1e-9).
    const double h = 1e-5;
    double qp[6], qm[6];
    JointAngles(t + h, qp);
    JointAngles(t - h, qm);
    const Vec3 ap = YawPitchRoll(Frames(qp)[6].block<3, 3>(0, 0) * R0.transpose());
    const Vec3 am = YawPitchRoll(Frames(qm)[6].block<3, 3>(0, 0) * R0.transpose());
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(m.at(r, ypr + 2 * a + 1), std::remainder(ap[a] - am[a], 2 * M_PI) / (2 * h), 1e-7) << r;
  }
}

// A body point's coordinate along a ground axis, 0 at the design: the piston-driven
// slider-crank driven through the slider's point instead of its prismatic joint.
TEST(MeasuredQuantities, CoordinateDriverEqualsTheJointTranslationDriver) {
  const json joint_driven = testing_files::ReadTestData("piston-driven-slider-crank.json");
  json point_driven = joint_driven;
  point_driven["drivers"][0] = {{"name", "piston"}, {"type", "coordinate"}, {"body", "slider"},
                                {"point", joint_driven["joints"][3]["origin"]}, {"axis", {1, 0, 0}},
                                {"function", joint_driven["drivers"][0]["function"]}};
  const Motion a = RunDoc(joint_driven, 2), b = RunDoc(point_driven, 2);
  ASSERT_EQ(a.rows(), b.rows());
  const int c = Col(a, "crank_angle");
  for (int r = 0; r < a.rows(); r += 7)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a.at(r, c + k), b.at(r, c + k), 1e-9 * (1 + std::abs(a.at(r, c + k)))) << r;
}

}  // namespace
}  // namespace mechkin

namespace mechkin {
namespace measured_quantities_test {

// Planar joint output: the block's slides along the table frame's f, g and its
// turn about the normal. The table frame at (100, 100, 0) with h = z; the block's
// origin is the joint point, so the slides are the origin's moves along f and g.
TEST(MeasuredQuantities, PlanarJointSlidesAndAngle) {
  json doc = testing_files::ReadJson("planar-xy-table.json");
  doc["outputs"] = {{{"name", "table"}, {"type", "joint"}, {"joint", "table"}}};
  const Motion m = RunDoc(doc, 1);
  const Model model = testing_files::FromJson(doc);
  const Vec3 f = model.joints[0].frame1.f, g = model.joints[0].frame1.g;
  const int s1 = Col(m, "table.slide1"), s2 = Col(m, "table.slide2"), an = Col(m, "table.angle");
  const int x = Col(m, "block.x"), y = Col(m, "block.y");
  for (int r = 0; r < m.rows(); ++r) {
    const Vec3 d(m.at(r, x) - 100, m.at(r, y) - 100, 0);
    EXPECT_NEAR(m.at(r, s1), f.dot(d), 1e-9) << r;
    EXPECT_NEAR(m.at(r, s2), g.dot(d), 1e-9) << r;
    EXPECT_NEAR(m.at(r, an), 45 * m.at(r, 0), 1e-9) << r;  // the rotation driver's value
    EXPECT_NEAR(m.at(r, an + 1), 45, 1e-9) << r;
  }
}

// Universal joint of the Hooke coupling: the cross's turn about axis 1 in the
// input shaft against the closed form (axis 2 ⊥ axis 1 and ⊥ the output shaft).
TEST(MeasuredQuantities, UniversalJointAngles) {
  json doc = testing_files::ReadJson("hooke-joint-30deg.json");
  doc["outputs"].push_back({{"name", "cross"}, {"type", "joint"}, {"joint", "cross"}});
  const Motion m = RunDoc(doc, 1);
  const int a1 = Col(m, "cross.angle1"), a2 = Col(m, "cross.angle2"), out = Col(m, "output_angle");
  const Vec3 shaft2(std::cos(M_PI / 6), std::sin(M_PI / 6), 0), f1_0(-0.5, std::sqrt(3.0) / 2, 0);
  for (int r = 0; r < m.rows(); ++r) {
    const double th = 2 * M_PI * m.at(r, 0);
    const Mat3 Rin = Eigen::AngleAxisd(th, Vec3::UnitX()).toRotationMatrix();
    const Vec3 axis1 = Rin * Vec3::UnitZ(), f1 = Rin * f1_0, g1 = axis1.cross(f1);
    const Vec3 axis2 = -shaft2.cross(axis1).normalized();
    EXPECT_NEAR(m.at(r, a1) * M_PI / 180, std::atan2(g1.dot(axis2), f1.dot(axis2)), 1e-9) << r;
    // Angle 2: body2's f (axis 1 at the design, z) turned with the output shaft, about axis 2 from axis 1.
    const Mat3 Rout = Eigen::AngleAxisd(m.at(r, out) * M_PI / 180, shaft2).toRotationMatrix();
    const Vec3 f2 = Rout * Vec3::UnitZ();
    EXPECT_NEAR(m.at(r, a2) * M_PI / 180, std::atan2(axis2.dot(axis1.cross(f2)), axis1.dot(f2)), 1e-9) << r;
  }
}

// A spherical joint's output is the orientation of its body2 frame in its body1
// frame: for bodies and frames drawn along the global axes, the orientation output.
TEST(MeasuredQuantities, SphericalJointAsASequence) {
  json doc = testing_files::ReadJson("double-wishbone-suspension.json");
  doc["outputs"].push_back({{"name", "ball"}, {"type", "joint"}, {"joint", "upper_ball"}, {"sequence", "XYZ"}});
  doc["outputs"].push_back({{"name", "rel"}, {"type", "orientation"}, {"body", "upright"}, {"relative_to", "upper_arm"},
                            {"sequence", "XYZ"}});
  const Motion m = RunDoc(doc, 2);
  const int b = Col(m, "ball.angle1"), o = Col(m, "rel.angle1");
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < 9; ++c) EXPECT_NEAR(m.at(r, b + c), m.at(r, o + c), 1e-12) << r << " " << c;
  EXPECT_GT(std::abs(m.at(m.rows() / 4, b)), 1.0);  // the arm turns against the upright
}

}  // namespace
}  // namespace mechkin
