// `mechkin optimize FILE --vary P,… --minimize R`: design by objective (issue 29;
// analysis/optimize.hpp; README "Design by objective").
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/optimize.hpp"

namespace mechkin {

struct OptimizeCommandOptions {
  std::string file;
  std::vector<std::string> vary;
  std::string minimize;
  std::vector<std::string> subject_to;  // "R >= v", repeatable
  int starts = 1;
  unsigned long seed = 0;
  int max_iterations = 100;
  std::string output;            // -o: the optimised mechanism file
  std::string report;            // --report: the JSON report
  std::string format = "text";   // the report on stdout: text or json
  bool progress = false;         // --progress: a line per iteration from the first
  std::vector<std::string> set;  // --set NAME=VALUE before optimising
  RunRequest request = OptimizeRequest::DefaultRun();  // --order, --tol
};

void SetupOptimizeCommand(CLI::App& app, OptimizeCommandOptions* options);
/// Exit codes: 0 converged (every constraint holds), 1 an invalid file, no start that
/// ran, not converged or a constraint violated (the optimised file and the report
/// are still written when a start ran), 2 unusable arguments (an unknown parameter or
/// reduction, a malformed --subject-to), 130 interrupted.
int RunOptimizeCommand(const OptimizeCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
