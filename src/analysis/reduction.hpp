// Reductions of a motion's columns to one number per run (issue 29; docs/format.md
// "Reductions", docs/constraints.md §14): min and max located between rows on the
// exact motion's jets, rms and mean by the trapezoid rule over the rows, the value at
// a time; each with its gradient from the table's sensitivity columns. Rows arrive
// one at a time (the CLI streams its table), so nothing keeps the whole motion.
#pragma once

#include <vector>

#include "analysis/motion.hpp"
#include "analysis/reduction_result.hpp"

namespace mechkin {

class ReductionAccumulator {
 public:
  /// The reductions `which` (the model's, or expect bounds as min/max reductions) of a
  /// table in `layout`.
  ReductionAccumulator(const Model& model, const MotionLayout& layout, std::vector<Reduction> which);
  ReductionAccumulator(const Model& model, const MotionLayout& layout)
      : ReductionAccumulator(model, layout, model.reductions) {}
  ~ReductionAccumulator();
  ReductionAccumulator(const ReductionAccumulator&) = delete;
  ReductionAccumulator& operator=(const ReductionAccumulator&) = delete;

  void Row(const double* row);
  std::vector<ReductionResult> Finish() const;

 private:
  struct State;
  std::vector<State> states_;
};

/// The model's reductions over a whole Motion (RunPlanned fills Motion::reductions so).
std::vector<ReductionResult> ComputeReductions(const Model& model, const Motion& motion);

/// The table column of an output column's value (time-derivative order 0, no
/// sensitivity): a point's coordinate by its component, a single-valued output's
/// series; −1 when the table does not show it.
int ValueColumnOf(const Model& model, const MotionLayout& layout, const OutputColumn& column);

/// Factor from a column's table unit to its unit in the file's units (lengths and
/// angles; 1 for the others): the expect bounds are in file units whatever --si.
double FileUnitFactor(const Model& model, const MotionLayout& layout, int column);

/// The Hermite polynomial of degree 2m + 1 (m = 1 cubic, 2 quintic, 3 septic) on
/// s ∈ [0, 1] through the values and time derivatives d0[0..m] at t0 and d1[0..m] at
/// t0 + h; coefficients c[0..2m+1] in s.
std::vector<double> HermiteCoefficients(const double* d0, const double* d1, int m, double h);
/// Its value (k = 0) or k-th derivative in s at s.
double HermiteEval(const std::vector<double>& c, double s, int k = 0);

}  // namespace mechkin
