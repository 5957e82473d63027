// Ceres position solve: unit Euler parameters by QuaternionManifold versus a
// pᵀp − 1 residual per body. Tracking cost per step on bundled mechanisms.
// Run: ./build/tools/bench_ceres
#include <benchmark/benchmark.h>

#include "analysis/kinematic_analysis.hpp"
#include "analysis/load.hpp"

namespace mechkin {
namespace {

void Track(benchmark::State& st, const char* file, bool normalization) {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/" + file);
  Model m = std::move(*r.model);
  m.analysis->steps = 60;
  AnalysisOptions o;
  o.solver = PositionSolver::Ceres;
  o.ceres_normalization_residual = normalization;
  double iters = 0;
  int rows = 0;
  for (auto _ : st) {
    const AnalysisReport rep = RunKinematicAnalysis(m, o, [&](const SystemState&, const StepDiagnostics& d) {
      iters += d.iterations;
      ++rows;
      return true;
    });
    if (!rep.complete) st.SkipWithError(rep.message.c_str());
  }
  st.counters["iterations_per_step"] = iters / std::max(rows, 1);
  st.counters["s_per_step"] = benchmark::Counter(rows, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK_CAPTURE(Track, slider_crank_manifold, "spatial-slider-crank.json", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Track, slider_crank_normalization, "spatial-slider-crank.json", true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Track, bennett_manifold, "bennett-linkage.json", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Track, bennett_normalization, "bennett-linkage.json", true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Track, stewart_legs_manifold, "stewart-platform.json", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Track, stewart_legs_normalization, "stewart-platform.json", true)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mechkin

BENCHMARK_MAIN();
