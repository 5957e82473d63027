// `mechkin run FILE`: driver-prescribed kinematic analysis, writes a motion table.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace mechkin {

struct RunOptions {
  std::string file;
  std::string output;          // -o; empty = stdout
  std::string format = "csv";  // csv | json
  int order = 3;               // highest derivative order computed (0..4)
  std::string formulation = "omega";  // omega | p
  std::string solver = "newton";      // newton | ceres
  double tolerance = 1e-10;           // scaled residual
  bool si = false;
  bool stats = false;
  bool keep_partial = false;
  bool forces = false, no_forces = false;         // SIGINT writes the rows so far (marked partial)
  std::vector<std::string> bodies;   // --bodies: subset of body columns
  std::vector<std::string> outputs;  // --outputs: subset of output columns
  bool bodies_given = false, outputs_given = false;
  std::vector<std::string> set;          // --set NAME=VALUE: parameter overrides
  std::vector<std::string> sensitivity;  // --sensitivity: parameters to differentiate by
};

void SetupRunCommand(CLI::App& app, RunOptions* options);
int RunRun(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
