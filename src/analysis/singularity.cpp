#include "analysis/singularity.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/assembly.hpp"

namespace mechkin {
namespace {

constexpr int kDenseLimit = 1200;  // columns above which the dense SVDs are skipped
// A probe farther than this from the pose it continues (|Δr| / L or rad) left the branch.
constexpr double kBranchJump = 0.1;

Eigen::MatrixXd SelectRowsOf(const Eigen::MatrixXd& J, const std::vector<int>& rows) {
  Eigen::MatrixXd out(rows.size(), J.cols());
  for (size_t k = 0; k < rows.size(); ++k) out.row(k) = J.row(rows[k]);
  return out;
}

double SmallestSingularValue(const ConstraintSystem& sys, const SystemState& s, const std::vector<int>& rows) {
  if (6 * sys.num_bodies() > kDenseLimit) return std::nan("");
  Eigen::BDCSVD<Eigen::MatrixXd> svd(SelectRowsOf(ScaledJacobian(sys, s), rows));
  return svd.singularValues().size() ? svd.singularValues().tail(1)[0] : 0.0;
}

// 6n − rank of the joints' scaled Jacobian (relative threshold 1e-6).
int JointMobility(const ConstraintSystem& sys, const SystemState& s) {
  const ConstraintSystem joints(sys.model(), false);
  SystemState js(joints);
  js.bodies = s.bodies;
  Eigen::BDCSVD<Eigen::MatrixXd> sj(ScaledJacobian(joints, js));
  int rank = 0;
  for (int k = 0; k < sj.singularValues().size(); ++k) rank += sj.singularValues()[k] > 1e-6 * sj.singularValues()[0];
  return 6 * sys.num_bodies() - rank;
}

// The sources (joints, drivers) with the largest weights in the left singular
// vector of σ_min: the equations that become dependent.
std::vector<std::string> InvolvedEquations(const ConstraintSystem& sys, const SystemState& s, const std::vector<int>& rows) {
  const Eigen::MatrixXd Ja = SelectRowsOf(ScaledJacobian(sys, s), rows);
  Eigen::BDCSVD<Eigen::MatrixXd> svd(Ja, Eigen::ComputeFullU);
  const Eigen::VectorXd u = svd.matrixU().col(Ja.rows() - 1);
  std::vector<std::pair<double, int>> w;
  for (int k = 0; k < u.size(); ++k) w.emplace_back(std::abs(u[k]), rows[k]);
  std::sort(w.rbegin(), w.rend());
  std::vector<std::string> names;
  for (const auto& [mag, row] : w) {
    if (mag < 0.1 * w[0].first || names.size() >= 4) break;
    const std::string src = sys.SourceName(row);
    if (std::find(names.begin(), names.end(), src) == names.end()) names.push_back(src);
  }
  return names;
}

// A solve from the Taylor prediction off `base` at time t to `tolerance`. A probe
// that does not close, or lands far from the branch (near a fold the prediction
// overshoots and Newton may close on another assembly: an axis of a cylindrical joint
// turned over), is no pose of the run's branch at t.
bool SolveOnBranch(KinematicsWorkspace& ws, const SystemState& base, double t, int predictor_order,
                   double tolerance, SystemState* probe) {
  const ConstraintSystem& sys = ws.system();
  SolveOptions tight;
  tight.tolerance = tolerance;
  tight.max_iterations = 100;
  *probe = base;
  PredictPose(t - base.t, predictor_order, probe);
  EvalDriverFunctions(sys.model(), t, probe);
  AimRotationDrivers(sys, probe);
  return ws.newton().Solve(tight, probe).success &&
         PoseDistance(base, *probe, sys.model().characteristic_length) <= kBranchJump;
}

}  // namespace

SingularPosition LocateSingularity(KinematicsWorkspace& ws, const SystemState& base, double t_lo, double t_hi,
                                   double sign_lo, double resolution, int predictor_order) {
  const ConstraintSystem& sys = ws.system();
  NewtonSolver& newton = ws.newton();
  SystemState s_lo = base, probe = base;
  while (t_hi - t_lo > resolution) {
    const double mid = 0.5 * (t_lo + t_hi);
    // A probe off the run's branch counts as past the position.
    const bool on_branch = SolveOnBranch(ws, base, mid, predictor_order, 1e-14, &probe);
    if (on_branch && newton.Factorize(probe) && newton.JacobianSign() == sign_lo) {
      t_lo = mid;
      s_lo = probe;
    } else {
      t_hi = mid;
    }
  }
  SingularPosition sp;
  sp.t = 0.5 * (t_lo + t_hi);
  EvalDriverFunctions(sys.model(), sp.t, &s_lo);
  for (const Jet& j : s_lo.driver_values) sp.driver_values.push_back(j.c[0]);
  if (6 * sys.num_bodies() <= kDenseLimit) {
    sp.joint_mobility = JointMobility(sys, s_lo);
    sp.involved = InvolvedEquations(sys, s_lo, newton.rows());
  }
  return sp;
}

namespace {

// Every equation the workspace's solves reach, the set-aside ones included, closes at
// s to `tolerance` (scaled).
bool ClosesAllRows(const KinematicsWorkspace& ws, const SystemState& s, double tolerance) {
  const ConstraintSystem& sys = ws.system();
  Eigen::VectorXd phi;
  CalcPhi(sys, s, &phi);
  const std::vector<int> rows = RowsOnSolvedBodies(ws, AllRows(sys));
  return ScaledResidual(phi, rows, RowScales(sys, rows)) <= tolerance;
}

// A tight solve from the Taylor prediction off `base` at time t (the run's branch).
bool ProbeFrom(KinematicsWorkspace& ws, const SystemState& base, double t, int predictor_order, SystemState* probe) {
  constexpr double kTolerance = 1e-13;
  if (!SolveOnBranch(ws, base, t, predictor_order, kTolerance, probe)) return false;
  // The equations set aside as redundant must close too: past the fold of a redundant
  // mechanism (Bricard's) the solved rows alone still close, on a curve that crosses
  // the mechanism's there and misses the set-aside ones in proportion to the overshoot.
  return ClosesAllRows(ws, *probe, 100 * kTolerance);
}

// The pose as one vector (r and p of every body) for the fold fit.
Eigen::VectorXd PoseVector(const SystemState& s) {
  Eigen::VectorXd v(7 * s.bodies.size());
  for (size_t b = 0; b < s.bodies.size(); ++b) v.segment<7>(7 * b) << s.bodies[b].r[0], s.bodies[b].p;
  return v;
}

}  // namespace

LimitOfMotion LocateLimit(KinematicsWorkspace& ws, const SystemState& base, double t_lo, double t_hi,
                          double resolution, int predictor_order) {
  SystemState probe = base, s_lo = base;
  while (t_hi - t_lo > resolution) {
    const double mid = 0.5 * (t_lo + t_hi);
    if (ProbeFrom(ws, base, mid, predictor_order, &probe)) {
      t_lo = mid;
      s_lo = probe;
    } else {
      t_hi = mid;
    }
  }
  LimitOfMotion lim;
  lim.t = t_lo;
  // The fold: three solutions approaching it, t as a parabola in the coordinate moving most.
  const double delta = 1e-6 * (t_hi - base.t);
  const double ts[3] = {t_lo - delta, t_lo - 0.25 * delta, t_lo};
  Eigen::VectorXd x[3];
  bool ok = t_lo - delta > base.t;
  for (int k = 0; k < 2 && ok; ++k) {
    ok = ProbeFrom(ws, base, ts[k], predictor_order, &probe);
    x[k] = PoseVector(probe);
  }
  if (ok) {
    x[2] = PoseVector(s_lo);
    int c = 0;
    (x[2] - x[0]).cwiseAbs().maxCoeff(&c);
    const double x0 = x[0][c], x1 = x[1][c], x2 = x[2][c];
    // Divided differences: t = ts0 + d1 (x − x0) + d2 (x − x0)(x − x1).
    const double d01 = (ts[1] - ts[0]) / (x1 - x0), d12 = (ts[2] - ts[1]) / (x2 - x1), d2 = (d12 - d01) / (x2 - x0);
    const double xv = 0.5 * (x0 + x1) - d01 / (2 * d2);  // dt/dx = 0
    const double tv = ts[0] + d01 * (xv - x0) + d2 * (xv - x0) * (xv - x1);
    if (std::isfinite(tv) && d2 != 0 && tv >= t_lo - delta && tv <= t_hi + delta) {
      lim.t = tv;
      lim.fold = true;
    }
  }
  // No fit where the samples coincide (the base itself on the fold: a limit on a
  // table row): the end is then a fold when the solved rows say so there, and the
  // bisection already placed it to `resolution`.
  if (!lim.fold && IsFold(ws.system(), AllRows(ws.system()), s_lo)) lim.fold = true;
  EvalDriverFunctions(ws.system().model(), lim.t, &s_lo);
  for (const Jet& j : s_lo.driver_values) lim.driver_values.push_back(j.c[0]);
  return lim;
}

std::string LimitMessage(const Model& model, const LimitOfMotion& lim, int rows_done) {
  std::ostringstream o;
  o.precision(12);
  o << "limit of motion at t = " << lim.t << " s after " << rows_done << " rows:";
  for (size_t d = 0; d < model.drivers.size(); ++d) {
    const bool angle = model.drivers[d].kind == DriverKind::JointRotation || model.drivers[d].kind == DriverKind::BodyRotation;
    o << " driver `" << model.drivers[d].name << "` = "
      << lim.driver_values[d] / (angle ? model.units.angle_to_si : model.units.length_to_si) << " "
      << (angle ? model.units.angle_name : model.units.length_name) << (d + 1 < model.drivers.size() ? "," : "");
  }
  o << (lim.fold ? "\n  the branch folds there (a stroke end or a toggle of the driven output): the drivers "
                   "cannot go further on it"
                 : "\n  the drivers' values beyond it cannot be reached from the branch the run is on")
    << "\n  Try: keep the drivers inside this range (mechkin runs what the mechanism can do up to here), or drive "
       "another joint through this position.";
  return o.str();
}

SingularPosition DescribeSingularPosition(const ConstraintSystem& sys, const std::vector<int>& rows,
                                          const SystemState& at, const SingularClassification& c) {
  SingularPosition sp;
  sp.t = c.t;
  sp.driver_values = c.driver_values;
  sp.corank = c.corank;
  sp.branches = c.branches;
  sp.branches_exact = c.branches_exact;
  if (6 * sys.num_bodies() <= kDenseLimit) {
    sp.joint_mobility = JointMobility(sys, at);
    sp.involved = InvolvedEquations(sys, at, rows);
  }
  return sp;
}

namespace {

// ", driver `crank` = 90 deg" for every driver, in the file's units.
std::string DriverValues(const Model& model, const std::vector<double>& values) {
  std::ostringstream o;
  o.precision(12);
  for (size_t d = 0; d < model.drivers.size() && d < values.size(); ++d) {
    const bool angle = model.drivers[d].kind == DriverKind::JointRotation || model.drivers[d].kind == DriverKind::BodyRotation;
    o << ", driver `" << model.drivers[d].name << "` = "
      << values[d] / (angle ? model.units.angle_to_si : model.units.length_to_si) << " "
      << (angle ? model.units.angle_name : model.units.length_name);
  }
  return o.str();
}

}  // namespace

std::string PassageNote(const Model& model, const SingularClassification& c) {
  std::ostringstream o;
  o.precision(12);
  o << "unique passage through a singular position at t = " << c.t << " s" << DriverValues(model, c.driver_values)
    << ": Φ_q loses rank " << c.corank
    << " there but only the run's branch crosses it, so the prescribed motion stays determined and the run goes "
       "on (the rows next to it carry larger error bounds)";
  return o.str();
}

std::string SingularityMessage(const Model& model, const SingularPosition& sp) {
  std::ostringstream o;
  o.precision(12);
  o << "singular position at t = " << sp.t << " s";
  for (size_t d = 0; d < model.drivers.size(); ++d) {
    const bool angle = model.drivers[d].kind == DriverKind::JointRotation || model.drivers[d].kind == DriverKind::BodyRotation;
    o << ", driver `" << model.drivers[d].name << "` = "
      << sp.driver_values[d] / (angle ? model.units.angle_to_si : model.units.length_to_si) << " "
      << (angle ? model.units.angle_name : model.units.length_name);
  }
  o << "\n  instantaneous mobility of the joints there: " << sp.joint_mobility
    << " (a dead centre, toggle or change point where branches meet)";
  if (sp.branches > 1)
    o << "\n  branches crossing there: " << (sp.branches_exact ? "" : "at least ") << sp.branches << " (Φ_q loses rank " << sp.corank
      << "; the prescribed motion continues on each of them)";
  if (!sp.involved.empty()) {
    o << "\n  equations that become dependent: ";
    for (size_t k = 0; k < sp.involved.size(); ++k) o << (k ? ", `" : "`") << sp.involved[k] << "`";
  }
  o << "\n  The run stops here instead of choosing a branch. Try: end the motion before this time, or change "
       "the geometry so that the mechanism does not pass through this position.";
  return o.str();
}

std::string SolveFailureMessage(KinematicsWorkspace& ws, const SystemState& s, double t, int rows_done,
                                const std::string& why) {
  const double smin = SmallestSingularValue(ws.system(), s, ws.active());
  std::ostringstream o;
  o << "position solve failed at t = " << t << " s after " << rows_done << " rows: " << why
    << "\n  largest residuals:" << DescribeResiduals(ws.system(), s, ws.active(), ws.newton().scales(), 3)
    << "\n  smallest singular value of the scaled Φ_q: " << smin
    << (smin < 1e-6 ? " (singular: a toggle, dead centre or lock-up position)" : "")
    << "\n  Try: keep the drivers inside the reachable range, start the motion away from the singular "
       "position, or use more steps.";
  return o.str();
}

}  // namespace mechkin
