#include "analysis/step_observer.hpp"

#include <algorithm>

#include "analysis/contact_watch.hpp"
#include "analysis/forces.hpp"
#include "analysis/joint_limits.hpp"
#include "analysis/sensitivity.hpp"
#include "spec/diagnostic.hpp"

namespace mechkin {

namespace {

class ForceObserver : public StepObserver {
 public:
  ForceObserver(const ConstraintSystem& sys, const RowSelection& selection, int order)
      : order_(order), solver_(std::make_unique<ForceSolver>(sys, selection, order)) {}
  bool Observe(const StepContext& ctx, SystemState& s, StepDiagnostics* diag, AnalysisReport* rep) override {
    solver_->Solve(ctx.ws, s, &results_);
    diag->forces = &results_;
    rep->indeterminate_reactions = solver_->indeterminate();
    return true;
  }
  // The multipliers belong to the rows solved: a new selection needs a new solver.
  void Reselected(const ConstraintSystem& sys, const RowSelection& selection) override {
    solver_ = std::make_unique<ForceSolver>(sys, selection, order_);
  }

 private:
  int order_;
  std::unique_ptr<ForceSolver> solver_;
  ForceResults results_;
};

class SensitivityObserver : public StepObserver {
 public:
  explicit SensitivityObserver(std::unique_ptr<SensitivitySolver> solver) : solver_(std::move(solver)) {}
  bool Observe(const StepContext& ctx, SystemState& s, StepDiagnostics* diag, AnalysisReport* rep) override {
    if (!solver_->Solve(ctx.ws, s)) {
      rep->stop = StopKind::SolveFailed;
      rep->message = "the sensitivities cannot be solved at t = " + std::to_string(s.t) + " s";
      return false;
    }
    diag->sensitivity = solver_.get();
    return true;
  }

 private:
  std::unique_ptr<SensitivitySolver> solver_;
};

// Joint limits (analysis/joint_limits.hpp), after the row's forces and sensitivities (the location's
// solves reuse the workspace): the first row must start inside them; a step that
// crosses a bound is located, then stops the run or, with on_limit_report, is noted.
class JointLimitObserver : public StepObserver {
 public:
  JointLimitObserver(const Model& model, const AnalysisOptions& options)
      : model_(model), report_only_(options.on_limit_report), watch_(model) {}
  bool Observe(const StepContext& ctx, SystemState& s, StepDiagnostics*, AnalysisReport* rep) override {
    return ctx.step == 0 ? AtStart(s, rep) : Between(ctx, s, rep);
  }

 private:
  bool AtStart(const SystemState& s, AnalysisReport* rep);
  bool Between(const StepContext& ctx, const SystemState& s, AnalysisReport* rep);
  const Model& model_;
  bool report_only_;
  JointLimitWatch watch_;
};

bool JointLimitObserver::AtStart(const SystemState& s, AnalysisReport* rep) {
  const std::optional<int> outside = watch_.Start(s);
  if (!outside) return true;
  const Joint& j = model_.joints[*outside];
  const bool rot = LimitOnRotation(j.type);
  const double unit = rot ? model_.units.angle_to_si : model_.units.length_to_si;
  const std::string text = "joint `" + j.name + "` starts at " + FormatNumber(LimitedCoordinate(j, s, 0.0) / unit) +
                           " " + (rot ? model_.units.angle_name : model_.units.length_name) + ", outside its limits [" +
                           FormatNumber(j.limits->first / unit) + ", " + FormatNumber(j.limits->second / unit) + "]";
  if (report_only_) {
    rep->notes.push_back(text);
    return true;
  }
  rep->stop = StopKind::JointLimit;
  rep->message = text + "; widen the limits or start the drivers elsewhere (`--on-limit report` goes on)";
  return false;
}

bool JointLimitObserver::Between(const StepContext& ctx, const SystemState& s, AnalysisReport* rep) {
  const std::optional<JointLimitHit> hit = watch_.Check(ctx.ws, ctx.previous, s, ctx.predictor_order);
  watch_.Accept(s);
  if (!hit) return true;
  rep->joint_limits.push_back(*hit);
  if (report_only_) {
    rep->notes.push_back(JointLimitMessage(model_, *hit, rep->rows, false));
    return true;
  }
  rep->stop = StopKind::JointLimit;
  rep->message = JointLimitMessage(model_, *hit, rep->rows, true);
  return false;
}

class ContactObserver : public StepObserver {
 public:
  ContactObserver(const Model& model, const std::vector<int>& needed_bodies, bool stop)
      : watch_(model, needed_bodies), stop_(stop) {}
  bool Observe(const StepContext& ctx, SystemState& s, StepDiagnostics*, AnalysisReport* rep) override {
    return !WatchContacts(&watch_, ctx.ws, ctx.previous, s, ctx.step, ctx.predictor_order, stop_, rep);
  }

 private:
  ContactWatch watch_;
  bool stop_;
};

class RowDelivery : public StepObserver {
 public:
  RowDelivery(const AnalysisOptions& options, const StepCallback& on_step) : options_(options), on_step_(on_step) {}
  bool Observe(const StepContext& ctx, SystemState& s, StepDiagnostics* diag, AnalysisReport* rep) override {
    diag->solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - ctx.started).count();
    UpdateAngleReferences(ctx.ws.system(), &s);
    if (options_.keep_step_diagnostics) rep->steps.push_back(*diag);
    ++rep->rows;
    if (!on_step_(s, *diag)) {
      rep->stop = StopKind::Interrupted;
      rep->message = "stopped by the caller";
      return false;
    }
    if (options_.interrupted && options_.interrupted()) {
      rep->stop = StopKind::Interrupted;
      rep->message = "interrupted";
      return false;
    }
    return true;
  }

 private:
  const AnalysisOptions& options_;
  const StepCallback& on_step_;
};

}  // namespace

std::unique_ptr<StepObserver> MakeForceObserver(const ConstraintSystem& sys, const RowSelection& selection, int order) {
  return std::make_unique<ForceObserver>(sys, selection, order);
}

std::unique_ptr<StepObserver> MakeSensitivityObserver(std::unique_ptr<SensitivitySolver> solver) {
  return std::make_unique<SensitivityObserver>(std::move(solver));
}

std::unique_ptr<StepObserver> MakeJointLimitObserver(const Model& model, const AnalysisOptions& options) {
  if (JointLimitWatch(model).empty()) return nullptr;
  return std::make_unique<JointLimitObserver>(model, options);
}

std::unique_ptr<StepObserver> MakeContactObserver(const Model& model, const std::vector<int>& needed_bodies, bool stop) {
  return std::make_unique<ContactObserver>(model, needed_bodies, stop);
}

std::unique_ptr<StepObserver> MakeRowDelivery(const AnalysisOptions& options, const StepCallback& on_step) {
  return std::make_unique<RowDelivery>(options, on_step);
}

}  // namespace mechkin
