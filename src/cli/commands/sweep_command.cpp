#include "cli/commands/sweep_command.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

#include "analysis/sweep.hpp"
#include "cli/commands/load_for_command.hpp"
#include "cli/commands/progress.hpp"
#include "cli/commands/request_options.hpp"
#include "io/sweep_writer.hpp"

namespace mechkin {

void SetupSweepCommand(CLI::App& app, SweepCommandOptions* o) {
  CLI::App* cmd = app.add_subcommand("sweep", "Run many variants of a parametric file; one summary row per variant");
  cmd->add_option("files", o->files, "Mechanism file (with --merge: the shard files)")->required();
  cmd->add_option("-o,--output", o->output, "Summary file (default: stdout); written atomically");
  cmd->add_option("--format", o->format, "csv, or json (the shard format --merge reads)")
      ->check(CLI::IsMember({"csv", "json"}));
  cmd->add_option("--grid", o->grid, "NAME=FROM:TO:COUNT, repeatable: the grid of all combinations (at most 1e8)");
  cmd->add_option("--samples", o->samples, "N variants uniform within the parameters' min/max")
      ->check(CountCheck(kSweepSamples));
  cmd->add_option("--seed", o->seed, "Seed of --samples (default 1)");
  cmd->add_option("--shard", o->shard, "i/N: run the variants with index = i-1 (mod N), for job arrays");
  cmd->add_option("--threads", o->threads, "Threads (default: all cores)")->check(CLI::Range(0, 4096));
  AddOrderOption(cmd, &o->request, "Derivative orders summarised (default 1)");
  AddToleranceOption(cmd, &o->request, "Position tolerance of every run (default 1e-10)");
  cmd->add_option("--set", o->set, "Parameter value replacing the file's for every variant: NAME=NUMBER");
  cmd->add_flag("--merge", o->merge, "Join shard files written with --format json (with --out: dataset parts)");
  cmd->add_option("--curves", o->curves, "COL,...: keep every row of these columns (e.g. coupler_point.x) in a dataset")
      ->delimiter(',');
  cmd->add_option("--out", o->out_dir, "Folder of the dataset (HDF5, docs/datasets.md): sweep.h5 or a shard's file");
  AddKeepPartialOption(cmd, &o->keep_partial, "the variants finished");
}

namespace {

// Variants a sweep accepts (the grid's product or --samples): stated in --help and
// checked before any variant is made.
constexpr double kMaxVariants = 100000000;

// The grid's variant count within kMaxVariants; false (why set) beyond it.
bool GridWithinLimit(const std::vector<GridAxis>& axes, std::string* why) {
  double product = 1;
  std::string factors;
  for (const GridAxis& a : axes) {
    product *= a.count;
    factors += (factors.empty() ? "" : " x ") + std::to_string(a.count);
  }
  if (product <= kMaxVariants) return true;
  char count[32];
  std::snprintf(count, sizeof count, "%.6g", product);
  *why = "--grid: " + std::string(count) + " variants (" + factors + ") is more than the limit of 100000000 variants: " +
         "use fewer points per axis or fewer axes";
  return false;
}

bool ParseShard(const std::string& s, SweepOptions* options) {
  return s.empty() || ParseShardText(s, &options->shard, &options->shards);
}

// The summary's destination, opened before the work; every input file is refused as it.
bool Open(const SweepCommandOptions& o, OutputFile* file, std::ostream& out, std::ostream& err) {
  return OpenReport(o.output, o.merge ? o.files : std::vector<std::string>{o.files.front()}, "sweep", file, out, err);
}

bool Write(const SweepCommandOptions& o, const SweepResult& result, OutputFile* file, std::ostream& err) {
  const std::string text = o.format == "json" ? SweepJsonText(result) + "\n" : SweepCsv(result);
  return CommitReport(file, text, "sweep", err);
}

// The shard's variants (only those: a shard's memory follows its share): the
// grid's, or samples within the parameters' ranges.
bool Variants(const SweepCommandOptions& o, const Model& model, const SweepOptions& options, ShardVariants* variants,
              std::ostream& err) {
  if (o.grid.empty() == (o.samples == 0)) {
    err << "mechkin sweep: give either --grid NAME=FROM:TO:COUNT (repeatable) or --samples N\n";
    return false;
  }
  std::string why;
  if (o.samples > 0) {
    *variants = SampleShard(model, o.samples, o.seed, options.shard, options.shards, &why);
  } else {
    std::vector<GridAxis> axes;
    for (const auto& g : o.grid) {
      GridAxis a;
      if (!ParseGridAxis(g, &a, &why)) break;
      if (!model.FindParameter(a.parameter)) why = "--grid: no parameter '" + a.parameter + "' in " + o.files.front();
      if (!why.empty()) break;
      axes.push_back(a);
    }
    if (why.empty() && GridWithinLimit(axes, &why)) *variants = GridShard(axes, options.shard, options.shards);
  }
  if (!why.empty()) err << "mechkin sweep: " << why << "\n";
  return why.empty();
}

}  // namespace

int RunSweepCommand(const SweepCommandOptions& o, std::ostream& out, std::ostream& err) {
  if (o.out_dir.empty() != o.curves.empty() && !(o.merge && !o.out_dir.empty())) {
    err << "mechkin sweep: a dataset needs both --curves COL,... and --out DIR\n";
    return 2;
  }
  if (!o.out_dir.empty() && (!o.output.empty() || o.format != "csv")) {
    err << "mechkin sweep: -o and --format are the summary's; a dataset sweep writes its file into --out DIR\n";
    return 2;
  }
  if (o.merge && !o.out_dir.empty()) return RunDatasetMerge(o, err);
  OutputFile file;
  if (o.merge) {
    if (!Open(o, &file, out, err)) return 1;
    SweepResult merged;
    std::string why;
    if (!MergeSweepFiles(o.files, &merged, &why)) {
      err << "mechkin sweep --merge: " << why << "\n";
      return 1;
    }
    return Write(o, merged, &file, err) ? 0 : 1;
  }
  if (o.files.size() != 1) {
    err << "mechkin sweep: give one mechanism file (several files only with --merge)\n";
    return 2;
  }
  SweepOptions options;
  if (!ParseShard(o.shard, &options)) {
    err << "mechkin sweep: --shard '" << o.shard << "': expected i/N with 1 <= i <= N, e.g. --shard 2/8\n";
    return 2;
  }
  ParameterOverrides overrides;
  if (!ParseOverrides(o.set, &overrides, err)) return 2;
  const std::optional<Model> model = LoadForCommand(o.files.front(), err, overrides);
  if (!model) return 1;
  ShardVariants variants;
  if (!Variants(o, *model, options, &variants, err)) return 2;
  if (!o.out_dir.empty()) return RunDatasetSweep(o, *model, variants, options, overrides, err);
  if (!Open(o, &file, out, err)) return 1;
  options.request = o.request;
  options.request.interrupted = InstallInterruptPoll(o.keep_partial);
  options.threads = o.threads;
  // Progress on a terminal's stderr, not over a summary written to that terminal.
  const bool summary_on_terminal = (o.output.empty() || o.output == "-") && &out == &std::cout && ::isatty(STDOUT_FILENO);
  ProgressLine progress(&err == &std::cerr && ::isatty(STDERR_FILENO) && !summary_on_terminal &&
                            variants.size() > 1,
                        variants.size(), "variants", err);
  options.progress = [&](int done) { progress.Update(done); };
  SweepResult result = RunSweepShard(*model, variants, options);
  progress.Finish();
  if (o.format == "json")
    result.identity = SweepIdentityText({o.files.front(), o.request.order, o.request.tolerance,
                                         static_cast<int>(o.request.solver), overrides, o.grid, o.samples, o.seed});
  if (!Write(o, result, &file, err)) return 1;
  return result.interrupted ? kInterruptedExit : 0;
}

}  // namespace mechkin
