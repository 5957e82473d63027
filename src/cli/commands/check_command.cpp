#include "cli/commands/check_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <memory>

#include "analysis/check_file.hpp"
#include "analysis/enum_names.hpp"
#include "cli/commands/check_files.hpp"
#include "cli/commands/load_for_command.hpp"
#include "io/check_formats.hpp"
#include "io/check_report_writer.hpp"

namespace mechkin {

void SetupCheckCommand(CLI::App& app, CheckOptions* options) {
  CLI::App* cmd = app.add_subcommand("check", "Validate mechanism files; report degrees of freedom and expectations");
  // Required unless --files-from is given: its callback (run before CLI11 checks the
  // requirements) lifts it, so --set still leaves the last positional to the files.
  CLI::Option* files =
      cmd->add_option("files", options->files, "Mechanism files (format v1), or URDF, MJCF, SDFormat, FreeCAD files (imported)")
          ->required();
  cmd->add_option("--format", options->format,
                  "Report format: text, json, jsonl (one line per file as it finishes), sarif (SARIF 2.1.0), "
                  "gcc (file:line:col: error: message)")
      ->check(CLI::IsMember(NamesOf<CheckFormat>()))
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
  cmd->add_option("--files-from", options->files_from, "Also check the files listed in LIST, one a line ('-': stdin)")
      ->each([files](const std::string&) { files->required(false); });
  cmd->add_option("--jobs,-j", options->jobs, "Files checked at once, on threads (default 1)")->check(CLI::Range(1, 1024));
  cmd->add_flag("--sorted", options->sorted, "Report the files in the order given, whatever --jobs");
  cmd->add_option("--shard", options->shard, "i/N: check the files with index = i-1 (mod N), for job arrays");
  cmd->add_option("--timeout", options->timeout,
                  "Seconds a file's check may take; a file over it gets the verdict timeout and the others go on")
      ->check(CLI::PositiveNumber);
  cmd->add_option("-o,--output", options->output,
                  "With --format jsonl: append the lines to OUT, each synced to disk as it is written");
  cmd->add_flag("--resume", options->resume, "With -o: skip the files OUT already holds (after a killed run)");
  cmd->add_flag("--quiet,-q", options->quiet, "No summary on stderr");
}

namespace {

// Where each finished file's report goes, per --format.
class CheckSink {
 public:
  CheckSink(const CheckOptions& o, size_t count, std::ostream& out) : format_(o.format), out_(out) {
    if (format_ == "json" || format_ == "sarif") kept_.resize(count);
  }
  bool OpenOutput(const std::string& path, size_t keep_bytes, std::string* error) {
    lines_ = std::make_unique<SyncedLines>();
    return lines_->Open(path, keep_bytes, error);
  }
  bool Deliver(size_t index, FileCheck&& c, std::string* error) {
    if (format_ == "text") PrintCheckReport(c.report, out_);
    if (format_ == "gcc") PrintGccDiagnostics(c, out_);
    if (format_ == "jsonl" && lines_) return lines_->Append(CheckLineJsonText(c), error);
    if (format_ == "jsonl") out_ << CheckLineJsonText(c) << "\n" << std::flush;
    if (!kept_.empty()) kept_[index] = std::move(c);
    return true;
  }
  /// The reports kept for the end, written; false (with *error) when OUT's lines failed.
  bool Finish(std::string* error) {
    if (lines_ && !lines_->Close(error)) return false;
    if (format_ == "sarif") out_ << CheckSarifText(kept_) << "\n";
    if (format_ != "json") return true;
    std::vector<CheckReport> reports;
    for (FileCheck& c : kept_) reports.push_back(std::move(c.report));
    out_ << CheckReportsJsonText(reports) << "\n";
    return true;
  }

 private:
  std::string format_;
  std::ostream& out_;
  std::vector<FileCheck> kept_;  // json, sarif: every file, written at the end in the list's order
  std::unique_ptr<SyncedLines> lines_;
};

CheckRequest RequestOf(const CheckOptions& o, const ParameterOverrides& overrides,
                       const importers::ImportOptions& foreign) {
  CheckRequest r;
  r.overrides = overrides;
  // Foreign files through the importers (docs/import.md), the same load as run and view.
  r.load_other = [overrides, foreign](const std::string& path) -> std::optional<LoadResult> {
    if (path == "-" || ForeignFormatOf(path) == importers::ForeignFormat::None) return std::nullopt;
    return LoadAnyMechanism(path, overrides, foreign);
  };
  r.branches = o.branches;
  r.restarts = o.restarts;
  r.clearance = o.clearance;
  r.timeout_seconds = o.timeout;
  return r;
}

}  // namespace

int RunCheck(const CheckOptions& options, std::ostream& out, std::ostream& err) {
  if (options.files.empty() && options.files_from.empty()) {  // as CLI11 says it for a required option
    err << "files is required\nRun with --help for more information.\n";
    return 2;
  }
  ParameterOverrides overrides;
  importers::ImportOptions foreign;
  if (!ParseOverrides(options.set, &overrides, err) || !ParseForeignOptions(options.foreign, &foreign, err)) return 2;
  CheckPlan plan;
  if (!PlanCheck(options, &plan, err)) return 2;
  for (const std::string& f : plan.files)
    if (!ForeignOptionsFit(f, foreign, err)) return 2;
  CheckSink sink(options, plan.files.size(), out);
  std::string error;
  const bool to_file = !options.output.empty() && options.output != "-";  // "-o -": the standard output
  if (to_file && !sink.OpenOutput(options.output, plan.keep_bytes, &error)) {
    err << "mechkin check: " << error << "\n";
    return 1;
  }
  CheckTally tally(plan);
  // On a terminal only (a redirected or captured stderr gets the summary alone), and
  // not over reports written to that terminal.
  const bool reports_on_terminal = !to_file && &out == &std::cout && ::isatty(STDOUT_FILENO);
  ProgressLine progress(&err == &std::cerr && ::isatty(STDERR_FILENO) && !reports_on_terminal && !options.quiet &&
                             plan.files.size() > 1,
                         plan.files.size(), "files", err);
  size_t done = 0;
  bool write_failed = false;
  CheckFiles(plan.files, RequestOf(options, overrides, foreign), options.jobs, options.sorted,
             [&](size_t index, FileCheck&& c) {
               tally.Add(plan.files[index], c);
               progress.Update(++done);
               if (sink.Deliver(index, std::move(c), &error)) return true;
               write_failed = true;
               return false;
             });
  progress.Finish();
  write_failed = !sink.Finish(&error) || write_failed;
  if (write_failed) err << "mechkin check: " << error << "\n";
  if (plan.summary && !options.quiet) tally.PrintSummary(options.jobs, err);
  return write_failed ? 1 : tally.ExitCode();
}

}  // namespace mechkin
