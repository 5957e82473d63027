// The speed/accuracy trade of the driven analysis (`mechkin bench`): runs a grid
// of settings, measures time per step and errors against a reference, and
// extracts the Pareto front (time per step vs error).
#pragma once

#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/motion.hpp"

namespace mechkin {

struct BenchSetting {
  PositionSolver solver = PositionSolver::Newton;
  double tolerance = 1e-10;
  int predictor = 3;
  Formulation formulation = Formulation::Omega;
  int steps = 100;
  std::string Describe() const;
};

struct BenchResult {
  BenchSetting setting;
  bool complete = false;
  double us_median = 0, us_min = 0, us_max = 0;  // per step, over repeats (median of each run's steps)
  double iterations = 0;                         // mean Newton iterations per step
  double residual = 0;                           // largest scaled residual
  double error[4] = {0, 0, 0, 0};                // position … jerk, relative to the reference's magnitude
  double worst_error() const;
  bool on_front = false;
};

/// A motion table in SI as column name → values, with its time column.
struct ReferenceTable {
  std::vector<double> t;
  std::map<std::string, std::vector<double>> columns;  // names without units
};

/// Runs `model` with a setting and returns its SI motion (order 3, every column).
Motion RunForBench(const Model& model, const BenchSetting& s);
/// The reference columns of a run, by column name.
ReferenceTable ReferenceFromMotion(const Motion& motion);
/// Reads a table written by `mechkin run --si` (CSV). Throws std::runtime_error.
ReferenceTable ReadReferenceCsv(const std::string& path);

struct BenchOptions {
  bool quick = false;
  int repeats = 3;
};

std::vector<BenchSetting> BenchGrid(const Model& model, const BenchOptions& options);
/// Measures every setting against `reference`; marks the Pareto front.
std::vector<BenchResult> RunBench(const Model& model, const std::vector<BenchSetting>& grid,
                                  const ReferenceTable& reference, const BenchOptions& options);

}  // namespace mechkin
