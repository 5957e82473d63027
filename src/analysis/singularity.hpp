// Singular positions between two accepted steps (the sign of det Φ_q flips) and
// the explanation of a failed position solve.
#pragma once

#include <string>
#include <vector>

#include "analysis/singular_points.hpp"
#include "kinematics/workspace.hpp"

namespace mechkin {

/// A singular position found between two steps (the sign of det Φ_q flips).
struct SingularPosition {
  double t = 0;                         // located by bisection to 1e-9 of the step
  std::vector<double> driver_values;    // SI, at t
  int joint_mobility = 0;               // 6n − rank of the joints' Jacobian there
  std::vector<std::string> involved;    // equations of the vanishing direction, by name
  int corank = 0;    // singular values of the driven Φ_q vanishing there (0: not classified)
  int branches = 0;  // branches crossing there (docs/singularities.md §3; 0: not classified)
  bool branches_exact = true;  // false: at least `branches`
};
/// The singular position a classification located (pose at c.t): driver values,
/// instantaneous mobility, the equations involved, corank and branches.
SingularPosition DescribeSingularPosition(const ConstraintSystem& sys, const std::vector<int>& rows,
                                          const SystemState& at, const SingularClassification& c);
/// "unique passage through a singular position at t = … s, driver `crank` = … deg: …".
std::string PassageNote(const Model& model, const SingularClassification& c);

/// Bisection in time for the root of det Φ_q between t_lo (sign_lo, state `base`
/// accepted at t_lo) and t_hi, each probe a tight Newton solve from the Taylor
/// prediction off `base`, so it follows the branch the run was on.
SingularPosition LocateSingularity(KinematicsWorkspace& ws, const SystemState& base, double t_lo, double t_hi,
                                   double sign_lo, double resolution, int predictor_order);
/// A limit of motion: the drivers ask for a pose the mechanism cannot reach (a
/// stroke end, the toggle of a driven output). Where the branch folds, the pose
/// moves like sqrt(t* − t), so t is a parabola in the coordinate moving most.
struct LimitOfMotion {
  double t = 0;                       // the fold (or the last solvable time when `fold` is false)
  std::vector<double> driver_values;  // SI, at t
  bool fold = false;                  // located as a fold of the branch (else: first unreachable time)
};
/// Bisection in time between t_lo (solvable from `base`) and t_hi (not) to
/// `resolution`, then the vertex of t = a·x² + b·x + c through three solutions
/// at t_lo, t_lo − δ/4 and t_lo − δ (δ = 1e-6 of t_hi − base.t).
LimitOfMotion LocateLimit(KinematicsWorkspace& ws, const SystemState& base, double t_lo, double t_hi,
                          double resolution, int predictor_order);
/// "limit of motion at t = … s: driver `piston` = … mm cannot go further …".
std::string LimitMessage(const Model& model, const LimitOfMotion& limit, int rows_done);
/// "singular position at t = … s, driver `crank` = … deg …" with advice.
std::string SingularityMessage(const Model& model, const SingularPosition& sp);
/// Why the position solve failed at t: the worst residuals and σ_min of the scaled Φ_q.
std::string SolveFailureMessage(KinematicsWorkspace& ws, const SystemState& s, double t, int rows_done,
                                const std::string& why);

}  // namespace mechkin
