#include "cli/commands/run_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "analysis/enum_names.hpp"
#include "analysis/check_report.hpp"
#include "analysis/motion.hpp"
#include "analysis/reduction.hpp"
#include "cli/commands/load_for_command.hpp"
#include "cli/commands/request_options.hpp"
#include "io/async_sink.hpp"
#include "io/check_report_writer.hpp"
#include "io/interrupt.hpp"
#include "io/table_writer.hpp"
#include "mobility/grubler.hpp"

namespace mechkin {

void SetupRunCommand(CLI::App& app, RunOptions* o) {
  CLI::App* cmd = app.add_subcommand("run", "Driven kinematic analysis: write the motion table");
  cmd->add_option("file", o->file, "Mechanism file (format v1)")->required();
  cmd->add_option("-o,--output", o->output, "Output file (default: stdout); written atomically");
  cmd->add_option("--format", o->format, "Table format (csv, json)")->check(CLI::IsMember(NamesOf<TableFormat>()));
  AddOrderOption(cmd, &o->request, "Highest time derivative shown: 0 position ... 4 snap (default 3)");
  AddFormulationOption(cmd, &o->request);
  AddSolverOption(cmd, &o->request);
  AddToleranceOption(cmd, &o->request, "Position tolerance relative to the mechanism size (default 1e-10)");
  cmd->add_flag("--forces", o->forces,
                "Also compute driver efforts, joint reactions and energies (default when the file has inertia or "
                "loads; solved with accelerations whatever --order shows)");
  cmd->add_flag("--no-forces", o->no_forces, "Kinematics only, even when the file has inertia or loads");
  cmd->add_flag("--keep-partial", o->keep_partial,
                "On Ctrl-C (SIGINT) write the rows computed so far as a partial table instead of nothing");
  cmd->add_flag("--si", o->request.si, "Write SI units (m, rad) instead of the file's units");
  cmd->add_option("--on-limit", o->on_limit,
                  "At a joint's limits (\"limits\" in the file): stop (default; the crossing located) or report "
                  "(note it on stderr and go on)")
      ->check(CLI::IsMember(NamesOf<LimitAction>()));
  cmd->add_option("--on-contact", o->on_contact,
                  "Where the bodies of a clearance output come into contact: report (default; the first contact "
                  "located and noted on stderr) or stop (the run stops there)")
      ->check(CLI::IsMember(NamesOf<ContactAction>()));
  cmd->add_option("--error-bounds", o->error_bounds,
                  "Rows whose error_bound columns are measured: auto (default; near singular positions and a sample "
                  "of the others, which raises the condition estimate's bounds where they fall short) or measured "
                  "(every row, 1.1-3.7x the time)")
      ->check(CLI::IsMember(NamesOf<ErrorBoundsChoice>()));
  cmd->add_flag("--stats", o->stats, "Print timing statistics on stderr");
  cmd->add_flag("--quiet", o->quiet,
                "No notes on stderr: redundant equations set aside, undetermined reactions, singular passages "
                "(warnings and errors still print)");
  cmd->add_option("--bodies", o->bodies, "Bodies whose columns are written (comma-separated; none: '')")->delimiter(',');
  cmd->add_option("--outputs", o->outputs, "Outputs whose columns are written (comma-separated)")->delimiter(',');
  cmd->add_option("--set", o->set, "Parameter value replacing the file's: NAME=NUMBER (repeatable)");
  cmd->add_option("--sensitivity", o->sensitivity,
                  "Parameters (comma-separated): adds d(column)/d(parameter) for every body and output column")
      ->delimiter(',');
  AddForeignOptions(cmd, &o->foreign);
  cmd->callback([o, cmd] {
    o->bodies_given = cmd->count("--bodies") > 0;
    o->outputs_given = cmd->count("--outputs") > 0;
  });
}

RunRequest RunOptions::Request() const {
  RunRequest r = request;
  if (bodies_given) r.bodies = bodies;
  if (outputs_given) r.outputs = outputs;
  r.forces = no_forces ? ForcesChoice::Off : forces ? ForcesChoice::On : ForcesChoice::Auto;
  r.sensitivity = sensitivity;
  LimitAction at_limit = LimitAction::Stop;
  Parse(on_limit, &at_limit);  // CLI11 admitted only NamesOf<LimitAction>()
  r.set_limit_action(at_limit);
  ContactAction at_contact = ContactAction::Report;
  Parse(on_contact, &at_contact);  // CLI11 admitted only NamesOf<ContactAction>()
  r.set_contact_action(at_contact);
  Parse(error_bounds, &r.error_bounds);  // CLI11 admitted only NamesOf<ErrorBoundsChoice>()
  r.keep_step_diagnostics = false;  // streamed: the table's diagnostic columns carry them
  return r;
}

namespace {

// Progress on a terminal's stderr for runs longer than a second.
class ProgressBar {
 public:
  ProgressBar(std::ostream& err, int total) : err_(err), total_(total), tty_(::isatty(2)) {}
  void Row() {
    ++done_;
    if (!tty_) return;
    const auto now = Clock::now();
    if (now - start_ > std::chrono::seconds(1) && now - last_draw_ > std::chrono::milliseconds(200)) {
      last_draw_ = now;
      const int pct = total_ ? static_cast<int>(100LL * done_ / total_) : 0;
      err_ << "\r[" << std::string(pct / 5, '#') << std::string(20 - pct / 5, ' ') << "] " << pct << "% " << std::flush;
    }
  }
  void Clear() {
    if (tty_ && Clock::now() - start_ > std::chrono::seconds(1)) err_ << "\r" << std::string(40, ' ') << "\r";
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::ostream& err_;
  int total_, done_ = 0;
  bool tty_;
  Clock::time_point start_ = Clock::now(), last_draw_ = start_;
};

// Loud, not quiet: the first row whose error bound exceeds 1e-4 for some
// derivative order (the 4th digit may be wrong), per order. Quieter, once per
// order: the time span where the bound exceeds 10× the tolerance although the step
// solved to the residual the derivatives need (the conditioning costs the digits).
class ConditioningWatch {
 public:
  ConditioningWatch(int order, double tolerance) : order_(order), tolerance_(tolerance) {}
  void Row(const StepDiagnostics& d) {
    for (int k = 0; k <= order_; ++k) {
      if (d.error_bound[k] > 1e-4 && !seen_[k]) { seen_[k] = true; first_t_[k] = d.t; first_condition_[k] = d.condition; }
      if (d.error_bound[k] > 10 * tolerance_) {
        if (!above_[k]) { above_[k] = true; above_from_[k] = d.t; }
        above_to_[k] = d.t;
      }
      worst_[k] = std::max(worst_[k], d.error_bound[k]);
    }
  }
  void Report(std::ostream& err, bool notes) const {
    static const char* kOrderName[] = {"position", "velocity", "acceleration", "jerk", "snap"};
    for (int k = 0; k <= order_; ++k)
      if (seen_[k])
        err << "mechkin run: warning: " << kOrderName[k] << " is ill-conditioned from t = " << first_t_[k]
            << " s (condition estimate " << first_condition_[k] << "; relative error bound up to " << worst_[k]
            << "): a singular position is near; see the error_bound columns\n";
      else if (above_[k] && notes)
        err << "mechkin run: note: the " << kOrderName[k] << " error bound exceeds 10 x --tol " << tolerance_
            << " from t = " << above_from_[k] << " to " << above_to_[k] << " s (up to " << worst_[k]
            << "): solved to the residual it needs, the mechanism's conditioning still costs digits there;"
               " see the error_bound columns\n";
  }

 private:
  int order_;
  double tolerance_;
  bool seen_[kMaxOrder + 1] = {false, false, false, false, false};
  bool above_[kMaxOrder + 1] = {false, false, false, false, false};
  double first_t_[kMaxOrder + 1] = {0, 0, 0, 0, 0}, first_condition_[kMaxOrder + 1] = {0, 0, 0, 0, 0};
  double above_from_[kMaxOrder + 1] = {0, 0, 0, 0, 0}, above_to_[kMaxOrder + 1] = {0, 0, 0, 0, 0};
  double worst_[kMaxOrder + 1] = {0, 0, 0, 0, 0};
};
// The equations set aside at the start and their changes along the motion.
// Large overconstrained models set aside thousands of rows: name the first ones, count the rest.
void ReportSetAside(const AnalysisReport& rep, std::ostream& err) {
  constexpr size_t kListedSetAside = 20;
  for (size_t k = 0; k < rep.set_aside.size() && k < kListedSetAside; ++k)
    err << "mechkin run: redundant equation set aside: " << rep.set_aside[k] << "\n";
  if (rep.set_aside.size() > kListedSetAside)
    err << "mechkin run: ... and " << rep.set_aside.size() - kListedSetAside
        << " more redundant equations set aside (mechkin check lists them all)\n";
  // Redundancy that follows the motion: each change of the set-aside equations.
  for (size_t k = 0; k < rep.reselections.size() && k < kListedSetAside; ++k) {
    const Reselection& r = rep.reselections[k];
    err << "mechkin run: at t = " << r.t << " s the equations set aside became the better-conditioned set:";
    for (size_t i = 0; i < r.set_aside.size() && i < 6; ++i) err << (i ? "; " : " ") << r.set_aside[i];
    if (r.set_aside.size() > 6) err << "; ... (" << r.set_aside.size() << " in all)";
    err << "\n";
  }
  if (rep.reselections.size() > kListedSetAside)
    err << "mechkin run: ... and " << rep.reselections.size() - kListedSetAside << " more re-selections\n";
}

// A planar file whose planar count equals its drivers (the run is fully driven, so
// mobility = drivers = planar count) has no redundancy in its plane: every equation
// set aside is one of the out-of-plane equations each planar loop repeats, which
// `mechkin check` reports once; a run does not repeat them.
bool OnlyOutOfPlaneRedundancy(const Model& model) {
  const std::optional<PlanarStructure> planar = FindPlanarStructure(model);
  return planar && planar->count == static_cast<int>(model.drivers.size());
}

void PrintNotes(const RunOptions& o, const Model& model, const AnalysisReport& rep, const ConditioningWatch& watch,
                std::ostream& err) {
  if (o.quiet) {
    watch.Report(err, false);
    return;
  }
  if (!OnlyOutOfPlaneRedundancy(model)) ReportSetAside(rep, err);
  if (!rep.indeterminate_reactions.empty()) {
    err << "mechkin run: overconstrained: these reaction components are not determined by the motion and the loads "
           "(the table gives the minimum-norm solution; driver efforts are exact); make the joints determinate as "
           "`mechkin check` suggests:\n";
    for (const auto& r : rep.indeterminate_reactions) err << "    " << r << "\n";
  }
  watch.Report(err, true);
  for (const std::string& passed : rep.notes) err << "mechkin run: note: " << passed << "\n";
}

void PrintStats(const AnalysisReport& rep, const std::vector<StepDiagnostics>& steps, std::ostream& err) {
  const StepStatistics st = SummarizeSteps(steps);
  char line[160];
  std::snprintf(line, sizeof line, "per step: %.3f us solve, %.3f Newton iterations", st.median_us, st.mean_iterations);
  err << "steps: " << steps.size() << ", blocks: " << rep.blocks << " (solved: " << rep.blocks_solved << ")"
      << ", assembly iterations: " << rep.assembly_iterations << ", set-aside equations: " << rep.set_aside.size()
      << " (largest scaled residual " << st.max_set_aside_residual << ")\n"
      << line << "\n";
}

// The request decided against the model, or false with the reason on `err`.
bool PlanFor(const RunOptions& o, const Model& model, RunPlan* plan, std::ostream& err) {
  const RunRequest request = o.Request();
  std::string why;
  if (!request.IsValid(&why)) {
    err << "mechkin run: " << why << "\n";
    return false;
  }
  for (const auto& p : request.sensitivity)
    if (!model.FindParameter(p)) {
      err << "mechkin run: --sensitivity: no parameter '" << p << "' in " << o.file << "\n";
      return false;
    }
  try {
    *plan = PlanRun(model, request);
  } catch (const std::exception& e) {
    err << "mechkin run: " << e.what() << "\n";
    return false;
  }
  return true;
}

// The file's reductions on stderr, one line each (the JSON table carries them too).
void PrintReductions(const std::vector<ReductionResult>& results, std::ostream& err) {
  for (const ReductionResult& r : results) {
    std::ostringstream line;
    line.precision(12);
    line << "mechkin run: " << r.name << " = " << ReduceKindName(r.kind) << " of " << r.of;
    if (!r.problem.empty()) {
      err << line.str() << ": not computed: " << r.problem << "\n";
      continue;
    }
    line << ": " << r.value << (r.unit.empty() ? "" : " " + r.unit);
    if (r.kind == ReduceKind::Min || r.kind == ReduceKind::Max || r.kind == ReduceKind::At)
      line << " at t = " << r.t << " s";
    if (r.kind == ReduceKind::Sse) line << " (" << r.residuals.size() << " residuals against the targets)";
    for (size_t k = 0; k < r.wrt.size(); ++k) line << (k ? ", " : "; ") << "d/d(" << r.wrt[k] << ") = " << r.gradient[k];
    err << line.str() << "\n";
  }
}

// expect "min"/"max" on the table's rows: each failure on stderr, as `check` prints it.
bool BoundsHeld(const Model& model, const MotionLayout& layout, const ReductionAccumulator& bounds,
                const std::string& stopped, const std::string& file, std::ostream& err) {
  bool held = true;
  const std::vector<ReductionResult> results = bounds.Finish();
  const std::vector<ExpectationResult> checked = BoundExpectations(model, layout, results, stopped);
  for (size_t k = 0; k < checked.size(); ++k) {
    const ExpectationResult& e = checked[k];
    if (e.held) continue;
    if (!results[k].in_table) {  // `--outputs` left it out: `check` checks it
      err << "mechkin run: note: expect " << e.key << " not checked: " << results[k].problem << "\n";
      continue;
    }
    held = false;
    err << "mechkin run: " << file << ": " << ExpectationLine(e) << "\n";
  }
  return held;
}

}  // namespace

int RunRun(const RunOptions& o, std::ostream& out, std::ostream& err) {
  ParameterOverrides overrides;
  importers::ImportOptions foreign;
  if (!ParseOverrides(o.set, &overrides, err) || !ParseForeignOptions(o.foreign, &foreign, err)) return 2;
  const std::optional<Model> loaded = LoadForCommand(o.file, err, overrides, foreign);
  if (!loaded || !ForeignHasDrives(o.file, foreign, *loaded, "run", err)) return 1;
  const Model& model = *loaded;
  RunPlan plan;
  if (!PlanFor(o, model, &plan, err)) return 2;
  const auto layout = std::make_unique<MotionLayout>(model, plan.table);
  InstallInterruptHandlers(o.keep_partial);
  // The destination first: a path that cannot be written fails before the analysis.
  OutputFile file;
  std::string why;
  if (!file.Open(o.output, {o.file}, &why, &out)) {
    err << "mechkin run: " << why << "\n";
    return 1;
  }
  TableFormat format = TableFormat::Csv;
  Parse(o.format, &format);
  TableWriter writer(*layout, format, &file);
  AsyncRowSink rows_out(&writer, layout->size());
  RowEvaluator eval(model, *layout);
  std::vector<double> row(layout->size());
  ProgressBar progress(err, model.analysis ? model.analysis->steps + 1 : 0);
  ConditioningWatch watch(plan.analysis.order, plan.analysis.tolerance);
  std::vector<StepDiagnostics> steps;
  ReductionAccumulator reductions(model, *layout), bounds(model, *layout, BoundReductions(model));
  const AnalysisReport rep = RunKinematicAnalysis(model, plan.analysis,
                                                  [&](const SystemState& s, const StepDiagnostics& d) {
    eval.Evaluate(s, d, row.data());
    progress.Row();
    watch.Row(d);
    if (o.stats) steps.push_back(d);
    reductions.Row(row.data());
    bounds.Row(row.data());
    return rows_out.Append(row.data(), layout->size()) && !InterruptRequested();
  }, [&](const SystemState& s) { eval.Follow(s); });
  const bool rows_written = rows_out.Drain();
  progress.Clear();
  PrintNotes(o, model, rep, watch, err);
  if (!rep.complete && rep.stop != StopKind::Interrupted) err << "mechkin run: " << o.file << ": " << rep.message << "\n";
  if (o.stats && !steps.empty()) PrintStats(rep, steps, err);
  if (rep.rows == 0) return 1;  // refused or failed before the first row: no table at all
  const bool interrupted = InterruptRequested();
  std::string note = rep.complete ? "" : interrupted ? "interrupted (SIGINT)" : rep.message.substr(0, rep.message.find('\n'));
  if (!rep.complete && note.empty()) note = "the run stopped early";
  const std::vector<ReductionResult> reduced = reductions.Finish();
  PrintReductions(reduced, err);
  if (!writer.Finish(note, &why, reduced) || !rows_written) {
    if (why.empty()) why = "writing the table failed";
    err << "mechkin run: " << why << "\n";
    return 1;
  }
  const bool held = BoundsHeld(model, *layout, bounds, note, o.file, err);
  return !rep.complete ? (interrupted ? 130 : 1) : held ? 0 : 1;
}

}  // namespace mechkin
