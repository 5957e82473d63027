// Dataset sweeps (issue 31): per variant the full rows of chosen columns (a coupler
// point's x, y over the motion), not one summary row. The variants are a sweep's
// (analysis/sweep.hpp: grid or seeded samples, the same shards); each runs the table
// `mechkin run FILE --set P=V --order K --tol T` computes, so its curves equal that
// run's columns bit for bit. Finished variants are handed to a sink one at a time
// (the dataset writer, io/hdf5_dataset.hpp): nothing is held beyond the variants
// running.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "analysis/sweep.hpp"

namespace mechkin {

/// The status names of sweeps in code order: a dataset stores a variant's status
/// as its index here ("complete" 0, "invalid" 1, ...; docs/datasets.md).
const std::vector<std::string>& SweepStatusNames();
/// The code of a status name (its index in SweepStatusNames()); −1 for none.
int SweepStatusCode(const std::string& status);

/// The columns a dataset keeps, resolved in the variants' table.
struct CurveSelection {
  RunRequest request;                 // every variant's run (the sweep's order, tolerance, solver)
  std::vector<int> columns;           // in the run's table
  std::vector<std::string> names, units;
  int rows = 0;                       // rows of a complete run (the analysis' steps + 1)
};
/// Resolves `names` (column names without units, as `mechkin run` heads them) in the
/// table `request` gives for `model`; false with `error` naming an unknown column and
/// the ones there are.
bool SelectCurves(const Model& model, const RunRequest& request, const std::vector<std::string>& names,
                  CurveSelection* selection, std::string* error);

struct VariantCurves {
  int index = 0;               // in the whole sweep
  int position = 0;            // in the shard (0 .. the shard's count − 1)
  std::vector<double> values;  // the varied parameters, in the shard's order
  std::string status, message;
  int rows = 0;                // rows run (0 for a variant that does not compile)
  double t_stop = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> t;       // the rows' times
  std::vector<double> curves;  // rows × selection columns, row-major
};

/// One variant's curves (what RunCurveSweep does per variant).
VariantCurves RunVariantCurves(const Model& model, const ParameterOverrides& values, const CurveSelection& selection);

/// Runs the shard's variants on `threads` and hands each finished one to `sink`, one
/// at a time (under a lock), in the order they finish; `progress(done)` after each.
/// Returns false when interrupted (request.interrupted) or when the sink returned false.
bool RunCurveSweep(const Model& model, const ShardVariants& shard, const CurveSelection& selection, int threads,
                   const std::function<bool(VariantCurves&&)>& sink,
                   const std::function<void(int done)>& progress = {});

}  // namespace mechkin
