// A Bennett linkage built from its Denavit–Hartenberg description, shared by the
// tests that run it (redundancy that follows the motion, error bounds).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace mechkin::testing_files {

// Bennett linkage with link lengths a (twist alpha) and b = a sin(beta)/sin(alpha)
// (twist beta), built by walking the loop in Denavit–Hartenberg steps from the
// input angle theta1 at the design pose; θ2 from the closure
//   tan(θ1/2)·tan(θ2/2) = sin((β+α)/2) / sin((β−α)/2),   θ3 = 2π − θ1, θ4 = 2π − θ2.
inline double BennettTheta2(double theta1, double alpha, double beta) {
  const double k = std::sin((beta + alpha) / 2) / std::sin((beta - alpha) / 2);
  return 2 * std::atan2(k * std::cos(theta1 / 2), std::sin(theta1 / 2));
}

inline nlohmann::json Bennett(double alpha, double beta, double theta1, int steps) {
  const double a = 100, b = a * std::sin(beta) / std::sin(alpha), theta2 = BennettTheta2(theta1, alpha, beta);
  const double th[4] = {theta1, theta2, 2 * M_PI - theta1, 2 * M_PI - theta2}, len[4] = {a, b, a, b},
               tw[4] = {alpha, beta, alpha, beta};
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> origin, axis;
  for (int k = 0; k < 4; ++k) {
    origin.push_back(p);
    axis.push_back(R.col(2));
    R = R * Eigen::AngleAxisd(th[k], Eigen::Vector3d::UnitZ()).toRotationMatrix();
    p += R * Eigen::Vector3d(len[k], 0, 0);
    R = R * Eigen::AngleAxisd(tw[k], Eigen::Vector3d::UnitX()).toRotationMatrix();
  }
  if (p.norm() > 1e-9) throw std::logic_error("the Bennett loop does not close");
  auto arr = [](const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  const char* names[3] = {"link1", "link2", "link3"};
  const char* pair[4][2] = {{"ground", "link1"}, {"link1", "link2"}, {"link2", "link3"}, {"link3", "ground"}};
  nlohmann::json bodies = nlohmann::json::array(), joints = nlohmann::json::array();
  for (int k = 0; k < 3; ++k) bodies.push_back({{"name", names[k]}, {"position", arr((origin[k] + origin[k + 1]) / 2)}});
  for (int k = 0; k < 4; ++k)
    joints.push_back({{"name", "J" + std::to_string(k + 1)}, {"type", "revolute"}, {"body1", pair[k][0]},
                      {"body2", pair[k][1]}, {"origin", arr(origin[k])}, {"axis", arr(axis[k])}});
  return {{"mechkin", 1}, {"units", {{"length", "mm"}, {"angle", "deg"}}}, {"bodies", bodies}, {"joints", joints},
          {"drivers", {{{"name", "motor"}, {"type", "rotation"}, {"joint", "J1"}, {"function", "360*t"}}}},
          {"outputs", {{{"name", "theta1"}, {"type", "joint"}, {"joint", "J1"}}, {{"name", "theta2"}, {"type", "joint"}, {"joint", "J2"}}}},
          {"analysis", {{"start", 0}, {"end", 1}, {"steps", steps}}}};
}

}  // namespace mechkin::testing_files
