// Singular positions between two accepted steps (the sign of det Φ_q flips) and
// the explanation of a failed position solve.
#pragma once

#include <string>
#include <vector>

#include "kinematics/workspace.hpp"

namespace mechkin {

/// A singular position found between two steps (the sign of det Φ_q flips).
struct SingularPosition {
  double t = 0;                         // located by bisection to 1e-9 of the step
  std::vector<double> driver_values;    // SI, at t
  int joint_mobility = 0;               // 6n − rank of the joints' Jacobian there
  std::vector<std::string> involved;    // equations of the vanishing direction, by name
};

/// Bisection in time for the root of det Φ_q between t_lo (sign_lo, state `base`
/// accepted at t_lo) and t_hi, each probe a tight Newton solve from the Taylor
/// prediction off `base`, so it follows the branch the run was on.
SingularPosition LocateSingularity(KinematicsWorkspace& ws, const SystemState& base, double t_lo, double t_hi,
                                   double sign_lo, double resolution, int predictor_order);
/// "singular position at t = … s, driver `crank` = … deg …" with advice.
std::string SingularityMessage(const Model& model, const SingularPosition& sp);
/// Why the position solve failed at t: the worst residuals and σ_min of the scaled Φ_q.
std::string SolveFailureMessage(KinematicsWorkspace& ws, const SystemState& s, double t, int rows_done,
                                const std::string& why);

}  // namespace mechkin
