#include "cli/commands/optimize_command.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

#include "analysis/enum_names.hpp"
#include "cli/commands/load_for_command.hpp"
#include "cli/commands/request_options.hpp"
#include "io/optimize_report_writer.hpp"

namespace mechkin {

void SetupOptimizeCommand(CLI::App& app, OptimizeCommandOptions* o) {
  CLI::App* cmd = app.add_subcommand(
      "optimize", "Minimise a reduction of the motion over parameters (Ceres, exact gradients from the sensitivities)");
  cmd->add_option("file", o->file, "Mechanism file (format v1) with the reductions named")->required();
  cmd->add_option("--vary", o->vary, "Parameters varied (comma-separated); bounds: their min/max")
      ->delimiter(',')
      ->required();
  cmd->add_option("--minimize", o->minimize, "The reduction minimised (its name in the file)")->required();
  cmd->add_option("--subject-to", o->subject_to,
                  "A constraint \"REDUCTION >= NUMBER\" or \"<= NUMBER\" (repeatable; quadratic penalty)");
  cmd->add_option("--starts", o->starts, "Starts: the file's values, then N-1 drawn within the bounds (default 1)")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--seed", o->seed, "Seed of the drawn starts (default 0)");
  cmd->add_option("--max-iterations", o->max_iterations, "Ceres iterations per start (default 100)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("-o,--output", o->output, "The optimised mechanism file (the input with the values replaced)");
  cmd->add_option("--report", o->report, "The report as JSON to this file");
  cmd->add_option("--format", o->format, "The report on stdout: text (default) or json")
      ->check(CLI::IsMember(NamesOf<ReportFormat>()));
  cmd->add_flag("--progress", o->progress,
                "A line per iteration on stderr from the start (default: only once the search has run 2 s)");
  cmd->add_option("--set", o->set, "Parameter value replacing the file's before the search: NAME=NUMBER (repeatable)");
  AddOrderOption(cmd, &o->request, "Derivative order of each run (default 3: min/max located on the degree-7 Hermite)");
  AddToleranceOption(cmd, &o->request, "Position tolerance of each run (default 1e-12)");
}

namespace {

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream b;
  b << in.rdbuf();
  return in ? b.str() : std::string();
}

// Progress lines on stderr: from the first iteration with --progress, else once the
// search has run for 2 s.
std::function<void(const OptimizeProgress&)> ProgressLines(bool always, std::ostream& err) {
  const auto t0 = std::chrono::steady_clock::now();
  return [always, t0, &err](const OptimizeProgress& p) {
    if (!always && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(2)) return;
    std::ostringstream line;
    line.precision(10);
    line << "mechkin optimize: start " << p.start + 1 << "/" << p.starts << " iteration " << p.iteration
         << ": objective " << p.objective << ", best so far " << p.best << "\n";
    err << line.str() << std::flush;
  };
}

// The request from the options; false (printed) for a malformed constraint.
bool BuildRequest(const OptimizeCommandOptions& o, OptimizeRequest* r, std::ostream& err) {
  r->vary = o.vary;
  r->minimize = o.minimize;
  r->starts = o.starts;
  r->seed = o.seed;
  r->max_iterations = o.max_iterations;
  r->run = o.request;
  for (const std::string& text : o.subject_to) {
    OptimizeConstraint c;
    std::string why;
    if (!ParseOptimizeConstraint(text, &c, &why)) {
      err << "mechkin optimize: " << why << "\n";
      return false;
    }
    r->subject_to.push_back(c);
  }
  r->progress = ProgressLines(o.progress, err);
  r->interrupted = InstallInterruptPoll(false);
  return true;
}

// -o: the input's text with the optimised values.
bool WriteOptimisedFile(const OptimizeCommandOptions& o, const OptimizeResult& r, std::ostream& out,
                        std::ostream& err) {
  std::map<std::string, double> values;
  for (size_t k = 0; k < r.vary.size(); ++k) values[r.vary[k]] = r.after[k];
  std::string text, error;
  const std::string original = ReadText(o.file);
  if (original.empty() || !WithParameterValues(original, values, &text, &error)) {
    err << "mechkin optimize: " << o.file << ": " << (error.empty() ? "cannot read the file again" : error) << "\n";
    return false;
  }
  return WriteReport(o.output, {o.file}, text, "optimize", out, err);
}

}  // namespace

int RunOptimizeCommand(const OptimizeCommandOptions& o, std::ostream& out, std::ostream& err) {
  ParameterOverrides overrides;
  if (!ParseOverrides(o.set, &overrides, err)) return 2;
  const std::optional<Model> model = LoadForCommand(o.file, err, overrides);
  if (!model) return 1;
  OptimizeRequest request;
  if (!BuildRequest(o, &request, err)) return 2;
  const std::string problem = OptimizeRequestProblem(*model, request);
  if (!problem.empty()) {
    err << "mechkin optimize: " << o.file << ": " << problem << "\n";
    return 2;
  }
  const OptimizeResult result = Optimize(*model, request);
  std::ostringstream text;
  if (o.format == "json") text << OptimizeReportJsonText(result) << "\n";
  else PrintOptimizeReport(result, text);
  bool written = WriteReport("", {o.file}, text.str(), "optimize", out, err);
  if (!o.report.empty())
    written = WriteReport(o.report, {o.file}, OptimizeReportJsonText(result) + "\n", "optimize", out, err) && written;
  if (result.best_start >= 0 && !o.output.empty()) written = WriteOptimisedFile(o, result, out, err) && written;
  if (result.interrupted) return kInterruptedExit;
  if (!result.message.empty()) err << "mechkin optimize: " << o.file << ": " << result.message << "\n";
  return written && result.converged ? 0 : 1;
}

}  // namespace mechkin
