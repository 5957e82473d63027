// Per-step observers (issue 32, "per-step observers behind one interface"): what
// runs on every accepted step besides the solve — the forces, the sensitivities,
// the joint-limit watch, the row delivery with its interrupt poll — so that the
// stepper (kinematic_analysis.cpp) knows none of them. The stepper keeps only
// what decides the step itself: the predictor, the Newton solve, its refinement,
// the re-selection of redundant rows and the conditioning watch (docs/singularities.md).
#pragma once

#include <chrono>
#include <memory>
#include <vector>

#include "analysis/kinematic_analysis.hpp"
#include "analysis/row_selection.hpp"

namespace mechkin {

class SensitivitySolver;

/// What an observer may read of the step besides its state.
struct StepContext {
  KinematicsWorkspace& ws;         // the step's factorization (the whole system)
  const SystemState& previous;     // the last accepted state
  int step = 0;                    // the row's index (0: the start)
  int predictor_order = 1;         // for locating events between rows
  std::chrono::steady_clock::time_point started;  // when the step's solve began
};

class StepObserver {
 public:
  virtual ~StepObserver() = default;
  /// The step is solved at `s`; the observer may fill `diag` and the report. False
  /// stops the run, with rep->stop and rep->message saying why.
  virtual bool Observe(const StepContext& ctx, SystemState& s, StepDiagnostics* diag, AnalysisReport* rep) = 0;
  /// The rows solved changed (a re-selection of the redundant equations).
  virtual void Reselected(const ConstraintSystem& /*sys*/, const RowSelection& /*selection*/) {}
};

/// Driver efforts, joint reactions and energies (analysis/forces.hpp) into diag.forces.
std::unique_ptr<StepObserver> MakeForceObserver(const ConstraintSystem& sys, const RowSelection& selection, int order);
/// d(state)/d(parameter) per step (analysis/sensitivity.hpp) into diag.sensitivity.
std::unique_ptr<StepObserver> MakeSensitivityObserver(std::unique_ptr<SensitivitySolver> solver);
/// Joint limits: a start outside them, a crossing located between rows; stops the
/// run unless options.on_limit_report (then a note).
std::unique_ptr<StepObserver> MakeJointLimitObserver(const Model& model, const AnalysisOptions& options);
/// Contacts between the clearance outputs' bodies (analysis/contact_watch.hpp): a
/// contact found between rows is located; it stops the run when `stop`, else a note.
std::unique_ptr<StepObserver> MakeContactObserver(const Model& model, const std::vector<int>& needed_bodies, bool stop);
/// Last: the step's time, the angle references, the kept diagnostics, the row to
/// `on_step`, then the interrupt poll.
std::unique_ptr<StepObserver> MakeRowDelivery(const AnalysisOptions& options, const StepCallback& on_step);

}  // namespace mechkin
