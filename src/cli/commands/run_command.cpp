#include "cli/commands/run_command.hpp"

namespace mechkin {

void SetupRunCommand(CLI::App& app, RunOptions* o) {
  CLI::App* cmd = app.add_subcommand("run", "Driven kinematic analysis: write the motion table");
  cmd->add_option("file", o->file, "Mechanism file (format v1)")->required();
  cmd->add_option("-o,--output", o->output, "Output file (default: stdout)");
  cmd->add_option("--format", o->format, "Table format")->check(CLI::IsMember({"csv", "json"}));
  cmd->add_option("--order", o->order, "Highest time derivative computed")->check(CLI::Range(0, 4));
  cmd->add_option("--formulation", o->formulation, "Rotational coordinates of the derivative solves")
      ->check(CLI::IsMember({"omega", "p"}));
  cmd->add_option("--solver", o->solver, "Position solver")->check(CLI::IsMember({"newton", "ceres"}));
  cmd->add_option("--tol", o->tolerance, "Position tolerance relative to the mechanism size")
      ->check(CLI::Range(1e-15, 1e-2));
  cmd->add_flag("--si", o->si, "Write SI units instead of the file's units");
  cmd->add_flag("--stats", o->stats, "Print timing statistics on stderr");
  cmd->add_option("--bodies", o->bodies, "Bodies whose columns are written")->delimiter(',');
  cmd->add_option("--outputs", o->outputs, "Outputs whose columns are written")->delimiter(',');
}

int RunRun(const RunOptions&, std::ostream&, std::ostream& err) {
  err << "mechkin run: not implemented yet\n";
  return 1;
}

}  // namespace mechkin
