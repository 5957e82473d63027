// Joint limits along the run (docs/format.md "limits"): a revolute or screw joint's
// angle, a prismatic or cylindrical joint's slide, kept within [lo, hi] (SI, from the
// design pose or where the joint's markers coincide). The watch follows each limited
// coordinate over whole turns; when a step crosses a bound, the crossing is located
// by Newton's method in time on q(t) − bound, with a tight position solve and the
// first-order solve for q̇ at each trial time (to 1e-12 of the bound, far inside the
// 1e-9 a limit of motion is located to, constraints.md §12).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "kinematics/workspace.hpp"

namespace mechkin {

struct JointLimitHit {
  double t = 0;                      // the located crossing (s)
  int joint = -1;
  bool upper = true;                 // the bound reached: hi (else lo)
  double bound = 0;                  // SI
  std::vector<double> driver_values; // SI, at t
};

/// The joint's coordinate at s: its angle continued from `ref` (rotation), or its slide.
double LimitedCoordinate(const Joint& j, const SystemState& s, double ref);
/// Its first time derivative at s (velocities solved).
double LimitedCoordinateRate(const Joint& j, const SystemState& s);
/// The joint's limits act on its rotation (revolute, screw) rather than its slide.
bool LimitOnRotation(const JointDescriptor* t);

class JointLimitWatch {
 public:
  explicit JointLimitWatch(const Model& model);
  bool empty() const { return joints_.empty(); }
  /// The first accepted pose: the coordinates' references; a joint outside its limits there.
  std::optional<int> Start(const SystemState& s);
  /// The first bound crossed between the accepted pose `prev` and the solved `s`,
  /// located in (prev.t, s.t]; nullopt when none is crossed.
  std::optional<JointLimitHit> Check(KinematicsWorkspace& ws, const SystemState& prev, const SystemState& s,
                                     int predictor_order);
  /// `s` accepted: the coordinates' references follow it.
  void Accept(const SystemState& s);
  double value(int k) const { return values_[k]; }

 private:
  JointLimitHit Locate(KinematicsWorkspace& ws, const SystemState& prev, double t_hi, double q_hi, int joint,
                       double bound, double ref, int predictor_order) const;
  const Model& model_;
  std::vector<int> joints_;        // the limited joints
  std::vector<double> values_;     // per limited joint: its coordinate at the last accepted pose
};

/// "joint `rocker` reaches its upper limit 40 deg at t = … s …".
std::string JointLimitMessage(const Model& model, const JointLimitHit& hit, int rows_done, bool stops);

}  // namespace mechkin
