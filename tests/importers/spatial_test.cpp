// Spatial frames (issue 26): the bundled Bennett linkage (four revolutes on skew axes,
// mobility 1 by its special geometry) written as URDF — every link frame turned by
// its own roll-pitch-yaw, the loop closed by a second parent — and as MJCF — bodies
// nested with quaternions, the loop closed by two <connect>s on the last axis — runs
// the native file's motion. A wrong rpy order or quaternion convention moves the axes
// and breaks the Bennett condition, so mobility and motion both test the frames.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "import_test_util.hpp"
#include "math/rotation.hpp"

namespace mechkin::import_test {
namespace spatial_test {

struct NativeJoint {
  std::string name, body1, body2;
  Vec3 origin, axis;  // m
};

std::vector<NativeJoint> BennettJoints() {
  const auto j = nlohmann::json::parse(ReadText(Source("mechanisms/bennett-linkage.json")));
  std::vector<NativeJoint> out;
  for (const auto& k : j["joints"]) {
    NativeJoint n{k["name"], k["body1"], k["body2"], Vec3::Zero(), Vec3::Zero()};
    for (int i = 0; i < 3; ++i) n.origin[i] = k["origin"][i].get<double>() / 1000, n.axis[i] = k["axis"][i];
    n.axis.normalize();
    out.push_back(n);
  }
  return out;
}

// A rotation of its own for frame k (test-only: built from axis-angle, not from rpy).
Mat3 TurnOf(int k) {
  return Eigen::AngleAxisd(0.4 + 0.9 * k, Vec3(std::sin(1.0 + k), std::cos(2.0 * k), 0.5 + k).normalized())
      .toRotationMatrix();
}

// URDF's fixed-axis rpy of R = Rz(yaw) Ry(pitch) Rx(roll).
Vec3 Rpy(const Mat3& R) {
  return Vec3(std::atan2(R(2, 1), R(2, 2)), std::asin(std::max(-1.0, std::min(1.0, -R(2, 0)))),
              std::atan2(R(1, 0), R(0, 0)));
}

std::string Triple(const Vec3& v) {
  char buf[100];
  std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g", v.x(), v.y(), v.z());
  return buf;
}

struct Frame3 {
  Mat3 R;
  Vec3 p;
};

// Bennett as URDF: J1–J3 a chain from the base (each child link's frame its joint's
// frame, turned by TurnOf), J4 the rocker's second parent, written from the base.
std::string BennettUrdf() {
  const auto joints = BennettJoints();
  std::map<std::string, Frame3> world{{"ground", {Mat3::Identity(), Vec3::Zero()}}};
  std::string s = "<robot name=\"bennett\">\n  <link name=\"ground\"/>\n";
  for (int k = 0; k < 4; ++k) {
    NativeJoint j = joints[k];
    if (j.body2 == "ground") std::swap(j.body1, j.body2);  // URDF's root is never a child
    if (!world.count(j.body2)) s += "  <link name=\"" + j.body2 + "\"/>\n";
    const Frame3 frame{TurnOf(k), j.origin};
    const Frame3& parent = world.at(j.body1);
    const Mat3 R = parent.R.transpose() * frame.R;
    const Vec3 p = parent.R.transpose() * (frame.p - parent.p);
    s += "  <joint name=\"" + j.name + "\" type=\"continuous\"><parent link=\"" + j.body1 + "\"/><child link=\"" +
         j.body2 + "\"/>\n    <origin xyz=\"" + Triple(p) + "\" rpy=\"" + Triple(Rpy(R)) + "\"/><axis xyz=\"" +
         Triple(frame.R.transpose() * j.axis) + "\"/></joint>\n";
    if (!world.count(j.body2)) world[j.body2] = frame;
  }
  return s + "</robot>\n";
}

std::string Quat(const Mat3& R) {
  const Eigen::Quaterniond q(R);
  char buf[120];
  std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g %.17g", q.w(), q.x(), q.y(), q.z());
  return buf;
}

// Bennett as MJCF: link1 ⊂ link2 ⊂ link3 nested from the world, each body frame at its
// hinge turned by TurnOf (quat), the hinge axis in it; J4 two connects on its axis.
std::string BennettMjcf() {
  const auto joints = BennettJoints();
  std::string s = "<mujoco model=\"bennett\">\n  <compiler angle=\"radian\"/>\n  <worldbody>\n";
  Frame3 parent{Mat3::Identity(), Vec3::Zero()};
  for (int k = 0; k < 3; ++k) {
    const NativeJoint& j = joints[k];
    const Frame3 frame{TurnOf(k), j.origin};
    s += std::string(4 + 2 * k, ' ') + "<body name=\"" + j.body2 + "\" pos=\"" +
         Triple(parent.R.transpose() * (frame.p - parent.p)) + "\" quat=\"" + Quat(parent.R.transpose() * frame.R) +
         "\">\n" + std::string(6 + 2 * k, ' ') + "<joint name=\"" + j.name + "\" axis=\"" +
         Triple(frame.R.transpose() * j.axis) + "\"/>\n";
    parent = frame;
  }
  s += "        </body>\n      </body>\n    </body>\n  </worldbody>\n  <equality>\n";
  const NativeJoint& j4 = joints[3];
  for (double along : {0.0, 0.05}) {
    const Vec3 anchor = parent.R.transpose() * (j4.origin + along * j4.axis - parent.p);  // in link3
    s += "    <connect name=\"J4_" + std::to_string(static_cast<int>(along * 100)) + "\" body1=\"link3\" anchor=\"" +
         Triple(anchor) + "\"/>\n";
  }
  return s + "  </equality>\n</mujoco>\n";
}

void ExpectBennettMotion(const std::string& imported_path) {
  const auto joints = BennettJoints();
  const Table native = RunTable(Source("mechanisms/bennett-linkage.json"));
  const Table imported = RunTable(imported_path + " --drive J1=pi/2*t --span 0:1:100");
  ASSERT_EQ(imported.at("t").size(), 101u);
  const std::pair<const char*, int> points[] = {{"link1", 1}, {"link2", 1}, {"link2", 2}, {"link3", 2}, {"link3", 3}};
  for (const auto& [body, k] : points) {
    const double p0[3] = {joints[k].origin.x(), joints[k].origin.y(), joints[k].origin.z()};
    EXPECT_LT(PathDistance(PointPath(imported, body, p0), PointPath(native, body, p0)), 1e-10) << body << " J" << k + 1;
  }
  // And it moves: link3's point at J3 travels more than 1 cm.
  const double p3[3] = {joints[2].origin.x(), joints[2].origin.y(), joints[2].origin.z()};
  const auto path = PointPath(native, "link3", p3);
  EXPECT_GT(std::hypot(path.back()[0] - path[0][0], path.back()[1] - path[0][1], path.back()[2] - path[0][2]), 0.01);
}

TEST(SpatialImport, BennettAsUrdfWithTurnedFrames) {
  const std::string path = TempFile("bennett.urdf", BennettUrdf());
  const auto report = CheckReport(path);
  EXPECT_EQ(report["mobility"]["mobility"], 1) << report.dump();
  EXPECT_EQ(report["mobility"]["redundant"], 3);
  ExpectBennettMotion(path);
}

TEST(SpatialImport, BennettAsMjcfWithQuaternionsAndConnects) {
  const std::string path = TempFile("bennett.xml", BennettMjcf());
  const auto report = CheckReport(path);
  EXPECT_EQ(report["mobility"]["mobility"], 1) << report.dump();
  EXPECT_EQ(report["mobility"]["redundant"], 4);  // Bennett's 3 and the second connect's along-axis equation
  ExpectBennettMotion(path);
}

}  // namespace
}  // namespace mechkin::import_test
