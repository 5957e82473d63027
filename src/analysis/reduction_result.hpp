// One reduction's result (docs/format.md "Reductions"): a number per run from a
// column of the motion, in the table's units, with where a min/max occurs and its
// gradient with respect to the table's sensitivity parameters.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace mechkin {

struct ReductionResult {
  std::string name, of;  // the reduction and the column it reads ("transmission", "tip.x")
  ReduceKind kind = ReduceKind::Min;
  std::string unit;      // the column's unit in the table ("" when it has none)
  double value = std::numeric_limits<double>::quiet_NaN();
  // Min/Max: where it occurs (s); At: the time asked.
  double t = std::numeric_limits<double>::quiet_NaN();
  // Min/Max: located between rows on the Hermite interpolant of the column's jets
  // (false: the row's value, the table having no velocity column).
  bool located = false;
  int rows = 0;          // rows it read
  std::string problem;   // non-empty: no value, and why
  bool in_table = true;  // false: the table does not show the column (--outputs), so no value
  // d(value)/d(parameter) per TableOptions::sensitivity (empty without --sensitivity).
  std::vector<std::string> wrt;
  std::vector<double> gradient;
  // Sse: the differences column − target at each target time (row i, column k at
  // i·K + k), in the columns' file units, and their gradients (per residual, per wrt):
  // value = Σ residuals², gradient = 2 Σ r ∂r/∂p (docs/constraints.md §15).
  // Rms with sensitivities: per row √(w_i/T) v_i (w_i its trapezoid weight), so that
  // value² = Σ residuals² (table units).
  std::vector<double> residuals;
  std::vector<std::vector<double>> residual_gradient;
};

/// "min", "max", "rms", "mean", "at", "sse".
const char* ReduceKindName(ReduceKind k);

}  // namespace mechkin
