#include "analysis/kinematic_analysis.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "analysis/assembly.hpp"
#include "analysis/bound_sampling.hpp"
#include "analysis/clearance.hpp"
#include "spec/diagnostic.hpp"
#include "analysis/error_bounds.hpp"
#include "analysis/row_error_estimate.hpp"
#include "analysis/row_selection.hpp"
#include "analysis/singular_points.hpp"
#include "analysis/step_observer.hpp"

namespace mechkin {

namespace {

std::string Shown(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

std::string OrderProblem(const std::string& shown) {
  return "order must be an integer in 0..4 (0 position, 1 velocity, 2 acceleration, 3 jerk, 4 snap), not " + shown;
}

std::string ToleranceProblem(const std::string& shown) {
  return "tol must be a number in [1e-15, 1e-3] (the position tolerance relative to the mechanism size), not " +
         shown;
}

bool CheckSolverFields(int order, double tolerance, int max_iterations, int predictor_order, bool sensitivities,
                       Formulation formulation, PositionSolver solver, std::string* why) {
  auto fail = [why](const std::string& message) {
    *why = message;
    return false;
  };
  if (order < 0 || order > kMaxOrder) return fail(OrderProblem(std::to_string(order)));
  // Written so that NaN fails too.
  if (!(tolerance >= kMinTolerance && tolerance <= kMaxTolerance)) return fail(ToleranceProblem(Shown(tolerance)));
  if (max_iterations < 1) return fail("max_iterations must be 1 or more, not " + std::to_string(max_iterations));
  if (predictor_order < 0 || predictor_order > 3)
    return fail("predictor order must be an integer in 0..3, not " + std::to_string(predictor_order));
  if (sensitivities && (formulation != Formulation::Omega || solver != PositionSolver::Newton))
    return fail("sensitivities use the default formulation and solver (omega, newton)");
  return true;
}

// The fields a request has are checked as RunRequest::IsValid checks them (one
// range, one message); then the solver's own precondition, which PlanRun always meets.
bool AnalysisOptions::IsValid(std::string* error) const {
  if (!CheckSolverFields(order, tolerance, max_iterations, predictor_order, !sensitivity_parameters.empty(),
                         formulation, solver, error))
    return false;
  if (forces && order < kForcesOrder) {
    *error = "forces need accelerations: the solved order must be 2 or more (PlanRun raises it)";
    return false;
  }
  return true;
}

StepStatistics SummarizeSteps(const std::vector<StepDiagnostics>& steps) {
  StepStatistics st;
  if (steps.empty()) return st;
  std::vector<double> us;
  us.reserve(steps.size());
  for (const auto& d : steps) {
    us.push_back(d.solve_seconds * 1e6);
    st.mean_iterations += d.iterations;
    st.max_residual = std::max(st.max_residual, d.residual);
    st.max_set_aside_residual = std::max(st.max_set_aside_residual, d.set_aside_residual);
  }
  std::nth_element(us.begin(), us.begin() + us.size() / 2, us.end());
  st.median_us = us[us.size() / 2];
  st.mean_iterations /= steps.size();
  return st;
}

namespace {

using Clock = std::chrono::steady_clock;


WorkspaceOptions WorkspaceOptionsOf(const AnalysisOptions& o) {
  WorkspaceOptions w;
  w.formulation = o.formulation;
  w.solver = o.solver;
  w.ceres_normalization_residual = o.ceres_normalization_residual;
  w.order = o.order;
  // Forces and sensitivities solve with the whole system's factorization.
  if (!o.forces && o.sensitivity_parameters.empty()) w.needed_bodies = o.needed_bodies;
  return w;
}

// Re-selection of the redundant equations: when the solved rows' condition estimate
// (dimensionless) exceeds this, look for a better-conditioned set (bundled
// mechanisms stay below 40 over their whole motion).
constexpr double kReselectCondition = 100;
// Above this condition no residual makes the derivatives' bound meet a tolerance
// (u·κ² ≥ 1e-8): the row reports its bound instead of polishing.
constexpr double kMaxPolishCondition = 1e4;
constexpr double kReselectGain = 4;  // ... and switch when that set is this much better
constexpr double kWellConditionedRows = 1e4;  // 1-norm condition a new set must stay below
constexpr int kMaxReselectColumns = 1200;  // 200 bodies: the dense QR of the selection
// Rows whose condition estimate reaches this, with 1/κ heading for zero, have the
// step before them examined for a singular position (bundled mechanisms: below 40 on
// the one-step estimate; three pass 50 on the sharper one, with their tables and
// times unchanged, docs/singularities.md §1).
constexpr double kExamineCondition = 50;
// A position located that many steps ahead of the row examined is kept (pending)
// until a row passes it: the condition estimate rises unevenly, and the
// rows nearest the position may be the ones whose examination cannot classify it
// (the N-four-bar, N = 4, 360 steps: located 4 steps ahead, missed from the rows
// beside it).
constexpr double kLookAheadSteps = 8;
// Rows whose condition estimate reaches both have their error bounds measured
// (row_error_estimate.hpp) instead of taken from κ alone: there a derivative's error
// grows faster than the a priori bound's powers of κ (bundled mechanisms: a few rows
// of four of them).
constexpr double kMeasureBoundsCondition = 20;
constexpr double kMeasureBoundsGrowth = 2;
constexpr int kSharperSteps = 2;
// A pose whose set-aside (redundant) equations miss by more than this many position
// tolerances is off the mechanism (Stepper::SetAsideCloses).
constexpr double kSetAsideFactor = 10;

// Condition number (1-norm estimate) of the scaled Jacobian's rows `rows`: compares
// two independent sets of the same mechanism.
double RowsCondition(const Eigen::MatrixXd& scaled_J, const std::vector<int>& rows) {
  Eigen::MatrixXd A(rows.size(), scaled_J.cols());
  for (size_t k = 0; k < rows.size(); ++k) A.row(k) = scaled_J.row(rows[k]);
  const double rcond = Eigen::PartialPivLU<Eigen::MatrixXd>(A).rcond();
  return rcond > 0 ? 1 / rcond : std::numeric_limits<double>::infinity();
}

// The time stepping of a run: the branch-guarded step, its refinement into
// sub-steps, and the per-row diagnostics. Owns the state that lives across steps.
class Stepper {
 public:
  Stepper(std::unique_ptr<KinematicsWorkspace> ws, const AnalysisOptions& options, RowSelection selection,
          SystemState start, std::unique_ptr<SensitivitySolver> sensitivity)
      : ws_(std::move(ws)), model_(ws_->system().model()), options_(options), selection_(std::move(selection)),
        s_(std::move(start)), prev_(s_), predicted_(s_), good_(s_) {
    // What runs on each accepted step besides the solve, in order (step_observer.hpp);
    // Run appends the row delivery last.
    if (options.forces) observers_.push_back(MakeForceObserver(ws_->system(), selection_, options.order));
    if (sensitivity) observers_.push_back(MakeSensitivityObserver(std::move(sensitivity)));
    if (auto limits = MakeJointLimitObserver(model_, options)) observers_.push_back(std::move(limits));
    errors_ = std::make_unique<RowErrorEstimator>(ws_->system(), options.order);
    solve_.tolerance = options.tolerance;
    solve_.max_iterations = options.max_iterations;
    predictor_ = std::min(options.predictor_order, options.order);
    CheckSetAsideOnSolvedBodies();
    if (!ClearanceOutputPairs(model_).empty())
      observers_.push_back(MakeContactObserver(model_, ws_->options().needed_bodies, options.on_contact_stop));
  }
  /// Runs every row; fills the report's stop reason when it ends early.
  void Run(const StepCallback& on_step, AnalysisReport* rep);

 private:
  enum class Outcome { Ok, Failed, Suspect };
  Outcome Attempt(double t, double dt, bool reuse, bool polish = true);
  Outcome Refine(double t, StepDiagnostics* diag, double* bad_t);
  bool SetAsideCloses();
  double UpdateSetAsideResidual();
  void CheckSetAsideOnSolvedBodies();
  void FinishDiagnostics(StepDiagnostics* diag);
  void MeasureRow(double kappa, BoundSampler::Row kind, StepDiagnostics* diag);
  bool MeasuresBounds(double condition) const {
    return options_.measure_every_row ||
           (condition >= kMeasureBoundsCondition && condition >= kMeasureBoundsGrowth * bounds_regular_);
  }
  bool Reselect(const SystemState& at, double min_gain, AnalysisReport* rep);
  bool ReselectAndResolve(StepDiagnostics* diag, AnalysisReport* rep);
  bool StopAtLimitOrSingularity(Outcome out, double t, double bad_t, AnalysisReport* rep);
  enum class Verdict { Undecided, Passed, Stop };
  Verdict ClassifySuspect(double t, double h, double* bad_t, Outcome* out, StepDiagnostics* diag, AnalysisReport* rep);
  Verdict PassOn(double t, double h, StepDiagnostics* diag, double* bad_t, Outcome* out);
  Verdict RetryAcrossPassage(double t, double h, double* bad_t, Outcome* out, AnalysisReport* rep);
  void NotePassage(const SingularClassification& c, double h, AnalysisReport* rep);
  bool StopAtConditionMinimum(double t, double h, AnalysisReport* rep);
  bool ActOnPending(double h, AnalysisReport* rep);
  SingularityClassifier& Classifier();
  void StopAtBifurcation(const SingularClassification& c, AnalysisReport* rep);
  bool CrossesPassage(double t, double dt) const { return dt > 0 && passage_t_ > t - dt * (1 + 1e-12) && passage_t_ <= t; }

  std::unique_ptr<KinematicsWorkspace> ws_;
  const Model& model_;
  const AnalysisOptions& options_;
  RowSelection selection_;
  SolveOptions solve_;
  int predictor_ = 3;
  SystemState s_, prev_, predicted_, good_;
  SolveSummary last_;
  double prev_sign_ = 0;
  double last_condition_ = 1;  // the previous row's condition estimate
  double set_aside_residual_ = 0;  // at s_, by UpdateSetAsideResidual
  std::vector<int> checked_set_aside_;  // the set-aside rows whose bodies the solves move
  Eigen::VectorXd checked_set_aside_scales_;
  double regular_condition_ = std::numeric_limits<double>::infinity();  // the smallest along the run
  double reselect_above_ = kReselectCondition;  // condition that triggers the next search
  bool have_sign_ = false;
  Eigen::VectorXd phi_;
  // Singular positions the sign of det Φ_q cannot see (docs/singularities.md): the
  // classifier (own workspace), the last unique passage and the conditions of the
  // two rows before this one.
  std::unique_ptr<SingularityClassifier> classifier_;
  double passage_t_ = -std::numeric_limits<double>::infinity();
  double earlier_condition_[2] = {0, 0};
  // This row's sharper κ (FinishDiagnostics): the watch for condition minima reads it,
  // not the one-step estimate, which lags by up to 5× three degrees from the N-four-bar's
  // bifurcation and hid the rise there.
  double sharper_condition_ = 0;
  std::optional<std::pair<SingularClassification, SingularPosition>> pending_;  // located ahead of the row
  double step_sign_ = 0;
  bool step_have_sign_ = false;
  std::vector<std::unique_ptr<StepObserver>> observers_;
  std::unique_ptr<RowErrorEstimator> errors_;  // the measured bounds near singular positions
  BoundSampler sampler_;  // and on a sample of the other rows
  BoundSampler sampler_at_row_;  // as it was before this row (a re-solved row goes through it once)
  double bounds_regular_ = std::numeric_limits<double>::infinity();  // smallest sharper κ along the run
};

// One attempt from the accepted state to time t (predictor over dt).
// Suspect: det Φ_q changed sign, or the solution is far (> 0.1 L or rad) from the
// prediction — the marks of a jump to another assembly branch or of a singular
// position between the two times.
Stepper::Outcome Stepper::Attempt(double t, double dt, bool reuse, bool polish) {
  EvalDriverFunctions(model_, t, &s_);
  AimRotationDrivers(ws_->system(), &s_);
  if (dt > 0 && predictor_ > 0) PredictPose(dt, predictor_, &s_);
  // Only the poses (all PoseDistance reads): the whole bodies are 1.8 kB each.
  for (size_t b = 0; b < s_.bodies.size(); ++b) {
    predicted_.bodies[b].r[0] = s_.bodies[b].r[0];
    predicted_.bodies[b].p = s_.bodies[b].p;
  }
  // The tolerance is on the answer too: the derivatives need κ² times less residual
  // (error_bounds.hpp). Not in the sub-steps that bracket a singular position
  // (Refine), where the pose must follow the plain continuation the bisection expects,
  // nor where no residual would do (κ ≥ 1e4).
  const bool accuracy_phase = polish && last_condition_ < kMaxPolishCondition;
  solve_.target = accuracy_phase ? ResidualForAccuracy(options_.tolerance, last_condition_, options_.order) : 0;
  // Below double round-off the residual is evaluated in extended precision.
  solve_.extended_precision =
      accuracy_phase && NeedsExtendedResidual(options_.tolerance, last_condition_, regular_condition_, options_.order);
  last_ = SolvePosition(*ws_, solve_, &s_, reuse && options_.modified_newton);
  if (!last_.success || !SetAsideCloses()) return Outcome::Failed;
  const double sign = ws_->factorization().Sign();
  if (options_.branch_guard) {
    if (have_sign_ && sign != prev_sign_ && !CrossesPassage(t, dt)) return Outcome::Suspect;
    if (dt > 0 && PoseDistance(predicted_, s_, model_.characteristic_length) > 0.1) return Outcome::Suspect;
  }
  SolveDerivatives(*ws_, options_.order, &s_);
  prev_sign_ = sign;
  have_sign_ = true;
  return Outcome::Ok;
}

// The equations set aside as redundant close at s_ too. Past the fold of a redundant
// mechanism (Bricard's linkage) the solved rows alone still close, on a curve of their
// own that crosses the mechanism's at the fold and misses the set-aside equations in
// proportion to the overshoot: such a pose is not the mechanism's (no assembly exists
// there), so the step fails and the fold is located. Along a motion they close to
// about the solved residual (bundled: ≤ 3e-12 at tolerance 1e-10).
bool Stepper::SetAsideCloses() {
  return UpdateSetAsideResidual() <= kSetAsideFactor * options_.tolerance;
}

// The scaled residual of the set-aside equations at s_, kept for the row's
// diagnostics: every accepted pose passed Attempt, which computed it there.
double Stepper::UpdateSetAsideResidual() {
  set_aside_residual_ = 0;
  if (checked_set_aside_.empty()) return 0;
  CalcPhi(ws_->system(), s_, &phi_);
  set_aside_residual_ = ScaledResidual(phi_, checked_set_aside_, checked_set_aside_scales_);
  return set_aside_residual_;
}

// A table that reads some bodies only solves the blocks they need (workspace.hpp);
// a set-aside equation on a body left at its design pose says nothing of the motion.
void Stepper::CheckSetAsideOnSolvedBodies() {
  checked_set_aside_ = RowsOnSolvedBodies(*ws_, selection_.set_aside);
  checked_set_aside_scales_ = RowScales(ws_->system(), checked_set_aside_);
}

// Adaptive sub-stepping between two table rows: halve until every sub-step is
// regular. A sign change that survives 1/1024 of the step is a genuine singular
// position; good_ and *bad_t then bracket it.
Stepper::Outcome Stepper::Refine(double t, StepDiagnostics* diag, double* bad_t) {
  const double good_sign = prev_sign_;
  const bool good_have_sign = have_sign_;  // false right after a re-selection: no sign to compare yet
  Outcome out = Outcome::Suspect;
  for (int parts = 2; parts <= 1024 && out != Outcome::Ok; parts *= 2) {
    s_ = prev_;
    prev_sign_ = good_sign;
    have_sign_ = good_have_sign;
    good_ = prev_;
    for (int i = 1; i <= parts; ++i) {
      const double ti = prev_.t + (t - prev_.t) * i / parts;
      out = Attempt(ti, (t - prev_.t) / parts, true, /*polish=*/false);
      diag->iterations += last_.iterations;
      if (out != Outcome::Ok) { *bad_t = ti; break; }
      UpdateAngleReferences(ws_->system(), &s_);
      good_ = s_;
      good_.t = ti;
    }
    if (out == Outcome::Ok) ++diag->substeps_refinements;
  }
  return out;
}

void Stepper::FinishDiagnostics(StepDiagnostics* diag) {
  diag->residual = last_.residual;
  diag->set_aside_residual = set_aside_residual_;
  diag->condition = ws_->factorization().ConditionEstimate();
  last_condition_ = diag->condition;
  regular_condition_ = std::min(regular_condition_, diag->condition);
  // Which rows take measured bounds is decided on the sharper κ (two more
  // iterations): the one-step estimate lags where a pivot collapses (constraints.md §8).
  const double kappa = std::max(diag->condition, ws_->factorization().SharperConditionEstimate(kSharperSteps));
  sharper_condition_ = kappa;
  bounds_regular_ = std::min(bounds_regular_, kappa);
  CalcErrorBounds(diag->condition, diag->residual, kMaxOrder, diag->error_bound);
  errors_->Observe(s_);
  // Samples only where there are derivatives to raise, and not on the block-by-block
  // path, whose factorization cannot solve the whole system the estimator needs.
  const bool sample = sampler_.Due() && options_.order > 0 && !ws_->block_solver();
  if (MeasuresBounds(kappa)) MeasureRow(kappa, BoundSampler::Row::MeasuredWhole, diag);
  else if (sample) MeasureRow(kappa, BoundSampler::Row::Sampled, diag);
  else sampler_.RaiseUnsampled(kappa, diag->error_bound, options_.order);
}

// A row whose bounds are measured, from nothing so that the sampler learns the measured
// bounds themselves (bound_sampling.hpp). A row measured whole (near a singular position,
// or --error-bounds measured) reports them as measured, its position's never below the
// bound from κ; a sampled row between the bound from κ and the ceiling.
void Stepper::MeasureRow(double kappa, BoundSampler::Row kind, StepDiagnostics* diag) {
  static_assert(BoundSampler::kMaxOrder == kMaxOrder, "one highest order");
  double measured[kMaxOrder + 1] = {};
  if (!errors_->Raise(*ws_, s_, kappa, measured)) {
    sampler_.RaiseUnsampled(kappa, diag->error_bound, options_.order);
    return;
  }
  sampler_.Learn(diag->error_bound, measured, options_.order, kind);
  if (kind == BoundSampler::Row::Sampled) {
    BoundSampler::ClampSampled(kappa, diag->error_bound, measured, options_.order);
  } else {
    measured[0] = std::max(measured[0], diag->error_bound[0]);
  }
  std::copy(measured, measured + options_.order + 1, diag->error_bound);
}

// Redundancy that follows the motion (issue "Right at every order", item 1): the
// equations set aside at assembly may stop being the redundant ones (a Bennett
// linkage half way round). At pose `at`, choose the best-conditioned independent
// set of the same equations and switch to it when its condition number is at least
// `min_gain` times smaller. Dense models only; never for mechanisms without redundancy.
bool Stepper::Reselect(const SystemState& at, double min_gain, AnalysisReport* rep) {
  const ConstraintSystem& sys = ws_->system();
  if (selection_.set_aside.empty() || 6 * sys.num_bodies() > kMaxReselectColumns) return false;
  RowSelection next = SelectWellConditionedRows(sys, at);
  if (next.active.empty() || next.active == selection_.active) return false;
  const Eigen::MatrixXd J = ScaledJacobian(sys, at);
  // Only a well-conditioned alternative: near a singular position of the whole
  // mechanism (a change point) every set degenerates and the run must stop there.
  const double next_condition = RowsCondition(J, next.active);
  if (!(next_condition < kWellConditionedRows) || !(next_condition * min_gain < RowsCondition(J, selection_.active)))
    return false;
  selection_ = std::move(next);
  ws_ = std::make_unique<KinematicsWorkspace>(sys, selection_.active, WorkspaceOptionsOf(options_));
  CheckSetAsideOnSolvedBodies();
  for (auto& o : observers_) o->Reselected(sys, selection_);
  have_sign_ = false;  // det Φ_q of other rows: its sign starts afresh
  rep->reselections.push_back({at.t, selection_.set_aside_names});
  return true;
}

// After an accepted row whose rows have become ill-conditioned: re-select there and
// solve the row again with the new rows (position from the pose found, derivatives).
// A search that found nothing better is not repeated at every row: the next one
// waits until the condition has grown 4× (or fallen back below the trigger).
bool Stepper::ReselectAndResolve(StepDiagnostics* diag, AnalysisReport* rep) {
  if (!(diag->condition > kReselectCondition)) {
    reselect_above_ = kReselectCondition;
    return false;
  }
  if (!(diag->condition > reselect_above_) || selection_.set_aside.empty()) return false;
  reselect_above_ = 4 * diag->condition;
  if (!Reselect(s_, kReselectGain, rep)) return false;
  reselect_above_ = kReselectCondition;
  last_ = SolvePosition(*ws_, solve_, &s_, false);
  if (!last_.success) return false;
  SolveDerivatives(*ws_, options_.order, &s_);
  prev_sign_ = ws_->factorization().Sign();
  have_sign_ = true;
  UpdateSetAsideResidual();  // other rows are set aside now
  sampler_ = sampler_at_row_;  // the row's bounds are decided again, once
  FinishDiagnostics(diag);
  return true;
}

// A step that stays irregular down to 1/1024 of the step. Where the branch folds
// (a stroke end, a limit of a non-Grashof input: no pose beyond it) it is a limit of
// motion, located as the fold; where the solve goes on but det Φ_q changes sign, a
// singular position the branches cross, located by bisection. Returns false when it
// is neither (the caller reports the failed solve).
bool Stepper::StopAtLimitOrSingularity(Outcome out, double t, double bad_t, AnalysisReport* rep) {
  const double resolution = 1e-9 * (t - prev_.t) / 1024;
  const int order = std::max(predictor_, 1);
  if (bad_t > good_.t && !ws_->block_solver()) {
    const LimitOfMotion lim = LocateLimit(*ws_, good_, good_.t, bad_t, resolution, order);
    if (lim.fold || out == Outcome::Failed) {
      rep->stop = StopKind::SolveFailed;
      rep->message = LimitMessage(model_, lim, rep->rows) + "\n  " + SolveFailureMessage(*ws_, s_, t, rep->rows, last_.message);
      rep->limit = lim;
      return true;
    }
  }
  if (out != Outcome::Suspect) return false;
  const SingularPosition sp = LocateSingularity(*ws_, good_, good_.t, bad_t, prev_sign_, resolution, order);
  rep->stop = StopKind::SingularPosition;
  rep->message = SingularityMessage(model_, sp);
  rep->singular = sp;
  return true;
}

SingularityClassifier& Stepper::Classifier() {
  if (!classifier_ || classifier_->active() != ws_->active())
    classifier_ = std::make_unique<SingularityClassifier>(ws_->system(), ws_->active());
  return *classifier_;
}

void Stepper::StopAtBifurcation(const SingularClassification& c, AnalysisReport* rep) {
  const SingularPosition sp = DescribeSingularPosition(ws_->system(), Classifier().active(), Classifier().pose(), c);
  rep->stop = StopKind::SingularPosition;
  rep->message = SingularityMessage(model_, sp);
  rep->singular = sp;
}

// A step still suspect at 1/1024 of the step: where the smallest singular values of
// Φ_q vanish between good_ and bad_t, classify the position (docs/singularities.md).
// A unique passage is crossed — the step redone with the sign test waived across it
// — and noted; a bifurcation stops the run; the rest is StopAtLimitOrSingularity's.
Stepper::Verdict Stepper::ClassifySuspect(double t, double h, double* bad_t, Outcome* out, StepDiagnostics* diag,
                                          AnalysisReport* rep) {
  if (!options_.branch_guard || ws_->block_solver() || !(*bad_t > good_.t)) return Verdict::Undecided;
  // Located ahead from well-determined rows: kept, not classified again from the
  // step's last good pose — that one lies so close to the position that its rates
  // are amplified by 1/σ_min and its prediction misses the position (N-four-bar, N = 3).
  if (pending_ && pending_->first.t > good_.t - 1e-9 * h && pending_->first.t < *bad_t + 1e-9 * h)
    return ActOnPending(h, rep) ? Verdict::Stop : PassOn(t, h, diag, bad_t, out);
  const SingularClassification c = Classifier().Classify(good_, *bad_t, h);
  if (!(c.t > good_.t - h && c.t < *bad_t + h)) return Verdict::Undecided;
  if (c.kind == SingularKind::Bifurcation) {
    StopAtBifurcation(c, rep);
    return Verdict::Stop;
  }
  if (c.kind != SingularKind::UniquePassage || std::abs(c.t - passage_t_) < 1e-6 * h) return Verdict::Undecided;
  NotePassage(c, h, rep);
  return PassOn(t, h, diag, bad_t, out);
}

// A step that does not converge where a unique passage lies inside it: the predictor
// starts too close to a position of corank ≥ 2 (its rates amplified by 1/σ_1), and
// the bisection's sub-steps land on the position itself, so the failure looks like a
// limit of motion (the N-four-bar, N = 3, in 360 steps: 0.6 steps before it). Located
// and classified as a sign flip is; the step is then taken from the classifier's last
// solved pose past the position (within the step), the sign of det Φ_q taken afresh
// there. Only a retry that succeeds notes the passage; otherwise the step is left as
// it failed (a limit of motion of a redundant mechanism — Bricard's — can look like a
// passage to the solved rows alone, and the retry fails on the set-aside ones).
Stepper::Verdict Stepper::RetryAcrossPassage(double t, double h, double* bad_t, Outcome* out, AnalysisReport* rep) {
  if (!options_.branch_guard || ws_->block_solver() || !(*bad_t > good_.t)) return Verdict::Undecided;
  // Over the whole step, not from its last good sub-step to the failed one: those
  // may lie within 1e-8 s of the position, where nothing is well determined.
  const SingularClassification c = Classifier().Classify(prev_, t, h);
  if (!(c.t > prev_.t && c.t < t)) return Verdict::Undecided;
  if (c.kind == SingularKind::Bifurcation) {
    StopAtBifurcation(c, rep);
    return Verdict::Stop;
  }
  const SystemState* past = Classifier().SolvedPast(c.t, t);
  if (c.kind != SingularKind::UniquePassage || !past) return Verdict::Undecided;
  const double kept_sign = prev_sign_;
  const bool kept_have_sign = have_sign_;
  s_ = *past;
  have_sign_ = false;
  if (Attempt(t, t - past->t, false) != Outcome::Ok) {
    s_ = prev_;
    prev_sign_ = kept_sign;
    have_sign_ = kept_have_sign;
    return Verdict::Undecided;
  }
  *out = Outcome::Ok;
  NotePassage(c, h, rep);
  return Verdict::Passed;
}

// A unique passage the run has crossed: noted once, and no longer pending.
void Stepper::NotePassage(const SingularClassification& c, double h, AnalysisReport* rep) {
  if (std::abs(c.t - passage_t_) >= 1e-6 * h) rep->notes.push_back(PassageNote(model_, c));
  if (pending_ && std::abs(pending_->first.t - c.t) < 1e-6 * h) pending_.reset();  // the same one
  passage_t_ = c.t;
}

// Past a unique passage: the step again, its sign change expected.
Stepper::Verdict Stepper::PassOn(double t, double h, StepDiagnostics* diag, double* bad_t, Outcome* out) {
  s_ = prev_;
  prev_sign_ = step_sign_;
  have_sign_ = step_have_sign_;
  *out = Attempt(t, h, false);
  if (*out != Outcome::Ok) *out = Refine(t, diag, bad_t);
  return Verdict::Passed;
}

// A singular position of even multiplicity leaves the sign of det Φ_q as it was:
// the rows' condition estimate shows it. When 1/κ, extrapolated from the two rows
// before, reaches zero by the middle of the next step and κ is high, the step
// (prev_, t] is classified before its row is delivered (docs/singularities.md §1).
// A position located ahead is kept until the row that passes it.
bool Stepper::StopAtConditionMinimum(double t, double h, AnalysisReport* rep) {
  const double k2 = earlier_condition_[0], k1 = earlier_condition_[1];
  earlier_condition_[0] = k1;
  earlier_condition_[1] = sharper_condition_;
  if (pending_ && pending_->first.t <= t + 1e-9 * h) return ActOnPending(h, rep);
  if (pending_ || !options_.branch_guard || !(k2 > 0) || !(k1 > k2) || ws_->block_solver()) return false;
  if (!(std::max(k1, sharper_condition_) >= kExamineCondition) || CrossesPassage(t, h)) return false;
  const double t_zero = prev_.t + h * (1 / k1) / (1 / k2 - 1 / k1);
  if (!(t_zero < t + 0.5 * h)) return false;
  const SingularClassification c = Classifier().Classify(prev_, t, h);
  if (c.kind != SingularKind::UniquePassage && c.kind != SingularKind::Bifurcation) return false;
  if (std::abs(c.t - passage_t_) < 1e-6 * h || !(c.t > prev_.t - 2 * h && c.t < t + kLookAheadSteps * h)) return false;
  pending_.emplace(c, DescribeSingularPosition(ws_->system(), Classifier().active(), Classifier().pose(), c));
  return c.t <= t + 1e-9 * h && ActOnPending(h, rep);
}

// The row passes the singular position classified before: a bifurcation stops the
// run (this row is past it), a unique passage is noted.
bool Stepper::ActOnPending(double h, AnalysisReport* rep) {
  const auto [c, sp] = *pending_;
  pending_.reset();
  if (c.kind == SingularKind::Bifurcation) {
    rep->stop = StopKind::SingularPosition;
    rep->message = SingularityMessage(model_, sp);
    rep->singular = sp;
    return true;
  }
  NotePassage(c, h, rep);
  return false;
}

void Stepper::Run(const StepCallback& on_step, AnalysisReport* rep) {
  const Analysis& an = *model_.analysis;
  const double h = (an.end - an.start) / an.steps;
  observers_.push_back(MakeRowDelivery(options_, on_step));
  for (int step = 0; step <= an.steps; ++step) {
    const double t = an.start + step * h;
    const auto t0 = Clock::now();
    StepDiagnostics diag;
    diag.t = t;
    step_sign_ = prev_sign_;
    step_have_sign_ = have_sign_;
    Outcome out = Attempt(t, step > 0 ? h : 0, step > 0);
    diag.iterations = last_.iterations;
    double bad_t = t;
    if (out != Outcome::Ok && step > 0) out = Refine(t, &diag, &bad_t);
    if (out != Outcome::Ok && step > 0 && Reselect(good_, 1.0, rep)) {
      // The failure may be the set-aside choice's, not the mechanism's: choose the
      // best-conditioned rows next to the trouble and retry the step with them.
      s_ = prev_;
      out = Attempt(t, h, false);
      if (out != Outcome::Ok) out = Refine(t, &diag, &bad_t);
    }
    if (out == Outcome::Suspect && step > 0 && ClassifySuspect(t, h, &bad_t, &out, &diag, rep) == Verdict::Stop) return;
    if (out == Outcome::Failed && step > 0 && RetryAcrossPassage(t, h, &bad_t, &out, rep) == Verdict::Stop) return;
    if (out != Outcome::Ok && step > 0 && StopAtLimitOrSingularity(out, t, bad_t, rep)) return;
    if (out != Outcome::Ok) {
      rep->stop = StopKind::SolveFailed;
      rep->message = SolveFailureMessage(*ws_, s_, t, rep->rows, last_.message);
      return;
    }
    sampler_at_row_ = sampler_;
    FinishDiagnostics(&diag);
    ReselectAndResolve(&diag, rep);
    if (StopAtConditionMinimum(t, h, rep)) return;
    const StepContext context{*ws_, prev_, step, std::max(predictor_, 1), t0};
    for (auto& o : observers_)
      if (!o->Observe(context, s_, &diag, rep)) return;
    prev_ = s_;
  }
  rep->complete = true;
}


}  // namespace

// The run as a sequence of named steps: assemble the design pose, select the
// independent equations, refuse mechanisms that are not fully driven, continue
// the drivers to `start`, then step through time.
AnalysisReport RunKinematicAnalysis(const Model& model, const AnalysisOptions& options, const StepCallback& on_step,
                                    const PoseCallback& on_assembly) {
  AnalysisReport rep;
  rep.stop = StopKind::Refused;
  if (!options.IsValid(&rep.message)) return rep;
  if (!model.analysis) {
    rep.message = "the file has no 'analysis' block: add {\"start\": 0, \"end\": 1, \"steps\": 100}";
    return rep;
  }
  std::unique_ptr<SensitivitySolver> sensitivity;
  try {
    if (!options.sensitivity_parameters.empty())
      sensitivity = std::make_unique<SensitivitySolver>(model, options.sensitivity_parameters, options.order);
  } catch (const std::exception& e) {
    rep.message = e.what();
    return rep;
  }
  try {
    const ConstraintSystem sys(model, true);
    SystemState s(sys);
    SolveOptions solve;
    solve.tolerance = options.tolerance;
    solve.max_iterations = options.max_iterations;
    rep.stop = StopKind::AssemblyFailed;
    if (!AssembleDesignPose(sys, solve, &s, &rep.assembly_iterations, &rep.message)) return rep;
    if (!AssembleHintedBranch(sys, solve, &s, &rep.assembly_iterations, &rep.message)) return rep;
    if (!AssembleFlippedBranch(sys, solve, &s, &rep.assembly_iterations, &rep.message)) return rep;
    const RowSelection selection = SelectRows(sys, s);
    rep.set_aside = selection.set_aside_names;
    rep.stop = StopKind::Refused;
    rep.message = DrivingRefusal(sys, selection);
    if (!rep.message.empty()) return rep;
    auto ws = std::make_unique<KinematicsWorkspace>(sys, selection.active, WorkspaceOptionsOf(options));
    rep.blocks = ws->blocks();
    rep.blocks_solved = ws->blocks_solved();
    rep.stop = StopKind::AssemblyFailed;
    if (on_assembly) on_assembly(s);
    if (!ContinueToStart(*ws, model.analysis->start, solve, &s, &rep.assembly_iterations, &rep.message, on_assembly))
      return rep;
    rep.stop = StopKind::None;
    Stepper(std::move(ws), options, selection, std::move(s), std::move(sensitivity)).Run(on_step, &rep);
  } catch (const std::exception& e) {
    rep.stop = StopKind::SolveFailed;
    rep.message = e.what();
  }
  return rep;
}

}  // namespace mechkin
