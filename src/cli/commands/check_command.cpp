#include "cli/commands/check_command.hpp"

#include <algorithm>

#include "analysis/check_report.hpp"
#include "analysis/enum_names.hpp"
#include "cli/commands/load_for_command.hpp"
#include "io/check_report_writer.hpp"

namespace mechkin {

void SetupCheckCommand(CLI::App& app, CheckOptions* options) {
  CLI::App* cmd = app.add_subcommand("check", "Validate mechanism files; report degrees of freedom and expectations");
  cmd->add_option("files", options->files, "Mechanism files (format v1), or URDF, MJCF, SDFormat files (imported)")->required();
  cmd->add_option("--format", options->format, "Report format")
      ->check(CLI::IsMember(NamesOf<ReportFormat>()))
      ->default_str("text");
  cmd->add_option("--set", options->set, "Parameter value replacing the file's: NAME=NUMBER (repeatable)");
  cmd->add_flag("--branches", options->branches,
                "Count the assembly branches at the drivers' design values (random restarts of the assembly)");
  cmd->add_option("--restarts", options->restarts, "Random starts for --branches (default 200)")
      ->check(CLI::Range(1, 1000000));
  AddForeignOptions(cmd, &options->foreign);
  cmd->add_flag("--clearance", options->clearance,
                "Sweep the analysis span: each clearance output's (else each unjointed pair of shaped bodies') "
                "smallest clearance and where; the tightest pair first");
}

int RunCheck(const CheckOptions& options, std::ostream& out, std::ostream& err) {
  ParameterOverrides overrides;
  importers::ImportOptions foreign;
  if (!ParseOverrides(options.set, &overrides, err) || !ParseForeignOptions(options.foreign, &foreign, err)) return 2;
  std::vector<CheckReport> reports;
  for (const auto& f : options.files) {
    CheckReport r;
    try {
      if (!ForeignOptionsFit(f, foreign, err)) return 2;
      const LoadResult loaded = LoadAnyMechanism(f, overrides, foreign);
      r = CheckLoaded(f, loaded);
      if (options.branches && loaded.ok()) r.branches = CountBranches(*loaded.model, options.restarts);
      if (options.clearance && loaded.ok() && !r.clearance) AddClearanceCheck(*loaded.model, &r);
    } catch (const std::exception& e) {
      // Defensive: a failure on one file must not take the others' reports with it.
      r = CheckReport{};
      r.file = f;
      r.errors.push_back({"", std::string("the check of this file failed: ") + e.what(), "please report this file"});
    }
    if (options.format == "text") PrintCheckReport(r, out);
    reports.push_back(std::move(r));
  }
  const bool ok = std::all_of(reports.begin(), reports.end(), [](const CheckReport& r) { return r.ok(); });
  if (options.format == "json") out << CheckReportsJsonText(reports) << "\n";
  return ok ? 0 : 1;
}

}  // namespace mechkin
