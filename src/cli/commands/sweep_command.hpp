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
  bool keep_partial = false;  // SIGINT writes the variants finished so far (marked partial), exit 130
};

void SetupSweepCommand(CLI::App& app, SweepCommandOptions* options);
int RunSweepCommand(const SweepCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
