// `mechkin sweep FILE ... --curves COLS --out DIR` and `mechkin sweep --merge --out DIR PARTS...`
// (issue 31, dataset sweeps): the HDF5 files of io/hdf5_dataset.hpp, docs/datasets.md.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>

#include "analysis/parallel.hpp"
#include "analysis/sweep_curves.hpp"
#include "cli/commands/progress.hpp"
#include "cli/commands/request_options.hpp"
#include "cli/commands/sweep_command.hpp"
#include "io/hdf5_dataset.hpp"
#include "io/sweep_writer.hpp"

namespace mechkin {

std::string DatasetFileName(const std::string& folder, int shard, int shards) {
  if (shards <= 1) return (std::filesystem::path(folder) / "sweep.h5").string();
  const int width = static_cast<int>(std::to_string(shards).size());
  char name[64];
  std::snprintf(name, sizeof name, "sweep-shard-%0*d-of-%d.h5", width, shard, shards);
  return (std::filesystem::path(folder) / name).string();
}

namespace {

bool MakeFolder(const std::string& folder, std::ostream& err) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (!ec && std::filesystem::is_directory(folder)) return true;
  err << "mechkin sweep: --out '" << folder << "': cannot make the folder (" << (ec ? ec.message() : "not a folder")
      << ")\n";
  return false;
}

// "mechkin sweep: 20 variants in 0.05 s (400 variants/s, 2 threads) -> DIR/sweep.h5: 18 complete, 2 invalid"
void PrintDatasetSummary(int variants, double seconds, int threads, const std::string& path,
                         const std::map<std::string, int>& statuses, std::ostream& err) {
  err << std::fixed << std::setprecision(2) << "mechkin sweep: " << variants << " variants in " << seconds << " s ("
      << std::setprecision(0) << (seconds > 0 ? variants / seconds : 0.0) << " variants/s, " << threads
      << (threads == 1 ? " thread" : " threads") << ") -> " << path << ":";
  bool first = true;
  for (const auto& [status, n] : statuses) {
    err << (first ? " " : ", ") << n << " " << status;
    first = false;
  }
  err << "\n";
  err.unsetf(std::ios::floatfield);
  err << std::setprecision(6);
}

}  // namespace

int RunDatasetSweep(const SweepCommandOptions& o, const Model& model, const ShardVariants& variants,
                    const SweepOptions& sweep, const ParameterOverrides& overrides, std::ostream& err) {
  CurveSelection selection;
  std::string why;
  RunRequest request = o.request;
  request.interrupted = InstallInterruptPoll(o.keep_partial);
  if (!SelectCurves(model, request, o.curves, &selection, &why)) {
    err << "mechkin sweep: " << why << "\n";
    return 2;
  }
  if (!MakeFolder(o.out_dir, err)) return 1;
  DatasetShape shape = ShapeOf(variants, selection);
  shape.shard = sweep.shards > 1 ? sweep.shard : 0;
  shape.shards = sweep.shards > 1 ? sweep.shards : 0;
  shape.source = o.files.front();
  shape.identity = SweepIdentityText({o.files.front(), o.request.order, o.request.tolerance,
                                      static_cast<int>(o.request.solver), overrides, o.grid, o.samples, o.seed});
  const std::string path = DatasetFileName(o.out_dir, sweep.shard, sweep.shards);
  DatasetWriter writer;
  if (!writer.Create(path, shape, &why)) {
    err << "mechkin sweep: " << why << "\n";
    return 1;
  }
  ProgressLine progress(&err == &std::cerr && ::isatty(STDERR_FILENO) && variants.size() > 1,
                        variants.size(), "variants", err);
  std::map<std::string, int> statuses;
  const auto start = std::chrono::steady_clock::now();
  const bool whole = RunCurveSweep(model, variants, selection, o.threads, [&](VariantCurves&& v) {
    ++statuses[v.status];
    return writer.Write(v, &why);
  }, [&](int done) { progress.Update(done); });
  progress.Finish();
  const bool interrupted = !whole && why.empty();
  if (!why.empty() || (interrupted && !o.keep_partial) || !writer.Finish(interrupted, &why)) {
    if (!why.empty()) err << "mechkin sweep: " << why << "\n";
    return why.empty() ? kInterruptedExit : 1;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  PrintDatasetSummary(writer.written(), seconds, ThreadCount(o.threads), path, statuses, err);
  if (interrupted) err << "mechkin sweep: interrupted; the dataset is partial (" << writer.written() << " of "
                       << variants.size() << " variants)\n";
  return interrupted ? kInterruptedExit : 0;
}

int RunDatasetMerge(const SweepCommandOptions& o, std::ostream& err) {
  if (!MakeFolder(o.out_dir, err)) return 1;
  const std::string path = DatasetFileName(o.out_dir, 1, 1);
  std::string why;
  if (!MergeDatasets(o.files, path, &why)) {
    err << "mechkin sweep --merge: " << why << "\n";
    return 1;
  }
  return 0;
}

}  // namespace mechkin
