#include "cli/commands/tolerance_command.hpp"

#include <sstream>

#include "analysis/enum_names.hpp"
#include "analysis/tolerance.hpp"
#include "cli/commands/load_for_command.hpp"
#include "cli/commands/request_options.hpp"
#include "io/tolerance_report_writer.hpp"

namespace mechkin {

void SetupToleranceCommand(CLI::App& app, ToleranceCommandOptions* o) {
  CLI::App* cmd = app.add_subcommand(
      "tolerance", "Tolerance stack-up of the outputs: worst case and RSS from exact sensitivities, Monte-Carlo check");
  cmd->add_option("file", o->file, "Mechanism file whose parameters declare tolerances")->required();
  cmd->add_option("-o,--output", o->output, "Report file (default: stdout); written atomically");
  cmd->add_option("--format", o->format, "Report format (text, json)")->check(CLI::IsMember(NamesOf<ReportFormat>()));
  AddOrderOption(cmd, &o->request, "Derivative orders of the outputs analysed (default 0: positions)");
  cmd->add_option("--monte-carlo", o->monte_carlo, "Also sample N variants uniformly within the tolerances")
      ->check(CountCheck(kMonteCarloSamples));
  cmd->add_option("--seed", o->seed, "Seed of the Monte-Carlo samples (default 1)");
  cmd->add_option("--threads", o->threads, "Threads for the Monte-Carlo runs (default: all cores)")
      ->check(CLI::Range(0, 4096));
  AddToleranceOption(cmd, &o->request, "Position tolerance of every run (default 1e-10)");
  cmd->add_option("--set", o->set, "Parameter value replacing the file's: NAME=NUMBER (repeatable)");
  AddKeepPartialOption(cmd, &o->keep_partial, "the report of the Monte-Carlo samples finished");
}

int RunToleranceCommand(const ToleranceCommandOptions& o, std::ostream& out, std::ostream& err) {
  ParameterOverrides overrides;
  if (!ParseOverrides(o.set, &overrides, err)) return 2;
  const std::optional<Model> model = LoadForCommand(o.file, err, overrides);
  if (!model) return 1;
  OutputFile file;  // the destination first: a refused or unwritable path fails before the work
  if (!OpenReport(o.output, {o.file}, "tolerance", &file, out, err)) return 1;
  ToleranceOptions options;
  options.request = o.request;
  options.request.interrupted = InstallInterruptPoll(o.keep_partial);
  options.monte_carlo = o.monte_carlo;
  options.seed = o.seed;
  options.threads = o.threads;
  const ToleranceReport report = AnalyzeTolerances(*model, options);
  std::ostringstream text;
  if (o.format == "json") text << ToleranceReportJsonText(report) << "\n";
  else PrintToleranceReport(report, text);
  if (!CommitReport(&file, text.str(), "tolerance", err)) return 1;
  if (report.interrupted) return kInterruptedExit;
  if (!report.ok) err << "mechkin tolerance: " << o.file << ": " << report.message << "\n";
  return report.ok ? 0 : 1;
}

}  // namespace mechkin
