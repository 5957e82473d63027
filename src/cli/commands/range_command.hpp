// `mechkin range FILE`: over which driver values the mechanism assembles.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace mechkin {

struct RangeCommandOptions {
  std::string file, output, format = "text", driver;
  int steps = 360;
  double span = 0, tolerance = 1e-10;
  std::vector<std::string> set;
  bool keep_partial = false;  // SIGINT writes the drivers done so far (marked partial), exit 130
};

void SetupRangeCommand(CLI::App& app, RangeCommandOptions* options);
int RunRangeCommand(const RangeCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
