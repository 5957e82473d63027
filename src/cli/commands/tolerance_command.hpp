// `mechkin tolerance FILE`: tolerance stack-up of the outputs along the motion.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/tolerance.hpp"

namespace mechkin {

struct ToleranceCommandOptions {
  std::string file, output, format = "text";
  int monte_carlo = 0, threads = 0;
  unsigned long seed = 1;
  RunRequest request = ToleranceOptions::DefaultRequest();  // --order (default 0), --tol
  std::vector<std::string> set;
  bool keep_partial = false;  // SIGINT writes the samples finished so far (marked partial), exit 130
};

void SetupToleranceCommand(CLI::App& app, ToleranceCommandOptions* options);
int RunToleranceCommand(const ToleranceCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
