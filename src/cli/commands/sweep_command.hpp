// `mechkin sweep FILE`: many variants of a parametric file, one summary row each;
// `mechkin sweep --merge SHARDS...` joins shard files.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/sweep.hpp"

namespace mechkin {

struct SweepCommandOptions {
  std::vector<std::string> files;  // the mechanism file, or with --merge the shard files
  std::string output, format = "csv", shard;
  std::vector<std::string> grid, set;
  int samples = 0, threads = 0;
  unsigned long seed = 1;
  RunRequest request = SweepOptions::DefaultRequest();  // --order (default 1), --tol
  bool merge = false;
  // Dataset sweeps (issue 31): the columns kept per row, and the folder of the HDF5 files.
  std::vector<std::string> curves;
  std::string out_dir;
  bool keep_partial = false;  // SIGINT writes the variants finished so far (marked partial), exit 130
};

void SetupSweepCommand(CLI::App& app, SweepCommandOptions* options);
/// `sweep --curves COLS --out DIR`: the shard's variants into DIR's dataset file
/// (cli/commands/sweep_dataset.cpp); `sweep --merge --out DIR PARTS...`: one file over them.
int RunDatasetSweep(const SweepCommandOptions& options, const Model& model, const ShardVariants& variants,
                    const SweepOptions& sweep, const ParameterOverrides& overrides, std::ostream& err);
int RunDatasetMerge(const SweepCommandOptions& options, std::ostream& err);
/// The dataset file a sweep writes in `folder`: sweep.h5, or sweep-shard-I-of-N.h5 for --shard I/N.
std::string DatasetFileName(const std::string& folder, int shard, int shards);
int RunSweepCommand(const SweepCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
