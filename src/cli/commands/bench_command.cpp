#include "cli/commands/bench_command.hpp"

#include <sstream>

#include "analysis/speed_accuracy.hpp"
#include "analysis/load.hpp"
#include "io/bench_report.hpp"
#include "io/output_file.hpp"

namespace mechkin {

void SetupBenchCommand(CLI::App& app, BenchCommandOptions* o) {
  CLI::App* cmd = app.add_subcommand("bench", "Measure the speed/accuracy trade over a grid of settings");
  cmd->add_option("file", o->file, "Mechanism file (format v1)")->required();
  cmd->add_flag("--quick", o->quick, "Small grid (a few seconds)");
  cmd->add_option("--repeats", o->repeats, "Timed repeats per setting")->check(CLI::Range(1, 50));
  cmd->add_option("--reference", o->reference,
                  "Reference table (CSV from `mechkin run --si`, same columns); default: tightest tolerance, 8x steps");
  cmd->add_option("--csv", o->csv, "Where to write the whole grid (CSV)");
  cmd->add_option("--svg", o->svg, "Where to write the Pareto front plot (SVG)");
}

int RunBenchCommand(const BenchCommandOptions& o, std::ostream& out, std::ostream& err) {
  const LoadResult loaded = LoadMechanismFile(o.file);
  if (!loaded.ok()) {
    for (const auto& e : loaded.errors) err << o.file << ": error: " << e.ToString() << "\n";
    return 1;
  }
  const Model& model = *loaded.model;
  if (!model.analysis) {
    err << o.file << ": no 'analysis' block to benchmark\n";
    return 1;
  }
  // The destinations first: neither an input nor each other, writable, before the measurements.
  OutputFile csv_file, svg_file;
  std::string why;
  const std::vector<std::string> inputs{o.file, o.reference};
  if (!DistinctOutputs({o.csv, o.svg}, {"--csv", "--svg"}, &why) ||
      !csv_file.Open(o.csv, inputs, &why, &out, "the grid") || !svg_file.Open(o.svg, inputs, &why, &out, "the plot")) {
    err << "mechkin bench: " << why << "\n";
    return 1;
  }
  ReferenceTable reference;
  try {
    if (!o.reference.empty()) {
      reference = ReadReferenceCsv(o.reference);
    } else {
      BenchSetting ref{PositionSolver::Newton, 1e-13, 3, Formulation::Omega, 8 * model.analysis->steps};
      const Motion run = RunForBench(model, ref);
      if (!run.complete) {
        err << "mechkin bench: the reference run failed: " << run.stop.message << "\n";
        return 1;
      }
      reference = ReferenceFromMotion(run);
      out << "reference: " << ref.Describe() << "\n";
    }
  } catch (const std::exception& e) {
    err << "mechkin bench: " << e.what() << "\n";
    return 1;
  }
  BenchOptions bo;
  bo.quick = o.quick;
  bo.repeats = o.repeats;
  const std::vector<BenchResult> results = RunBench(model, BenchGrid(model, bo), reference, bo);
  out << results.size() << " settings measured on " << (model.name.empty() ? o.file : model.name) << "\n";
  PrintFront(results, out);
  std::ostringstream csv, svg;
  WriteBenchCsv(results, csv);
  WriteBenchSvg(results, "mechkin bench: " + (model.name.empty() ? o.file : model.name), svg);
  csv_file.Write(csv.str());
  svg_file.Write(svg.str());
  if (!csv_file.Commit("", &why) || !svg_file.Commit("", &why)) {
    err << "mechkin bench: " << why << "\n";
    return 1;
  }
  out << "grid written to " << o.csv << ", front plot to " << o.svg << "\n";
  return 0;
}

}  // namespace mechkin
