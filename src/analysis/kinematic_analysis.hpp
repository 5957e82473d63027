// Driver-prescribed kinematic analysis (issue: driven analysis): at each time
// step, the position solve Φ(q, t) = 0, then Φ_q q^(k) = RHS_k for k = 1..order
// (velocity ν, acceleration γ, jerk η, snap σ) with one factorization of Φ_q.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "constraints/system.hpp"
#include "solvers/position.hpp"

namespace mechkin {

enum class PositionSolver { Newton, Ceres };

struct AnalysisOptions {
  int order = 3;                       // highest derivative computed (0..4)
  Formulation formulation = Formulation::Omega;
  PositionSolver solver = PositionSolver::Newton;
  double tolerance = 1e-10;            // scaled residual (relative to the mechanism size)
  int max_iterations = 25;
  int predictor_order = 3;             // Taylor predictor order (≤ order)
  bool modified_newton = true;         // reuse the previous step's factorization while it converges fast
  bool ceres_normalization_residual = false;  // Ceres: pᵀp − 1 residuals instead of the manifold (measured worse)
  bool branch_guard = true;
  // Bodies whose motion is asked for (table selection); empty = all. When it is a
  // strict subset, the position and derivative solves run block by block along the
  // block-triangular structure and skip the blocks nothing requested depends on.
  std::vector<int> needed_bodies;            // sub-step on a det Φ_q sign change or a far jump (off: plain Newton)
  bool IsValid(std::string* error) const;
};

struct StepDiagnostics {
  double t = 0;
  int iterations = 0;
  double residual = 0;             // scaled, active equations
  double set_aside_residual = 0;   // scaled, redundant equations set aside
  double condition = 0;            // estimate of cond(Φ_q)
  // Relative error bounds per derivative order (0 = position): with κ the condition
  // estimate, r the scaled residual and u the unit round-off,
  //   e_0 = κ·max(r, 4u),   e_k = 8u·κ^k + κ·e_0   (k ≥ 1):
  // round-off of each back-solve is amplified by κ and enters the next order's
  // right-hand side; the position error e_0 perturbs Φ_q itself, costing one more κ.
  // Relative to the magnitude of q^(k) over the motion. Checked against closed forms
  // near a dead centre in tests/extremes/assembly_test.cpp.
  double error_bound[kMaxOrder + 1] = {0, 0, 0, 0, 0};
  double solve_seconds = 0;        // position + derivative solves of this step
  int substeps_refinements = 0;    // 1 when the step had to be refined into sub-steps
};

/// A singular position found between two steps (the sign of det Φ_q flips).
struct SingularPosition {
  double t = 0;                         // located by bisection to 1e-9 of the step
  std::vector<double> driver_values;    // SI, at t
  int joint_mobility = 0;               // 6n − rank of the joints' Jacobian there
  std::vector<std::string> involved;    // equations of the vanishing direction, by name
};

struct AnalysisReport {
  bool complete = false;
  std::optional<SingularPosition> singular;
  std::string message;                    // failure explanation (empty on success)
  std::vector<std::string> set_aside;     // redundant equations, by name
  std::vector<StepDiagnostics> steps;
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
/// order) and the step's diagnostics.
using StepCallback = std::function<void(const SystemState&, const StepDiagnostics&)>;

/// Runs the analysis of model.analysis. Never throws for a mechanism that cannot
/// move as asked: the report says why and where it stopped.
AnalysisReport RunKinematicAnalysis(const Model& model, const AnalysisOptions& options, const StepCallback& on_step);

}  // namespace mechkin
