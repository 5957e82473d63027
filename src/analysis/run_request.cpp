#include "analysis/run_request.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mechkin {
namespace {

// The order at which the inverse dynamics has what it reads (q̈; docs/format.md "Forces").
constexpr int kForcesOrder = 2;

std::string Shown(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// The names of a selection; an empty name selects nothing (`--bodies ''`: no body columns).
std::vector<std::string> Selection(const std::optional<std::vector<std::string>>& names) {
  std::vector<std::string> out;
  if (names)
    for (const auto& n : *names)
      if (!n.empty()) out.push_back(n);
  return out;
}

}  // namespace

std::string RunRequest::OrderProblem(const std::string& shown) {
  return "order must be an integer in 0..4 (0 position, 1 velocity, 2 acceleration, 3 jerk, 4 snap), not " + shown;
}

std::string RunRequest::ToleranceProblem(const std::string& shown) {
  return "tol must be a number in [1e-15, 1e-3] (the position tolerance relative to the mechanism size), not " +
         shown;
}

bool RunRequest::IsValid(std::string* why) const {
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
  if (!sensitivity.empty() && (formulation != Formulation::Omega || solver != PositionSolver::Newton))
    return fail("sensitivities use the default formulation and solver (omega, newton)");
  return true;
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
  DecideComputation(model, &plan);
  return plan;
}

Motion RunPlanned(const Model& model, const RunPlan& plan) {
  Motion motion{MotionLayout(model, plan.table)};
  if (model.analysis) motion.mutable_values().reserve(static_cast<size_t>(model.analysis->steps + 1) * motion.cols());
  motion.report = RunIntoSink(model, plan.analysis, motion.layout(), &motion);
  motion.complete = motion.report.complete;
  motion.stop = StopOf(motion.report);
  return motion;
}

Motion RunMotion(const Model& model, const RunRequest& request) { return RunPlanned(model, PlanRun(model, request)); }

}  // namespace mechkin
