// `expect: {"min": {...}, "max": {...}}`: bounds on columns over the run, checked by
// `check` (a run of its own) and by `run` (on the table it writes).
#include <sstream>

#include "analysis/check_report.hpp"
#include "analysis/reduction.hpp"
#include "analysis/run_request.hpp"

namespace mechkin {

std::vector<Reduction> BoundReductions(const Model& m) {
  std::vector<Reduction> out;
  for (const MotionBound& b : m.expect.bounds) {
    Reduction r;
    r.name = std::string(b.is_min ? "min/" : "max/") + b.key;
    r.of = b.key;
    r.column = b.column;
    r.kind = b.is_min ? ReduceKind::Min : ReduceKind::Max;
    out.push_back(r);
  }
  return out;
}

namespace {

// "at t = 0.25 s (crank = 90 deg)": the time, and the unit the bound is in.
std::string BoundWhere(const ReductionResult& r, const std::string& unit) {
  std::ostringstream o;
  o.precision(10);
  o << (r.kind == ReduceKind::Min ? "minimum" : "maximum") << " of " << r.of;
  if (!unit.empty()) o << " [" << unit << "]";
  o << " at t = " << r.t << " s" << (r.located ? "" : " (a row: the table has no velocity column)");
  return o.str();
}

}  // namespace

std::vector<ExpectationResult> BoundExpectations(const Model& m, const MotionLayout& layout,
                                                 const std::vector<ReductionResult>& results,
                                                 const std::string& stopped) {
  std::vector<ExpectationResult> out;
  for (size_t k = 0; k < m.expect.bounds.size() && k < results.size(); ++k) {
    const MotionBound& b = m.expect.bounds[k];
    const ReductionResult& r = results[k];
    ExpectationResult e{r.name, ExpectValue::Of(b.value), {}, false, ""};
    if (!r.problem.empty()) {
      e.where = r.problem;
    } else {
      // The bound is in the file's units; the table may be in SI (--si).
      const int col = ValueColumnOf(m, layout, b.column);
      const double f = col >= 0 ? FileUnitFactor(m, layout, col) : 1;
      const double actual = r.value * f;
      e.actual = ExpectValue::Of(actual);
      e.held = (b.is_min ? actual >= b.value : actual <= b.value) && stopped.empty();
      e.where = BoundWhere(r, f == 1 ? r.unit : "file units") + (stopped.empty() ? "" : "; the run stopped early: " + stopped);
    }
    out.push_back(e);
  }
  return out;
}

void AddMotionBoundCheck(const Model& m, CheckReport* r, const InterruptPoll& stop) {
  if (!r->valid || !m.analysis) return;
  RunRequest request;
  request.order = 3;  // the jets (to the jerk) a Hermite of degree 7 locates the extremum with
  request.bodies = std::vector<std::string>{""};
  request.forces = ForcesChoice::Off;
  request.keep_step_diagnostics = false;
  Model with_bounds = m;
  with_bounds.reductions = BoundReductions(m);
  RunPlan plan = PlanRun(with_bounds, request);
  plan.analysis.interrupted = stop;
  const Motion motion = RunPlanned(with_bounds, plan);
  const std::string stopped = motion.complete ? "" : motion.stop.Summary();
  for (ExpectationResult& e : BoundExpectations(m, motion.layout(), motion.reductions, stopped))
    r->expectations.push_back(std::move(e));
}

}  // namespace mechkin
