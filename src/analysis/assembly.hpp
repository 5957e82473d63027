// Getting a run to its first row: the design pose assembled with every driver
// at its design value, then continuation of the drivers to their values at
// `start` in small increments, so that the branch connected to the design pose
// is the one followed.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "kinematics/workspace.hpp"

namespace mechkin {

/// The value a driver has at the design pose: angles and slides of joints given in
/// global coordinates are 0 there (format v1); those of a joint on markers are its
/// coordinate in the pose drawn (0 where the markers coincide); a distance driver
/// gives the design distance itself.
double DesignDriverValue(const Model& model, const Driver& driver);
/// Points the multi-turn angle of rotation drivers at their target f(t).
void AimRotationDrivers(const ConstraintSystem& sys, SystemState* s);
/// The `count` worst-closing rows, each with how far it misses in file units.
std::string DescribeResiduals(const ConstraintSystem& sys, const SystemState& s, const std::vector<int>& rows,
                              const Eigen::VectorXd& scales, int count);

/// Min-norm assembly of the design pose (all rows, drivers at design values).
/// On failure returns false with the explanation in *message.
bool AssembleDesignPose(const ConstraintSystem& sys, const SolveOptions& solve, SystemState* s, int* iterations,
                        std::string* message);
/// Continuation from the design driver values to those at t = start.
/// Largest body move between two poses: |Δr| / length and the rotation angle (rad).
double PoseDistance(const SystemState& a, const SystemState& b, double length);
/// With `analysis.branch` hints: from the assembled design pose, first the joints
/// with the hinted joint coordinates held (min-norm Gauss–Newton), then the joints
/// and drivers again from there, so the pose lands on the hinted branch. True
/// without hints.
bool AssembleHintedBranch(const ConstraintSystem& sys, const SolveOptions& solve, SystemState* s, int* iterations,
                          std::string* message);
/// With `analysis.branch` flips: for each named joint the other closure of its loop
/// (the nearest assembly, from hinted ones at its coordinate ± 10°, ± 20° …, whose
/// coordinate of that joint differs). True without flips.
bool AssembleFlippedBranch(const ConstraintSystem& sys, const SolveOptions& solve, SystemState* s, int* iterations,
                           std::string* message);
/// Follows the drivers from the design pose to their values at t = start in small
/// increments; `on_pose` (if set) sees every pose reached on the way, so outputs that
/// keep their turn (joint angles) continue across the move.
bool ContinueToStart(KinematicsWorkspace& ws, double start, const SolveOptions& solve, SystemState* s,
                     int* iterations, std::string* message,
                     const std::function<void(const SystemState&)>& on_pose = {});

}  // namespace mechkin
