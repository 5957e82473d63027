#include "cli/commands/run_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "analysis/kinematic_analysis.hpp"
#include "model/loader.hpp"
#include "output/motion_table.hpp"

namespace mechkin {

void SetupRunCommand(CLI::App& app, RunOptions* o) {
  CLI::App* cmd = app.add_subcommand("run", "Driven kinematic analysis: write the motion table");
  cmd->add_option("file", o->file, "Mechanism file (format v1)")->required();
  cmd->add_option("-o,--output", o->output, "Output file (default: stdout); written atomically");
  cmd->add_option("--format", o->format, "Table format (csv, json)")->check(CLI::IsMember({"csv", "json"}));
  cmd->add_option("--order", o->order, "Highest time derivative computed: 0 position ... 4 snap (default 3)")
      ->check(CLI::Range(0, 4));
  cmd->add_option("--formulation", o->formulation, "Rotational unknowns of the derivative solves (omega, p)")
      ->check(CLI::IsMember({"omega", "p"}));
  cmd->add_option("--solver", o->solver, "Position solver (newton, ceres)")->check(CLI::IsMember({"newton", "ceres"}));
  cmd->add_option("--tol", o->tolerance, "Position tolerance relative to the mechanism size (default 1e-10)")
      ->check(CLI::Range(1e-15, 1e-3));
  cmd->add_flag("--si", o->si, "Write SI units (m, rad) instead of the file's units");
  cmd->add_flag("--stats", o->stats, "Print timing statistics on stderr");
  cmd->add_option("--bodies", o->bodies, "Bodies whose columns are written (comma-separated; none: '')")->delimiter(',');
  cmd->add_option("--outputs", o->outputs, "Outputs whose columns are written (comma-separated)")->delimiter(',');
  cmd->callback([o, cmd] {
    o->bodies_given = cmd->count("--bodies") > 0;
    o->outputs_given = cmd->count("--outputs") > 0;
  });
}

int RunRun(const RunOptions& o, std::ostream& out, std::ostream& err) {
  const LoadResult loaded = LoadMechanismFile(o.file);
  for (const auto& w : loaded.warnings) err << o.file << ": warning: " << w.ToString() << "\n";
  if (!loaded.ok()) {
    for (const auto& e : loaded.errors) err << o.file << ": error: " << e.ToString() << "\n";
    return 1;
  }
  const Model& model = *loaded.model;
  TableOptions topt;
  topt.order = o.order;
  topt.si = o.si;
  topt.all_bodies = !o.bodies_given;
  topt.all_outputs = !o.outputs_given;
  for (const auto& b : o.bodies) if (!b.empty()) topt.bodies.push_back(b);
  for (const auto& x : o.outputs) if (!x.empty()) topt.outputs.push_back(x);
  std::unique_ptr<MotionTable> table;
  try {
    table = std::make_unique<MotionTable>(model, topt);
  } catch (const std::exception& e) {
    err << "mechkin run: " << e.what() << "\n";
    return 2;
  }
  AnalysisOptions aopt;
  aopt.order = o.order;
  aopt.formulation = o.formulation == "p" ? Formulation::P : Formulation::Omega;
  aopt.solver = o.solver == "ceres" ? PositionSolver::Ceres : PositionSolver::Newton;
  aopt.tolerance = o.tolerance;
  if (o.bodies_given || o.outputs_given) {
    // Only the bodies the table shows, or that its outputs read, are needed.
    std::vector<char> need(model.num_bodies(), 0);
    for (int b = 0; b < model.num_bodies(); ++b)
      if (topt.all_bodies || std::count(topt.bodies.begin(), topt.bodies.end(), model.bodies[b].name)) need[b] = 1;
    for (const auto& out : model.outputs)
      if (topt.all_outputs || std::count(topt.outputs.begin(), topt.outputs.end(), out.name))
        for (BodyIndex b : {out.body1, out.body2})
          if (b != kGround) need[b] = 1;
    for (int b = 0; b < model.num_bodies(); ++b)
      if (need[b]) aopt.needed_bodies.push_back(b);
    if (aopt.needed_bodies.empty()) aopt.needed_bodies.push_back(-1);  // nothing requested: solve no block
  }

  const bool tty = ::isatty(2);
  const auto start = std::chrono::steady_clock::now();
  auto last_draw = start;
  const int total = model.analysis ? model.analysis->steps + 1 : 0;
  int done = 0;
  const AnalysisReport rep = RunKinematicAnalysis(model, aopt, [&](const SystemState& s, const StepDiagnostics& d) {
    table->AddRow(s, d.t, d.iterations, d.residual, d.condition, d.error_bound);
    ++done;
    if (tty) {
      const auto now = std::chrono::steady_clock::now();
      if (now - start > std::chrono::seconds(1) && now - last_draw > std::chrono::milliseconds(200)) {
        last_draw = now;
        const int pct = total ? 100 * done / total : 0;
        err << "\r[" << std::string(pct / 5, '#') << std::string(20 - pct / 5, ' ') << "] " << pct << "% " << std::flush;
      }
    }
  });
  if (tty && std::chrono::steady_clock::now() - start > std::chrono::seconds(1)) err << "\r" << std::string(40, ' ') << "\r";
  for (const auto& sa : rep.set_aside) err << "mechkin run: redundant equation set aside: " << sa << "\n";
  // Loud, not quiet: a row whose error bound (from the condition estimate) exceeds
  // 1e-4 for some derivative order (the 4th digit may be wrong) is named on stderr.
  {
    static const char* kOrderName[] = {"position", "velocity", "acceleration", "jerk", "snap"};
    for (int k = 0; k <= o.order; ++k) {
      const StepDiagnostics* first = nullptr;
      double worst = 0;
      for (const auto& d : rep.steps) {
        if (d.error_bound[k] > 1e-4 && !first) first = &d;
        worst = std::max(worst, d.error_bound[k]);
      }
      if (first)
        err << "mechkin run: warning: " << kOrderName[k] << " is ill-conditioned from t = " << first->t
            << " s (condition estimate " << first->condition << "; relative error bound up to " << worst
            << "): a singular position is near; see the error_bound columns\n";
    }
  }
  if (!rep.complete) err << "mechkin run: " << o.file << ": " << rep.message << "\n";
  if (o.stats && !rep.steps.empty()) {
    const StepStatistics st = SummarizeSteps(rep.steps);
    char line[160];
    std::snprintf(line, sizeof line, "per step: %.3f us solve, %.3f Newton iterations", st.median_us, st.mean_iterations);
    err << "steps: " << rep.steps.size() << ", blocks: " << rep.blocks << " (solved: " << rep.blocks_solved << ")"
        << ", assembly iterations: " << rep.assembly_iterations
        << ", set-aside equations: " << rep.set_aside.size() << " (largest scaled residual " << st.max_set_aside_residual << ")\n"
        << line << "\n";
  }
  if (rep.steps.empty()) return 1;  // refused or failed before the first row: no table at all
  std::ostringstream text;
  const bool partial = !rep.complete;
  const std::string note = partial ? rep.message.substr(0, rep.message.find('\n')) : "";
  if (o.format == "json") table->WriteJson(text, partial, note);
  else table->WriteCsv(text, partial, note);
  if (o.output.empty()) {
    out << text.str();
  } else {
    std::string why;
    if (!WriteFileAtomically(o.output, text.str(), &why)) {
      err << "mechkin run: " << why << "\n";
      return 1;
    }
  }
  return rep.complete ? 0 : 1;
}

}  // namespace mechkin
