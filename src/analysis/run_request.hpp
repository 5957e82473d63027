// One run request (issue 32, "One run request"): what a driven run computes and
// shows, with its defaults and the single valid range of each field, decided once
// for every front end. The CLI (run, view, range, tolerance, sweep) checks its
// options through RunRequest::IsValid, the Python binding builds a RunRequest, so
// a value is accepted or refused everywhere with the same message.
//
// The policy "forces need accelerations" lives in PlanRun and nowhere else: the
// inverse dynamics reads q̈ (and its rates q⃛), so a run that computes forces solves
// the derivatives to order max(order, 2) while its table shows the derivative
// columns up to the requested order plus the force columns (their "_t" rates from
// order 3, as before). `--order 1` on a file with inertia therefore shows positions,
// velocities and the very forces of an `--order 2` run; no invocation that worked
// before changes its output.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/motion.hpp"

namespace mechkin {

/// Whether a run computes driver efforts, joint reactions and energies.
enum class ForcesChoice {
  Auto,  // when the file has inertia or loads (Model::HasForces)
  On,    // always (zero masses give zero reactions)
  Off,   // never: kinematics only
};

/// What a run does when a joint reaches its limits: stop there (the crossing located),
/// or note it and go on. The CLI's `--on-limit` and Python's `on_limit` (their names
/// in analysis/enum_names.hpp).
enum class LimitAction { Stop, Report };
/// What a run does at a first contact of a clearance output's bodies (`run --on-contact`):
/// note it and go on (the default), or stop there.
enum class ContactAction { Stop, Report };
/// Which rows have their error bounds measured (`run --error-bounds`, Python's
/// error_bounds): those near singular positions and a sample of the others (auto, the
/// default, bound_sampling.hpp), or every row (measured, docs/constraints.md §8, at
/// 1.1–3.7× the time).
enum class ErrorBoundsChoice { Auto, Measured };

struct RunRequest {
  // --- what the table shows ---
  int order = 3;           // highest time derivative shown: 0 position, 1 velocity … 4 snap
  bool si = false;         // SI units (m, rad, N) instead of the file's
  std::optional<std::vector<std::string>> bodies;   // body columns; nullopt: every body
  std::optional<std::vector<std::string>> outputs;  // output columns; nullopt: every output
  ForcesChoice forces = ForcesChoice::Auto;
  std::vector<std::string> sensitivity;  // parameters: adds d(column)/d(parameter) columns
  // --- how it is solved ---
  Formulation formulation = Formulation::Omega;  // rotational unknowns of the derivative solves
  PositionSolver solver = PositionSolver::Newton;
  double tolerance = 1e-10;  // position residual relative to the mechanism size
  int max_iterations = 25;   // Newton iterations per step
  int predictor_order = 3;   // Taylor predictor of the next pose (used up to the solved order)
  bool keep_step_diagnostics = true;  // every row's StepDiagnostics in the report (streaming runs: off)
  bool on_limit_report = false;       // joint limits: note a crossing and go on (default: stop there)
  LimitAction limit_action() const { return on_limit_report ? LimitAction::Report : LimitAction::Stop; }
  void set_limit_action(LimitAction a) { on_limit_report = a == LimitAction::Report; }
  bool on_contact_stop = false;       // clearance outputs: stop at a first contact (default: note it)
  ContactAction contact_action() const { return on_contact_stop ? ContactAction::Stop : ContactAction::Report; }
  void set_contact_action(ContactAction a) { on_contact_stop = a == ContactAction::Stop; }
  ErrorBoundsChoice error_bounds = ErrorBoundsChoice::Auto;  // rows whose bounds are measured
  InterruptPoll interrupted;          // polled between steps and runs: true stops (Interrupted)

  // The ranges (kMinTolerance, kMaxTolerance, order 0..kMaxOrder) and their messages are
  // the solver's (CheckSolverFields, analysis/kinematic_analysis.hpp): one definition.

  /// True when every field is in its range; otherwise false with *why the first problem
  /// ("tol must be a number in [1e-15, 1e-3] ..., not 0.005"). The front ends print *why as is.
  bool IsValid(std::string* why) const;
  /// Order 0..4 and tolerance messages for a value as the user wrote it (CLI text that is
  /// not a number at all); IsValid uses the same words.
  static std::string OrderProblem(const std::string& shown);
  static std::string ToleranceProblem(const std::string& shown);
};

/// A request decided against a model: what the table shows and what the solver computes.
struct RunPlan {
  TableOptions table;        // order = the requested order; forces resolved
  AnalysisOptions analysis;  // order = the solved order (raised for forces), blocks needed
};

/// The derivative order the solver computes for a table of `shown_order` (forces need 2).
int SolvedOrder(int shown_order, bool forces);
/// Whether `request` computes forces on `model` (ForcesChoice::Auto: inertia or loads).
bool ComputesForces(const Model& model, const RunRequest& request);
/// Decides a valid request. Throws std::invalid_argument for a selected body or output
/// the model does not have ("--bodies: no body named 'x'").
RunPlan PlanRun(const Model& model, const RunRequest& request);
/// The solver's part of a plan that the table decides (solved order, forces,
/// sensitivities, the blocks the selection needs), for callers that set the solver's
/// internals themselves (`plan->analysis` keeps its other fields).
void DecideComputation(const Model& model, RunPlan* plan);

/// Runs a request into a Motion: never throws for a mechanism that cannot move as asked
/// (the Motion says why it stopped); throws std::invalid_argument with IsValid's message
/// for an invalid request, or for a selected body or output the model does not have.
Motion RunMotion(const Model& model, const RunRequest& request);
/// Runs a decided plan into a Motion.
Motion RunPlanned(const Model& model, const RunPlan& plan);

}  // namespace mechkin
