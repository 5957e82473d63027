// Design by objective (issue 29; docs/format.md "Reductions", "Targets"; README
// "Design by objective"): minimise a reduction of the motion over some of the file's
// parameters, with Ceres and the exact gradient from the reductions' parameter
// gradients (one run with sensitivities per evaluation, docs/constraints.md §15).
//
// The problem handed to Ceres (ceres::Problem, Levenberg–Marquardt, the parameters'
// min/max as its bounds) is a sum of squares, ½ Σ rᵢ²:
//   - an "sse" objective: its residuals (column − target at each target time), so
//     the cost is ½ sse and Gauss–Newton converges quadratically on a zero-residual fit;
//   - an "rms" objective: one residual per row, √(wᵢ/T) vᵢ with wᵢ the row's trapezoid
//     weight, whose squares sum to rms² exactly (the same minimiser; Gauss–Newton);
//   - any other (min, max, mean, at): the single residual √(2 (R − L)), so the cost is
//     R − L exactly; L = R₀ − 1000 (|R₀| + 1) is fixed per start (a step below L is a
//     failed evaluation: Ceres shrinks it);
//   - each constraint "R ≥ v" (≤ v) a residual √ρ · max(0, v − R)/s (s = |v|, 1 when
//     v = 0): a quadratic penalty, ρ = 1e4 first, × 100 (up to 1e10) while a
//     constraint is still violated by more than 1e-6 s after the solve.
// A variant that does not compile, does not assemble, or whose run stops (a joint
// limit, a singular position) is a failed evaluation: the cost function returns
// false, Ceres shrinks the step, and the start's report counts it with the reason.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "analysis/run_request.hpp"

namespace mechkin {

/// `--subject-to "R >= v"`: the reduction R at least (or at most) v.
struct OptimizeConstraint {
  std::string reduction;
  bool at_least = true;  // ">=" (false: "<=")
  double bound = 0;
};

/// Reads "R >= v" / "R <= v"; false with *why for anything else.
bool ParseOptimizeConstraint(const std::string& text, OptimizeConstraint* out, std::string* why);

/// One iteration of one start, for progress lines.
struct OptimizeProgress {
  int start = 0, starts = 1, iteration = 0;
  double objective = 0;  // the reduction minimised at the iteration's point
  double cost = 0;       // Ceres' cost (objective term + penalties)
  double best = 0;       // the best objective of a feasible point so far (NaN: none yet)
};

struct OptimizeRequest {
  std::vector<std::string> vary;  // parameters varied (each a parameter of the file)
  std::string minimize;           // a reduction of the file
  std::vector<OptimizeConstraint> subject_to;
  int starts = 1;                 // the file's values, then starts − 1 drawn (seeded)
  unsigned long seed = 0;
  int max_iterations = 100;       // Ceres iterations per start (per penalty round)
  RunRequest run = DefaultRun();  // each evaluation's run (sensitivities set by Optimize)
  std::function<void(const OptimizeProgress&)> progress;  // called after every iteration
  InterruptPoll interrupted;      // true: stop after the current iteration
  /// The run every evaluation makes: order 3 (min/max located on the degree-7
  /// Hermite), tolerance 1e-12, no body columns, no forces.
  static RunRequest DefaultRun();
};

/// The objective and its gradient at one point (Model::objective/gradient in Python).
struct ObjectiveValue {
  bool ok = false;
  std::string problem;            // !ok: why (the variant's error, where the run stopped)
  double value = 0;               // the reduction
  std::vector<double> gradient;   // d value / d vary[k]
  std::vector<double> residuals;  // sse: its residuals
  std::vector<std::vector<double>> residual_gradient;
  std::vector<double> constraint_values;  // per OptimizeRequest::subject_to
  std::vector<std::vector<double>> constraint_gradients;
};

/// Evaluates `request.minimize` and the constraints for the parameter values `x`
/// (in `request.vary`'s order): the variant compiled from the model's spec
/// (WithParameters), one run with sensitivities to `vary`. Never throws for a
/// variant that fails: ok = false with the reason.
ObjectiveValue EvaluateObjective(const Model& model, const OptimizeRequest& request, const std::vector<double>& x);

/// What one start did.
struct OptimizeStart {
  std::vector<double> initial, final;
  double objective_initial = 0, objective_final = 0;  // NaN when not evaluated
  int iterations = 0;
  int failed_evaluations = 0;             // variants that failed during the search
  std::vector<std::string> failures;      // their distinct reasons (at most 5)
  std::string termination;                // Ceres' message, or why the start failed
  bool ok = false;                        // the start ended at an evaluated point
  bool feasible = false;                  // every constraint holds there (to 1e-6 of its scale)
};

struct OptimizeResult {
  bool ok = false;          // a request that could be run (else `message` says why)
  std::string message;
  bool converged = false;   // the best start ended feasible and Ceres reported convergence
  bool interrupted = false;
  std::vector<std::string> vary;
  std::vector<double> before, after;           // the parameters (file units)
  double objective_before = 0, objective_after = 0;
  std::vector<double> gradient;  // of the objective at `after`
  double gradient_norm = 0;      // Ceres' projected gradient norm of the cost at the end
  int iterations = 0;            // of the best start
  int best_start = -1;
  std::vector<std::string> active_bounds;  // "a = min", "c = max" at `after`
  std::vector<OptimizeConstraint> constraints;
  std::vector<double> constraint_values;  // at `after`
  std::vector<bool> constraint_active;    // within 1e-6 of its bound (or violated)
  std::vector<OptimizeStart> per_start;
  std::string minimize;
};

/// Checks the request against the model (names, bounds, counts); "" when valid.
std::string OptimizeRequestProblem(const Model& model, const OptimizeRequest& request);

/// Minimises: never throws for a variant that fails; an invalid request gives
/// ok = false with the message.
OptimizeResult Optimize(const Model& model, const OptimizeRequest& request);

}  // namespace mechkin
