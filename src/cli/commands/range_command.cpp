#include "cli/commands/range_command.hpp"

#include <sstream>

#include "analysis/enum_names.hpp"
#include "analysis/range.hpp"
#include "cli/commands/load_for_command.hpp"
#include "cli/commands/request_options.hpp"
#include "io/range_report_writer.hpp"

namespace mechkin {

void SetupRangeCommand(CLI::App& app, RangeCommandOptions* o) {
  CLI::App* cmd = app.add_subcommand(
      "range", "Range of motion of each driver from the design pose: limits located, classified, or a full turn");
  cmd->add_option("file", o->file, "Mechanism file")->required();
  cmd->add_option("--driver", o->driver, "Only this driver (default: each in turn, the others held at the design)");
  cmd->add_option("-o,--output", o->output, "Report file (default: stdout); written atomically");
  cmd->add_option("--format", o->format, "Report format (text, json)")->check(CLI::IsMember(NamesOf<ReportFormat>()));
  cmd->add_option("--steps", o->steps, "Steps per direction (a turn, or the search span; default 360)")
      ->check(CountCheck(kRangeSteps));
  cmd->add_option("--span", o->span, "Search span of translations and distances, file units (default 4x the size)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--tol", o->tolerance, "Position tolerance (default 1e-10)")->check(ToleranceCheck());
  cmd->add_option("--set", o->set, "Parameter value replacing the file's: NAME=NUMBER (repeatable)");
  AddKeepPartialOption(cmd, &o->keep_partial, "the drivers done");
}

int RunRangeCommand(const RangeCommandOptions& o, std::ostream& out, std::ostream& err) {
  ParameterOverrides overrides;
  if (!ParseOverrides(o.set, &overrides, err)) return 2;
  const std::optional<Model> model = LoadForCommand(o.file, err, overrides);
  if (!model) return 1;
  OutputFile file;  // the destination first: a refused or unwritable path fails before the work
  if (!OpenReport(o.output, {o.file}, "range", &file, out, err)) return 1;
  RangeOptions options;
  options.driver = o.driver;
  options.steps = o.steps;
  options.span = o.span;
  options.tolerance = o.tolerance;
  options.interrupted = InstallInterruptPoll(o.keep_partial);
  const RangeReport report = CalcRange(*model, options);
  if (!report.ok) {
    err << "mechkin range: " << o.file << ": " << report.message << "\n";
    return 1;
  }
  std::ostringstream text;
  if (o.format == "json") text << RangeReportJsonText(report) << "\n";
  else PrintRangeReport(report, text);
  if (!CommitReport(&file, text.str(), "range", err)) return 1;
  return report.interrupted ? kInterruptedExit : 0;
}

}  // namespace mechkin
