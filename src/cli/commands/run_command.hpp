// `mechkin run FILE`: driver-prescribed kinematic analysis, writes a motion table.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/run_request.hpp"
#include "cli/commands/foreign.hpp"

namespace mechkin {

struct RunOptions {
  std::string file;
  std::string output;          // -o; empty = stdout
  std::string format = "csv";  // csv | json
  // --order, --tol, --solver, --formulation, --si (defaults: RunRequest's); the
  // selections and forces below are folded into it by Request().
  RunRequest request;
  bool stats = false;
  bool keep_partial = false;                // SIGINT writes the rows so far (marked partial)
  bool quiet = false;                       // --quiet: no notes on stderr (warnings and errors stay)
  bool forces = false, no_forces = false;   // --forces / --no-forces (default: when the file has inertia or loads)
  std::vector<std::string> bodies;   // --bodies: subset of body columns
  std::vector<std::string> outputs;  // --outputs: subset of output columns
  bool bodies_given = false, outputs_given = false;
  std::vector<std::string> set;          // --set NAME=VALUE: parameter overrides
  std::vector<std::string> sensitivity;  // --sensitivity: parameters to differentiate by
  std::string on_limit = "stop";         // --on-limit stop|report: at a joint's limits
  std::string on_contact = "report";     // --on-contact stop|report: at a clearance output's first contact
  std::string error_bounds = "auto";     // --error-bounds auto|measured: rows whose bounds are measured
  ForeignOptions foreign;                // --drive, --span: for an imported file
  /// The whole request: `request` with the selections, forces and sensitivities.
  RunRequest Request() const;
};

void SetupRunCommand(CLI::App& app, RunOptions* options);
int RunRun(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
