// Design by objective: the formulation and its reasons are in optimize.hpp; the
// gradient's derivation in docs/constraints.md §15.
#include "analysis/optimize.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>

#include "analysis/load.hpp"
#include "analysis/reduction.hpp"
#include "math/numbers.hpp"

namespace mechkin {

namespace {
constexpr double kFirstPenalty = 1e4, kLastPenalty = 1e10, kFeasible = 1e-6;
}  // namespace

bool ParseOptimizeConstraint(const std::string& text, OptimizeConstraint* out, std::string* why) {
  const size_t ge = text.find(">="), le = text.find("<=");
  const size_t at = ge != std::string::npos ? ge : le;
  auto trim = [](std::string s) {
    const size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
  };
  if (at == std::string::npos || (ge != std::string::npos && le != std::string::npos)) {
    *why = "--subject-to '" + text + "': write REDUCTION >= NUMBER or REDUCTION <= NUMBER";
    return false;
  }
  out->reduction = trim(text.substr(0, at));
  out->at_least = at == ge;
  const std::string number = trim(text.substr(at + 2));
  char* end = nullptr;
  out->bound = std::strtod(number.c_str(), &end);
  if (out->reduction.empty() || number.empty() || *end != '\0' || !std::isfinite(out->bound)) {
    *why = "--subject-to '" + text + "': write REDUCTION >= NUMBER or REDUCTION <= NUMBER (a finite number)";
    return false;
  }
  return true;
}

RunRequest OptimizeRequest::DefaultRun() {
  RunRequest r;
  r.order = 3;
  r.tolerance = 1e-12;
  r.bodies = std::vector<std::string>{""};
  r.forces = ForcesChoice::Off;
  r.keep_step_diagnostics = false;
  return r;
}

namespace {

const Reduction* FindReduction(const Model& m, const std::string& name) {
  for (const Reduction& r : m.reductions)
    if (r.name == name) return &r;
  return nullptr;
}

std::string ReductionNames(const Model& m) {
  std::string s;
  for (const Reduction& r : m.reductions) s += (s.empty() ? "" : ", ") + r.name;
  return s.empty() ? "the file has none: add {\"type\": \"reduction\"} outputs" : "the file's: " + s;
}

}  // namespace

std::string OptimizeRequestProblem(const Model& model, const OptimizeRequest& r) {
  if (r.vary.empty()) return "--vary: name at least one parameter to vary";
  std::set<std::string> seen;
  for (const std::string& p : r.vary) {
    if (!model.FindParameter(p)) return "--vary: the file has no parameter '" + p + "'";
    if (!seen.insert(p).second) return "--vary: parameter '" + p + "' is given twice";
    const Parameter& q = *model.FindParameter(p);
    if (q.min && q.max && *q.min > *q.max) return "--vary: parameter '" + p + "' has min > max";
  }
  if (!FindReduction(model, r.minimize))
    return "--minimize: '" + r.minimize + "' is not a reduction (" + ReductionNames(model) + ")";
  for (const OptimizeConstraint& c : r.subject_to)
    if (!FindReduction(model, c.reduction))
      return "--subject-to: '" + c.reduction + "' is not a reduction (" + ReductionNames(model) + ")";
  if (r.starts < 1 || r.starts > 10000) return "--starts must be a whole number in [1, 10000], not " + std::to_string(r.starts);
  if (r.max_iterations < 1 || r.max_iterations > 100000)
    return "--max-iterations must be a whole number in [1, 100000], not " + std::to_string(r.max_iterations);
  if (!model.analysis) return "the file has no \"analysis\": nothing to run";
  std::string why;
  RunRequest run = r.run;
  run.sensitivity = r.vary;
  if (!run.IsValid(&why)) return why;
  return "";
}

namespace {

// The reduction named in the results of a run, or nullptr.
const ReductionResult* Named(const std::vector<ReductionResult>& results, const std::string& name) {
  for (const ReductionResult& r : results)
    if (r.name == name) return &r;
  return nullptr;
}

// The variant at x with only the reductions the request reads.
LoadResult Variant(const Model& model, const OptimizeRequest& request, const std::vector<double>& x) {
  ParameterOverrides overrides;
  for (size_t k = 0; k < x.size(); ++k) overrides[request.vary[k]] = x[k];
  LoadResult v = WithParameters(model, overrides);
  if (!v.ok()) return v;
  std::set<std::string> needed = {request.minimize};
  for (const OptimizeConstraint& c : request.subject_to) needed.insert(c.reduction);
  std::vector<Reduction> kept;
  for (const Reduction& r : v.model->reductions)
    if (needed.count(r.name)) kept.push_back(r);
  v.model->reductions = std::move(kept);
  return v;
}

}  // namespace

ObjectiveValue EvaluateObjective(const Model& model, const OptimizeRequest& request, const std::vector<double>& x) {
  ObjectiveValue out;
  const LoadResult v = Variant(model, request, x);
  if (!v.ok()) {
    out.problem = v.errors.empty() ? "the variant does not compile" : v.errors.front().ToString();
    return out;
  }
  RunRequest run = request.run;
  run.sensitivity = request.vary;
  run.interrupted = request.interrupted;
  std::optional<Motion> run_motion;
  try {
    run_motion.emplace(RunMotion(*v.model, run));
  } catch (const std::invalid_argument& e) {  // a parameter the sensitivities refuse (it changes the span)
    out.problem = e.what();
    return out;
  }
  const Motion& motion = *run_motion;
  if (!motion.complete) {
    out.problem = "the run stopped: " + motion.stop.Summary();
    return out;
  }
  const ReductionResult* objective = Named(motion.reductions, request.minimize);
  if (!objective || !objective->problem.empty()) {
    out.problem = request.minimize + ": " + (objective ? objective->problem : "no value");
    return out;
  }
  out.value = objective->value;
  out.gradient = objective->gradient;
  out.residuals = objective->residuals;
  out.residual_gradient = objective->residual_gradient;
  for (const OptimizeConstraint& c : request.subject_to) {
    const ReductionResult* r = Named(motion.reductions, c.reduction);
    if (!r || !r->problem.empty()) {
      out.problem = c.reduction + ": " + (r ? r->problem : "no value");
      return out;
    }
    out.constraint_values.push_back(r->value);
    out.constraint_gradients.push_back(r->gradient);
  }
  out.ok = std::isfinite(out.value);
  if (!out.ok) out.problem = request.minimize + " is not a finite number there";
  return out;
}

namespace {

// The scale a constraint's violation is measured in: |v|, or 1 for v = 0.
double ConstraintScale(const OptimizeConstraint& c) { return c.bound != 0 ? std::abs(c.bound) : 1.0; }

// By how much (in its scale) a constraint is violated at a point (≤ 0: it holds).
double Violation(const OptimizeConstraint& c, double value) {
  return (c.at_least ? c.bound - value : value - c.bound) / ConstraintScale(c);
}

// The sum of squares handed to Ceres (optimize.hpp): the objective's residuals, then
// one penalty residual per constraint; every evaluation one run, the last one kept.
class DesignCost : public ceres::CostFunction {
 public:
  DesignCost(const Model& model, const OptimizeRequest& request, ReduceKind kind, OptimizeStart* start)
      : model_(model), request_(request), kind_(kind), start_(start) {
    objective_residuals_ = 1;
    if (kind == ReduceKind::Sse) {
      const Reduction& r = *FindReduction(model, request.minimize);
      objective_residuals_ = static_cast<int>(r.target_t.size() * r.columns.size());
    } else if (kind == ReduceKind::Rms) {
      objective_residuals_ = model.analysis->steps + 1;  // one per row (a run that stops short fails)
    }
    set_num_residuals(objective_residuals_ + static_cast<int>(request.subject_to.size()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(request.vary.size()));
  }
  void set_floor(double floor) { floor_ = floor; }
  void set_penalty(double rho) { penalty_ = rho; }
  // The last two points evaluated are kept: a rejected step's candidate, and the
  // current point the progress reads.
  const ObjectiveValue& At(const std::vector<double>& x) const {
    for (int k = 0; k < 2; ++k)
      if (has_[k] && x_[k] == x) return value_[k];
    std::swap(x_[0], x_[1]);
    std::swap(value_[0], value_[1]);
    has_[1] = has_[0];
    value_[0] = EvaluateObjective(model_, request_, x);
    x_[0] = x;
    has_[0] = true;
    if (!value_[0].ok) Failed(value_[0].problem);
    return value_[0];
  }
  bool Evaluate(double const* const* p, double* residuals, double** jacobians) const override;

 private:
  void Failed(const std::string& why) const {
    ++start_->failed_evaluations;
    if (start_->failures.size() < 5 &&
        std::find(start_->failures.begin(), start_->failures.end(), why) == start_->failures.end())
      start_->failures.push_back(why);
  }
  bool ObjectiveRows(const ObjectiveValue& v, double* residuals, double* jac) const;

  const Model& model_;
  const OptimizeRequest& request_;
  ReduceKind kind_;
  OptimizeStart* start_;
  int objective_residuals_ = 1;
  double floor_ = 0, penalty_ = kFirstPenalty;
  mutable ObjectiveValue value_[2];
  mutable std::vector<double> x_[2];
  mutable bool has_[2] = {false, false};
};

// The objective's residual rows: sse its residuals, rms its rows' √(w/T) v, others √(2(R − L)).
bool DesignCost::ObjectiveRows(const ObjectiveValue& v, double* residuals, double* jac) const {
  const size_t n = request_.vary.size();
  if (kind_ == ReduceKind::Sse || kind_ == ReduceKind::Rms) {
    if (static_cast<int>(v.residuals.size()) != objective_residuals_) return false;
    for (int i = 0; i < objective_residuals_; ++i) {
      residuals[i] = v.residuals[i];
      for (size_t k = 0; jac && k < n; ++k) jac[i * n + k] = v.residual_gradient[i][k];
    }
    return true;
  }
  if (!(v.value > floor_)) return false;
  residuals[0] = std::sqrt(2 * (v.value - floor_));
  for (size_t k = 0; jac && k < n; ++k) jac[k] = v.gradient[k] / residuals[0];
  return true;
}

bool DesignCost::Evaluate(double const* const* p, double* residuals, double** jacobians) const {
  const size_t n = request_.vary.size();
  const ObjectiveValue& v = At(std::vector<double>(p[0], p[0] + n));
  if (!v.ok) return false;
  double* jac = jacobians ? jacobians[0] : nullptr;
  if (!ObjectiveRows(v, residuals, jac)) return false;
  const double root = std::sqrt(penalty_);
  for (size_t c = 0; c < request_.subject_to.size(); ++c) {
    const OptimizeConstraint& con = request_.subject_to[c];
    const double viol = Violation(con, v.constraint_values[c]);
    const int row = objective_residuals_ + static_cast<int>(c);
    residuals[row] = viol > 0 ? root * viol : 0;
    const double slope = viol > 0 ? root / ConstraintScale(con) * (con.at_least ? -1 : 1) : 0;
    for (size_t k = 0; jac && k < n; ++k) jac[row * n + k] = slope * v.constraint_gradients[c][k];
  }
  for (int i = 0; i < num_residuals(); ++i)
    if (!std::isfinite(residuals[i])) return false;
  return true;
}

// Progress after each iteration; aborts when the request is interrupted.
class Progress : public ceres::IterationCallback {
 public:
  Progress(const OptimizeRequest& r, const DesignCost& cost, const std::vector<double>& x, OptimizeProgress base,
           double* best)
      : request_(r), cost_(cost), x_(x), base_(base), best_(best) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (request_.interrupted && request_.interrupted()) return ceres::SOLVER_ABORT;
    const ObjectiveValue& v = cost_.At(x_);  // the iteration's point (Ceres updates x in place)
    bool feasible = v.ok;
    for (size_t c = 0; feasible && c < request_.subject_to.size(); ++c)
      feasible = Violation(request_.subject_to[c], v.constraint_values[c]) <= kFeasible;
    if (feasible && !(v.value >= *best_)) *best_ = v.value;
    if (request_.progress) {
      OptimizeProgress p = base_;
      p.iteration = iterations_ + s.iteration;
      p.objective = v.ok ? v.value : kNaN;
      p.cost = s.cost;
      p.best = *best_;
      request_.progress(p);
    }
    return ceres::SOLVER_CONTINUE;
  }
  void add_iterations(int n) { iterations_ += n; }

 private:
  const OptimizeRequest& request_;
  const DesignCost& cost_;
  const std::vector<double>& x_;
  OptimizeProgress base_;
  double* best_;
  int iterations_ = 0;
};

ceres::Solver::Options SolverOptions(const OptimizeRequest& request) {
  ceres::Solver::Options o;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = request.max_iterations;
  o.function_tolerance = 1e-15;
  o.gradient_tolerance = 1e-16;
  o.parameter_tolerance = 1e-13;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  o.update_state_every_iteration = true;  // the progress reads the iteration's point
  o.num_threads = 1;
  return o;
}

// The parameters' bounds (±inf where the file gives none).
void Bounds(const Model& m, const OptimizeRequest& r, std::vector<double>* lo, std::vector<double>* hi) {
  const double inf = std::numeric_limits<double>::infinity();
  for (const std::string& name : r.vary) {
    const Parameter& p = *m.FindParameter(name);
    lo->push_back(p.min.value_or(-inf));
    hi->push_back(p.max.value_or(inf));
  }
}

}  // namespace

namespace {

struct StartContext {
  const Model& model;
  const OptimizeRequest& request;
  ReduceKind kind;
  const std::vector<double>& lo;
  const std::vector<double>& hi;
  double* best;  // the best feasible objective so far (every start)
  bool* interrupted;
  double gradient_norm = kNaN;  // of the last solve
};

bool Feasible(const OptimizeRequest& r, const ObjectiveValue& v) {
  for (size_t c = 0; c < r.subject_to.size(); ++c)
    if (!(Violation(r.subject_to[c], v.constraint_values[c]) <= kFeasible)) return false;
  return true;
}

// One start from x (clamped into the bounds): Ceres, then more penalty rounds while a
// constraint is violated.
OptimizeStart RunStart(StartContext& ctx, std::vector<double> x, int index) {
  OptimizeStart start;
  for (size_t k = 0; k < x.size(); ++k) x[k] = std::clamp(x[k], ctx.lo[k], ctx.hi[k]);
  start.initial = x;
  DesignCost* cost = new DesignCost(ctx.model, ctx.request, ctx.kind, &start);  // owned by the problem
  const ObjectiveValue first = cost->At(x);
  start.objective_initial = first.ok ? first.value : kNaN;
  if (!first.ok) {
    start.termination = "the start fails: " + first.problem;
    start.final = x;
    start.objective_final = kNaN;
    delete cost;
    return start;
  }
  cost->set_floor(first.value - 1000 * (std::abs(first.value) + 1));
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, x.data());
  for (size_t k = 0; k < x.size(); ++k) {
    if (std::isfinite(ctx.lo[k])) problem.SetParameterLowerBound(x.data(), static_cast<int>(k), ctx.lo[k]);
    if (std::isfinite(ctx.hi[k])) problem.SetParameterUpperBound(x.data(), static_cast<int>(k), ctx.hi[k]);
  }
  OptimizeProgress base;
  base.start = index;
  base.starts = ctx.request.starts;
  Progress progress(ctx.request, *cost, x, base, ctx.best);
  ceres::Solver::Options options = SolverOptions(ctx.request);
  options.callbacks.push_back(&progress);
  bool converged = false;
  for (double rho = kFirstPenalty; rho <= kLastPenalty; rho *= 100) {
    cost->set_penalty(rho);
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    start.iterations += static_cast<int>(summary.iterations.size()) - 1;
    progress.add_iterations(static_cast<int>(summary.iterations.size()) - 1);
    start.termination = summary.message;
    converged = summary.termination_type == ceres::CONVERGENCE;
    if (!summary.iterations.empty()) ctx.gradient_norm = summary.iterations.back().gradient_norm;
    if (summary.termination_type == ceres::USER_FAILURE) *ctx.interrupted = true;
    if (*ctx.interrupted || summary.termination_type == ceres::FAILURE) break;
    if (Feasible(ctx.request, cost->At(x))) break;
  }
  const ObjectiveValue& end = cost->At(x);
  start.final = x;
  start.ok = end.ok;
  start.objective_final = end.ok ? end.value : kNaN;
  start.feasible = end.ok && Feasible(ctx.request, end);
  if (!converged && start.ok && !*ctx.interrupted) start.termination += " (not converged)";
  return start;
}

// A number in [0, 1) from the generator, the same on every platform.
double Uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// The starts: the file's values, then drawn uniformly within the bounds (±20 % of
// the file's value for a parameter without both bounds, 0 ± 0.2 for a value 0).
std::vector<std::vector<double>> Starts(const Model& m, const OptimizeRequest& r, const std::vector<double>& lo,
                                        const std::vector<double>& hi) {
  std::vector<std::vector<double>> out;
  std::vector<double> file;
  for (const std::string& name : r.vary) file.push_back(m.FindParameter(name)->value);
  out.push_back(file);
  std::mt19937_64 rng(r.seed);
  for (int s = 1; s < r.starts; ++s) {
    std::vector<double> x(file.size());
    for (size_t k = 0; k < x.size(); ++k) {
      const double u = Uniform(rng);
      if (std::isfinite(lo[k]) && std::isfinite(hi[k])) x[k] = lo[k] + u * (hi[k] - lo[k]);
      else x[k] = file[k] != 0 ? file[k] * (0.8 + 0.4 * u) : 0.4 * u - 0.2;
    }
    out.push_back(x);
  }
  return out;
}

// The report's figures at the best start's end.
void Describe(const Model& model, const OptimizeRequest& r, const std::vector<double>& lo,
              const std::vector<double>& hi, OptimizeResult* out) {
  const OptimizeStart& best = out->per_start[out->best_start];
  out->after = best.final;
  out->objective_after = best.objective_final;
  out->iterations = best.iterations;
  const ObjectiveValue v = EvaluateObjective(model, r, out->after);
  out->gradient = v.gradient;
  for (size_t k = 0; k < lo.size(); ++k) {
    const double scale = std::max({std::abs(lo[k]), std::abs(hi[k]), std::abs(out->after[k]), 1.0}) * 1e-9;
    const double x = out->after[k];
    if (std::isfinite(lo[k]) && x - lo[k] <= (std::isfinite(hi[k]) ? 1e-9 * (hi[k] - lo[k]) : scale))
      out->active_bounds.push_back(r.vary[k] + " = min");
    else if (std::isfinite(hi[k]) && hi[k] - x <= (std::isfinite(lo[k]) ? 1e-9 * (hi[k] - lo[k]) : scale))
      out->active_bounds.push_back(r.vary[k] + " = max");
  }
  for (size_t c = 0; c < r.subject_to.size() && v.ok; ++c) {
    out->constraint_values.push_back(v.constraint_values[c]);
    out->constraint_active.push_back(Violation(r.subject_to[c], v.constraint_values[c]) >= -kFeasible);
  }
}

}  // namespace

OptimizeResult Optimize(const Model& model, const OptimizeRequest& request) {
  OptimizeResult out;
  out.vary = request.vary;
  out.minimize = request.minimize;
  out.constraints = request.subject_to;
  out.message = OptimizeRequestProblem(model, request);
  if (!out.message.empty()) return out;
  out.ok = true;
  std::vector<double> lo, hi;
  Bounds(model, request, &lo, &hi);
  const std::vector<std::vector<double>> starts = Starts(model, request, lo, hi);
  out.before = starts.front();
  double best = kNaN;
  bool interrupted = false;
  StartContext ctx{model, request, FindReduction(model, request.minimize)->kind, lo, hi, &best, &interrupted};
  double best_gradient_norm = kNaN;
  for (size_t s = 0; s < starts.size() && !interrupted; ++s) {
    out.per_start.push_back(RunStart(ctx, starts[s], static_cast<int>(s)));
    const OptimizeStart& now = out.per_start.back();
    if (s == 0) out.objective_before = now.objective_initial;
    if (!now.ok) continue;
    const OptimizeStart* prior = out.best_start >= 0 ? &out.per_start[out.best_start] : nullptr;
    const bool better = !prior || (now.feasible && !prior->feasible) ||
                        (now.feasible == prior->feasible && now.objective_final < prior->objective_final);
    if (better) out.best_start = static_cast<int>(s), best_gradient_norm = ctx.gradient_norm;
  }
  out.interrupted = interrupted;
  if (out.best_start < 0) {
    out.after = out.before;
    out.objective_after = kNaN;
    out.message = "no start reached an evaluated point (each start's reason is in the report)";
    return out;
  }
  out.gradient_norm = best_gradient_norm;
  Describe(model, request, lo, hi, &out);
  const OptimizeStart& b = out.per_start[out.best_start];
  out.converged = b.feasible && b.termination.find("not converged") == std::string::npos && !interrupted;
  return out;
}

}  // namespace mechkin
