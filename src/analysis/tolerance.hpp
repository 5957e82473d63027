// Tolerance stack-up along the motion (issue "Parametric designs", item 5).
//
// Linear estimate from the exact sensitivities (analysis/sensitivity.hpp): per
// output column and row, with tolerances ±τ_p,
//   worst case  Σ_p |∂o/∂p| τ_p        (every parameter at its limit, signs aligned)
//   RSS         √(Σ_p (∂o/∂p τ_p)²)    (the statistical stack: ±τ read as ±3σ)
// and the parameters ranked by their share at the worst-case row. The Monte-Carlo
// check samples every parameter uniformly within ±τ (seeded, reproducible), runs
// each variant and reports the largest deviation from the nominal motion seen and
// the largest standard deviation; for uniform sampling the linear theory gives
// std = RSS/√3 and max → worst case, so the two methods check each other.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/motion.hpp"
#include "analysis/parallel.hpp"
#include "analysis/run_request.hpp"

namespace mechkin {

struct ToleranceOptions {
  // Every run's request: order (derivative orders of the outputs analysed, default
  // 0), tolerance, solver; the columns are the outputs' (the bodies' without any),
  // no forces, and the sensitivities are the toleranced parameters.
  RunRequest request = DefaultRequest();
  int monte_carlo = 0;       // samples (0: linear estimate only)
  unsigned long seed = 1;
  int threads = 0;           // 0: all cores
  static RunRequest DefaultRequest() {
    RunRequest r;
    r.order = 0;
    r.keep_step_diagnostics = false;
    return r;
  }
};

struct ToleranceColumn {
  std::string name, unit;
  // Why the column has no stack-up (a velocity ratio at order 0: no velocities);
  // empty when it has one. Such a column carries no numbers.
  std::string not_computed;
  std::vector<double> worst_case, rss;  // per row
  double max_worst_case = 0, t_worst_case = 0, max_rss = 0, t_rss = 0;
  std::vector<std::pair<std::string, double>> contributions;  // |∂o/∂p| τ_p at the worst-case row, largest first
  // Monte-Carlo (when samples > 0)
  double mc_max_deviation = 0, t_mc_max = 0, mc_max_std = 0, t_mc_std = 0;
};

struct ToleranceReport {
  bool ok = false;
  std::string message;  // why not, when !ok
  std::vector<std::string> parameters;
  std::vector<double> tolerances;
  std::vector<double> t;  // the rows' times
  std::vector<ToleranceColumn> columns;
  int samples = 0, failed_samples = 0;  // Monte-Carlo variants run / that did not complete
  unsigned long seed = 0;
  // Stopped by options.request.interrupted: the Monte-Carlo figures are those of the
  // samples that finished (samples + failed_samples < the N asked for), or — before
  // the nominal run completed — no report (ok false).
  bool interrupted = false;
};

/// The stack-up over the parameters that declare a tolerance (an invalid
/// options.request: ok false with IsValid's message).
ToleranceReport AnalyzeTolerances(const Model& model, const ToleranceOptions& options);

}  // namespace mechkin
