// Driver-prescribed kinematic analysis (issue: driven analysis): at each time
// step, the position solve Φ(q, t) = 0, then Φ_q q^(k) = RHS_k for k = 1..order
// (velocity ν, acceleration γ, jerk η, snap σ) with one factorization of Φ_q.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/contact_watch.hpp"
#include "analysis/joint_limits.hpp"
#include "analysis/forces.hpp"
#include "analysis/sensitivity.hpp"
#include "analysis/singularity.hpp"
#include "kinematics/workspace.hpp"

namespace mechkin {

/// The inverse dynamics reads q̈: a run that computes forces solves at least this order.
constexpr int kForcesOrder = 2;

/// The single valid range of each solver field and its message, shared by
/// RunRequest::IsValid (what the front ends check) and AnalysisOptions::IsValid.
bool CheckSolverFields(int order, double tolerance, int max_iterations, int predictor_order, bool sensitivities,
                       Formulation formulation, PositionSolver solver, std::string* why);
/// The order / tolerance message for a value as shown to the user ("5", "0.005", "'abc'").
std::string OrderProblem(const std::string& shown);
std::string ToleranceProblem(const std::string& shown);
constexpr double kMinTolerance = 1e-15;  // below: under the round-off of the scaled residual
constexpr double kMaxTolerance = 1e-3;   // above: the branch guard's steps stop being reliable

/// Asked between steps (and between the runs of a sweep or Monte-Carlo): true stops
/// the work as StopKind::Interrupted. The front end decides what it means (the CLI:
/// a SIGINT with --keep-partial; Python: a pending KeyboardInterrupt); it must be
/// cheap and safe to call from every thread. Empty: never interrupted.
using InterruptPoll = std::function<bool()>;

// The solver's settings of one run. Front ends do not fill these: they build a
// RunRequest (analysis/run_request.hpp) whose PlanRun decides them, the solved
// order included (raised for forces).
struct AnalysisOptions {
  int order = 3;                       // highest derivative computed (0..4)
  Formulation formulation = Formulation::Omega;
  PositionSolver solver = PositionSolver::Newton;
  double tolerance = 1e-10;            // scaled residual (relative to the mechanism size)
  int max_iterations = 25;
  int predictor_order = 3;             // Taylor predictor order (≤ order)
  bool modified_newton = true;         // reuse the previous step's factorization while it converges fast
  bool ceres_normalization_residual = false;  // Ceres: pᵀp − 1 residuals instead of the manifold (measured worse)
  bool branch_guard = true;             // sub-step on a det Φ_q sign change or a far jump (off: plain Newton)
  // Every row's error bounds measured (row_error_estimate.hpp), not only near singular
  // positions and on a sample of the other rows (bound_sampling.hpp; docs/constraints.md §8),
  // for 1.1–3.7× the run time (tools/error_bounds_cost.sh).
  bool measure_every_row = false;
  // Bodies whose motion is asked for (table selection); empty = all. When it is a
  // strict subset, the position and derivative solves run block by block along the
  // block-triangular structure and skip the blocks nothing requested depends on.
  std::vector<int> needed_bodies;
  // Keep every row's StepDiagnostics in the report (the CLI streams and keeps none).
  bool keep_step_diagnostics = true;
  // Inverse dynamics along the motion (driver efforts, joint reactions, energy):
  // needs order ≥ 2 (PlanRun raises it); rates with order ≥ 3.
  bool forces = false;
  // Parameters whose sensitivities each row carries (analysis/sensitivity.hpp).
  std::vector<std::string> sensitivity_parameters;
  // Joint limits (analysis/joint_limits.hpp): a crossing is located and noted and the
  // run goes on (`--on-limit report`); false: the run stops there.
  bool on_limit_report = false;
  // Clearance outputs (analysis/contact_watch.hpp): a first contact is located and
  // noted and the run goes on (`--on-contact report`, the default); true: it stops there.
  bool on_contact_stop = false;
  InterruptPoll interrupted;  // polled once per step (empty: never)
  bool IsValid(std::string* error) const;
};

struct StepDiagnostics {
  double t = 0;
  int iterations = 0;
  double residual = 0;             // scaled, active equations
  double set_aside_residual = 0;   // scaled, redundant equations set aside
  double condition = 0;            // estimate of cond(Φ_q)
  // Relative error bounds per derivative order (0 = position), analysis/error_bounds.hpp.
  double error_bound[kMaxOrder + 1] = {0, 0, 0, 0, 0};
  double solve_seconds = 0;        // position + derivative solves of this step
  const ForceResults* forces = nullptr;  // when AnalysisOptions::forces
  const SensitivitySolver* sensitivity = nullptr;  // when AnalysisOptions::sensitivity_parameters
  int substeps_refinements = 0;    // 1 when the step had to be refined into sub-steps
};

/// Why a run ended before its last row.
enum class StopKind { None, Refused, AssemblyFailed, SingularPosition, SolveFailed, Interrupted, JointLimit, Contact };

/// A change of the equations set aside along the motion (redundancy that follows it).
struct Reselection {
  double t = 0;
  std::vector<std::string> set_aside;  // the equations set aside from t on
};

struct AnalysisReport {
  bool complete = false;
  StopKind stop = StopKind::None;
  std::optional<SingularPosition> singular;
  std::optional<LimitOfMotion> limit;     // where the position solve fails: the fold located
  std::vector<JointLimitHit> joint_limits;  // joint limits reached, located (the first stops the run unless reported)
  std::vector<ContactHit> contacts;        // first contacts of clearance outputs' bodies, located
  std::string message;                    // failure explanation (empty on success)
  std::vector<std::string> set_aside;     // redundant equations, by name (at the start)
  std::vector<Reselection> reselections;  // later changes of that set
  std::vector<std::string> notes;         // singular positions the run passed (a unique passage), one line each
  std::vector<std::string> indeterminate_reactions;  // with forces and redundant equations
  std::vector<StepDiagnostics> steps;     // every row's, when options.keep_step_diagnostics
  int rows = 0;                           // rows delivered to the callback
  int assembly_iterations = 0;
  int blocks = 0;          // diagonal blocks of the block-triangular form
  int blocks_solved = 0;   // of those, solved (fewer when the table selection allows)
};

/// Per-step statistics of a run: the median solve time (µs), the mean Newton
/// iterations and the largest residuals (used by `run --stats` and `bench`).
struct StepStatistics {
  double median_us = 0, mean_iterations = 0, max_residual = 0, max_set_aside_residual = 0;
};
StepStatistics SummarizeSteps(const std::vector<StepDiagnostics>& steps);

/// Called after each solved step with the state (pose and derivatives up to the
/// order) and the step's diagnostics. Returning false stops the run (Interrupted).
using StepCallback = std::function<bool(const SystemState&, const StepDiagnostics&)>;

/// Runs the analysis of model.analysis. Never throws for a mechanism that cannot
/// move as asked: the report says why and where it stopped.
/// `on_assembly` (if set) sees the assembled design pose and every pose of the move
/// to the start (no rows: RowEvaluator::Follow keeps angles' turns across it).
using PoseCallback = std::function<void(const SystemState&)>;
AnalysisReport RunKinematicAnalysis(const Model& model, const AnalysisOptions& options, const StepCallback& on_step,
                                    const PoseCallback& on_assembly = {});

}  // namespace mechkin
