// `mechkin tolerance FILE`: tolerance stack-up of the outputs along the motion.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace mechkin {

struct ToleranceCommandOptions {
  std::string file, output, format = "text";
  int order = 0, monte_carlo = 0, threads = 0;
  unsigned long seed = 1;
  double tolerance = 1e-10;
  std::vector<std::string> set;
};

void SetupToleranceCommand(CLI::App& app, ToleranceCommandOptions* options);
int RunToleranceCommand(const ToleranceCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
