// Singular positions found and classified independently of the sign of det Φ_q
// (docs/singularities.md): the smallest singular values of the driven, dimensionless
// Φ_q are followed along the run's branch, their common zero is located between two
// times, and the position is classified from the null spaces and the second-order
// terms — a fold (limit of motion), a bifurcation (branches cross) or a unique
// passage (the prescribed motion stays determined and the run goes on).
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "kinematics/workspace.hpp"

namespace mechkin {

enum class SingularKind {
  None,           // no zero of the singular values between the times (a near miss)
  Fold,           // Φ_t leaves the range of Φ_q: the drivers cannot go on (limit of motion)
  Bifurcation,    // two or more branches cross: the prescribed motion does not say which
  UniquePassage,  // the branch is the only one crossing: the motion stays determined
  Undetermined,   // could not be located or classified (the caller keeps its old rules)
};

struct SingularClassification {
  SingularKind kind = SingularKind::Undetermined;
  double t = 0;          // the zero of the vanishing singular values
  int corank = 0;        // how many vanish there
  int branches = 0;      // real tangent directions crossing t (docs/singularities.md §3)
  bool branches_exact = true;  // false: a multiple root or a lost path, `branches` is a lower bound
  std::vector<double> driver_values;  // SI, at t
};

/// At a pose where the position solve stops going on (the last one solvable, within
/// the bisection's resolution of the end): true when the scaled Φ_q of `rows` has
/// singular values below 1e-4 of the largest and ν = −Φ_t (scaled) has a part above
/// 1e-2 ‖ν‖ on their left singular vectors — ν leaves the range, the drivers cannot go
/// on: a fold (docs/singularities.md §3). Rank-revealing, so `rows` may be every
/// equation of a redundant mechanism: its redundancy is a left null vector that ν never
/// leaves (the equations agree along the motion), the fold one more that it does. (The
/// solved rows alone do not tell: at the fold of Bricard's linkage they have a curve of
/// their own crossing the mechanism's, and ν stays in their range.) Dense, ≤ 200 bodies.
bool IsFold(const ConstraintSystem& sys, const std::vector<int>& rows, const SystemState& s);

/// Owns a workspace of its own so that the run's factorization and state are left
/// untouched (a classification never changes the table). Dense: for models up to
/// 200 bodies; larger ones get Undetermined.
class SingularityClassifier {
 public:
  SingularityClassifier(const ConstraintSystem& sys, const std::vector<int>& active);
  /// Looks for a zero of the smallest singular values between ta (`base`, solved on
  /// the run's branch) and tb; where σ_1 still falls at an end the search walks on,
  /// up to 5 (tb − ta) beyond it.
  SingularClassification Classify(const SystemState& base, double tb, double step);
  /// The pose at the located t (after Classify returned Fold, Bifurcation or UniquePassage).
  const SystemState& pose() const { return pose_; }
  const std::vector<int>& active() const { return ws_.active(); }
  /// After Classify: the latest well-determined pose it solved on the run's branch in
  /// (t_star, t_end] (tight, with derivatives to order 3), or nullptr when it solved none.
  const SystemState* SolvedPast(double t_star, double t_end) const;

 private:
  struct Sample {
    SystemState s;
    Eigen::VectorXd sigma;  // singular values of the scaled Φ_q, ascending
  };
  /// Its pose and derivatives are meaningful: σ_min ≥ 1e-4 σ_max (closer to the
  /// singular position the velocities are amplified by 1/σ_min and the pose is fixed
  /// only to √(residual) along the null space).
  static bool WellDetermined(const Sample& s) { return s.sigma[0] >= 1e-4 * s.sigma[s.sigma.size() - 1]; }
  bool Probe(double t, const Sample** out);
  double Locate(double ta, double tb, double step, int* corank);
  double FitZero(double center, double delta, int corank, bool* ok);
  int CountVanishing(double center, double delta, bool* ok);
  void PoseAt(double t, double delta, int corank);
  SingularKind ClassifyAt(double t, double delta, int corank, int* branches, bool* exact);
  Eigen::VectorXd SingularValues(const SystemState& s) const;

  KinematicsWorkspace ws_;
  std::deque<Sample> samples_;  // a deque: pointers to samples stay valid as it grows
  SystemState pose_;
};

}  // namespace mechkin
