#include "analysis/run_request.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "analysis/reduction.hpp"

namespace mechkin {
namespace {

// The names of a selection; an empty name selects nothing (`--bodies ''`: no body columns).
std::vector<std::string> Selection(const std::optional<std::vector<std::string>>& names) {
  std::vector<std::string> out;
  if (names)
    for (const auto& n : *names)
      if (!n.empty()) out.push_back(n);
  return out;
}

}  // namespace

std::string RunRequest::OrderProblem(const std::string& shown) { return mechkin::OrderProblem(shown); }

std::string RunRequest::ToleranceProblem(const std::string& shown) { return mechkin::ToleranceProblem(shown); }

bool RunRequest::IsValid(std::string* why) const {
  // A parameter named twice would give two identical column sets with one header.
  std::set<std::string> seen;
  for (const std::string& p : sensitivity)
    if (!seen.insert(p).second) {
      *why = "sensitivity: parameter '" + p + "' is given twice: name each parameter once";
      return false;
    }
  return CheckSolverFields(order, tolerance, max_iterations, predictor_order, !sensitivity.empty(), formulation,
                           solver, why);
}

int SolvedOrder(int shown_order, bool forces) { return forces ? std::max(shown_order, kForcesOrder) : shown_order; }

bool ComputesForces(const Model& model, const RunRequest& request) {
  return request.forces == ForcesChoice::On || (request.forces == ForcesChoice::Auto && model.HasForces());
}

void DecideComputation(const Model& model, RunPlan* plan) {
  const TableOptions& table = plan->table;
  AnalysisOptions& a = plan->analysis;
  a.order = SolvedOrder(table.order, table.forces);
  a.forces = table.forces;
  a.sensitivity_parameters = table.sensitivity;
  a.needed_bodies.clear();
  if (!table.all_bodies || !table.all_outputs) {
    // Only the bodies the table shows, or that its outputs read, are needed.
    a.needed_bodies = MotionLayout(model, table).NeededBodies(model);
    if (a.needed_bodies.empty()) a.needed_bodies.push_back(-1);  // nothing requested: solve no block
  }
}

RunPlan PlanRun(const Model& model, const RunRequest& r) {
  std::string why;
  if (!r.IsValid(&why)) throw std::invalid_argument(why);
  RunPlan plan;
  TableOptions& t = plan.table;
  t.order = r.order;
  t.si = r.si;
  t.all_bodies = !r.bodies.has_value();
  t.all_outputs = !r.outputs.has_value();
  t.bodies = Selection(r.bodies);
  t.outputs = Selection(r.outputs);
  t.forces = ComputesForces(model, r);
  t.sensitivity = r.sensitivity;
  AnalysisOptions& a = plan.analysis;
  a.formulation = r.formulation;
  a.solver = r.solver;
  a.tolerance = r.tolerance;
  a.max_iterations = r.max_iterations;
  a.predictor_order = r.predictor_order;
  a.keep_step_diagnostics = r.keep_step_diagnostics;
  a.on_limit_report = r.on_limit_report;
  a.on_contact_stop = r.on_contact_stop;
  a.measure_every_row = r.error_bounds == ErrorBoundsChoice::Measured;
  a.interrupted = r.interrupted;
  DecideComputation(model, &plan);
  return plan;
}

Motion RunPlanned(const Model& model, const RunPlan& plan) {
  Motion motion{MotionLayout(model, plan.table)};
  if (model.analysis) motion.mutable_values().reserve(static_cast<size_t>(model.analysis->steps + 1) * motion.cols());
  motion.report = RunIntoSink(model, plan.analysis, motion.layout(), &motion);
  motion.complete = motion.report.complete;
  motion.stop = StopOf(motion.report);
  motion.reductions = ComputeReductions(model, motion);
  return motion;
}

Motion RunMotion(const Model& model, const RunRequest& request) { return RunPlanned(model, PlanRun(model, request)); }

}  // namespace mechkin
