// Design sweeps (issue "Parametric designs", item 6): many variants of one
// parametric file, each run through the whole motion and summarised in one row
// (parameters; assembled or not and why; where a limit or singular position
// stopped it; min/max of every output column; the worst conditioning).
//
// Variants are numbered deterministically (a grid in row-major order, the last
// axis fastest; or seeded samples drawn up front), so `--shard i/N` (variants
// with index ≡ i−1 mod N) is the same partition on every machine and merged
// shards equal the unsharded sweep exactly.
#pragma once

#include <functional>
#include <memory>
#include <limits>
#include <string>
#include <vector>

#include "analysis/kinematic_analysis.hpp"
#include "analysis/motion.hpp"
#include "analysis/run_request.hpp"
#include "analysis/load.hpp"

namespace mechkin {

struct GridAxis {
  std::string parameter;
  double from = 0, to = 0;
  int count = 1;
};

/// "crank=90:110:21" → {crank, 90, 110, 21}; false with `error` set when malformed.
bool ParseGridAxis(const std::string& text, GridAxis* axis, std::string* error);
/// The grid's variants, row-major (the last axis varies fastest).
std::vector<ParameterOverrides> GridVariants(const std::vector<GridAxis>& axes);
/// `count` variants uniform within each parameter's min/max (those declaring both), seeded.
/// Empty with `error` set when no parameter declares a range.
std::vector<ParameterOverrides> SampleVariants(const Model& model, int count, unsigned long seed, std::string* error);

class SampleStream;  // sweep.cpp: the seeded samples, drawn as they are asked for

/// One shard's variants alone (index ≡ shard−1 mod shards), so that memory follows
/// the shard's share, not the sweep's size: a grid's or the samples' variants are made
/// when asked for (no list: memory stays flat however many variants a dataset sweep
/// has); only a list given by the caller (Add) is kept.
class ShardVariants {
 public:
  int total = 0;                         // variants in the whole sweep
  std::vector<std::string> parameters;   // the varied parameters (the overrides' keys, in their order)

  size_t size() const { return count_; }
  /// The sweep index of variant k: first + k·stride (the shard's variants are every
  /// stride-th from first).
  int Index(size_t k) const { return first_ + static_cast<int>(k) * stride_; }
  int first() const { return first_; }
  int stride() const { return stride_; }
  /// Variant k (equal to GridVariants'/SampleVariants' entry of Index(k)). Safe to call
  /// from several threads; cheapest in (nearly) ascending k, as ParallelFor asks.
  ParameterOverrides Variant(size_t k) const;
  /// Appends variant `index` of a caller's list (its keys must be `parameters`; the
  /// indices must step evenly: throws std::invalid_argument otherwise).
  void Add(int index, const ParameterOverrides& variant);

 private:
  friend ShardVariants GridShard(const std::vector<GridAxis>& axes, int shard, int shards);
  friend ShardVariants SampleShard(const Model& model, int count, unsigned long seed, int shard, int shards,
                                   std::string* error);
  size_t count_ = 0;
  int first_ = 0, stride_ = 1;
  std::vector<double> listed_;           // Add's variants (size() × parameters.size())
  std::vector<GridAxis> grid_;           // a grid's axes (made from the index)
  std::shared_ptr<SampleStream> samples_;  // the seeded samples
};
/// The grid's variants of shard `shard`/`shards`, each made from its index.
ShardVariants GridShard(const std::vector<GridAxis>& axes, int shard, int shards);
/// The samples of shard `shard`/`shards`: the seeded stream drawn through once and
/// only the shard's kept. Empty with `error` set when no parameter declares a range.
ShardVariants SampleShard(const Model& model, int count, unsigned long seed, int shard, int shards, std::string* error);

struct SweepOptions {
  // Every variant's run: order (derivative orders summarised, default 1), tolerance,
  // solver. The columns are the sweep's (the outputs, or the bodies of a file without
  // any) and no forces, whatever the request's selection and forces say.
  RunRequest request = DefaultRequest();
  int threads = 0;        // 0: all cores
  int shard = 1, shards = 1;  // run the variants with index ≡ shard−1 (mod shards)
  // Called after each finished variant with the count done (one call at a time).
  std::function<void(int done)> progress;
  static RunRequest DefaultRequest() {
    RunRequest r;
    r.order = 1;
    return r;
  }
};

struct VariantSummary {
  int index = 0;
  std::vector<double> values;  // per SweepResult::parameters
  // "complete", "invalid" (the file does not compile: geometry that does not
  // close), "assembly", "refused", "limit", "singular", "failed"
  std::string status;
  std::string message;    // first line of why it is not complete
  int rows = 0;
  double t_stop = std::numeric_limits<double>::quiet_NaN();  // where a run stopped early
  double max_condition = 0, t_max_condition = 0;
  std::vector<double> min, max;  // per SweepResult::columns, over the rows run
};

struct SweepResult {
  std::vector<std::string> parameters;  // varied ones, in the variants' order
  std::vector<std::string> columns;     // summarised column headers ("piston.x [mm]")
  int total = 0;                        // variants in the whole sweep
  int shard = 1, shards = 1;
  std::vector<VariantSummary> variants;  // by index
  // Which sweep this is (the CLI's shards: file hash, variants, overrides, run settings),
  // as JSON text written and compared by `sweep --merge`; empty: not recorded.
  std::string identity;
  // Stopped by options.request.interrupted: `variants` holds the ones that finished
  // (fewer than the shard's share), the report is partial.
  bool interrupted = false;
};

/// Runs the shard's variants on the threads. Throws std::invalid_argument for an
/// invalid options.request (RunRequest::IsValid).
SweepResult RunSweep(const Model& model, const std::vector<ParameterOverrides>& variants, const SweepOptions& options);
/// Runs a shard's variants (options.shard/shards say which shard they are): the
/// result RunSweep gives for the whole list with the same options.
SweepResult RunSweepShard(const Model& model, const ShardVariants& shard, const SweepOptions& options);
/// The run a variant does: the request's order, tolerance and solver; the outputs'
/// columns (no outputs: the bodies'), no forces, no sensitivities.
RunRequest VariantRequest(const Model& model, const RunRequest& request);
/// One variant's summary (what RunSweep does per variant; the Python binding's unit of work).
VariantSummary RunVariant(const Model& model, const ParameterOverrides& values, const SweepOptions& options);
/// A run's status as a sweep names it ("complete", "limit", "singular", ...: VariantSummary::status).
std::string VariantStatus(const Motion& motion);
/// The column headers a sweep of `model` summarises.
std::vector<std::string> SweepColumns(const Model& model, int order);
/// Those columns' descriptors (name and unit apart, as a Motion of the same order has them).
std::vector<ColumnDescriptor> SweepColumnDescriptors(const Model& model, int order);

}  // namespace mechkin
