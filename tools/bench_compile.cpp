// Per-variant cost of a sweep: Compile of mechanisms/parametric-four-bar.json's spec
// with one parameter override per iteration (what `sweep`, `tolerance`, the
// sensitivity sides and Python's with_parameters pay per variant), against the full
// read (JSON text → spec) + compile that every variant paid before the spec layer.
// Also a sweep variant whole (RunVariant: compile + run + summary) against its run
// alone on the precompiled variant (tools/sweep_benchmark.sh prints the ratio).
// Run: ./build/tools/bench_compile
#include <benchmark/benchmark.h>

#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <vector>

#include "analysis/motion.hpp"
#include "analysis/run_request.hpp"
#include "analysis/sweep.hpp"
#include "model/compile.hpp"
#include "analysis/load.hpp"
#include "model/loader.hpp"
#include "spec/reader.hpp"

namespace mechkin {
namespace {

std::string FourBarText() {
  std::ifstream f(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json");
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// The crank length a over its sweep range [20, 60] mm, one value per iteration.
double CrankLength(int64_t i) { return 30 + static_cast<double>(i % 200) * 0.1; }

void BM_CompileVariant(benchmark::State& state) {
  SpecReadResult read = ReadMechanismSpec(FourBarText(), "parametric-four-bar.json");
  if (!read.spec || !read.spec->valid) throw std::runtime_error("cannot read the four-bar");
  const auto spec = std::make_shared<const MechanismSpec>(std::move(*read.spec));
  int64_t i = 0;
  for (auto _ : state) {
    LoadResult r = Compile(spec, {{"a", CrankLength(i++)}});
    if (!r.ok()) throw std::runtime_error("variant failed");
    benchmark::DoNotOptimize(r.model->bodies.data());
  }
}
BENCHMARK(BM_CompileVariant)->Unit(benchmark::kMicrosecond);

void BM_WithParameters(benchmark::State& state) {
  LoadResult base = LoadTextUnassembled(FourBarText(), "parametric-four-bar.json");
  if (!base.ok()) throw std::runtime_error("cannot load the four-bar");
  int64_t i = 0;
  for (auto _ : state) {
    LoadResult r = WithParametersUnassembled(*base.model, {{"a", CrankLength(i++)}});
    if (!r.ok()) throw std::runtime_error("variant failed");
    benchmark::DoNotOptimize(r.model->bodies.data());
  }
}
BENCHMARK(BM_WithParameters)->Unit(benchmark::kMicrosecond);

void BM_ReadAndCompile(benchmark::State& state) {
  const std::string text = FourBarText();
  int64_t i = 0;
  for (auto _ : state) {
    LoadResult r = LoadTextUnassembled(text, "parametric-four-bar.json", {{"a", CrankLength(i++)}});
    if (!r.ok()) throw std::runtime_error("variant failed");
    benchmark::DoNotOptimize(r.model->bodies.data());
  }
}
BENCHMARK(BM_ReadAndCompile)->Unit(benchmark::kMicrosecond);

void BM_ReadSpecOnly(benchmark::State& state) {
  const std::string text = FourBarText();
  for (auto _ : state) {
    SpecReadResult r = ReadMechanismSpec(text, "parametric-four-bar.json");
    benchmark::DoNotOptimize(r.spec->bodies.data());
  }
}
BENCHMARK(BM_ReadSpecOnly)->Unit(benchmark::kMicrosecond);

// The run of a sweep variant alone, on models compiled beforehand (the same 200 crank lengths).
void BM_VariantRunOnly(benchmark::State& state) {
  LoadResult base = LoadMechanismText(FourBarText(), "parametric-four-bar.json");
  if (!base.ok()) throw std::runtime_error("cannot load the four-bar");
  std::vector<Model> models;
  for (int64_t i = 0; i < 200; ++i) models.push_back(*WithParameters(*base.model, {{"a", CrankLength(i)}}).model);
  const RunRequest request = VariantRequest(models.front(), SweepOptions::DefaultRequest());
  int64_t i = 0;
  for (auto _ : state) {
    const Motion m = RunMotion(models[static_cast<size_t>(i++ % 200)], request);
    benchmark::DoNotOptimize(m.rows());
  }
}
BENCHMARK(BM_VariantRunOnly)->Unit(benchmark::kMicrosecond);

// A sweep variant whole: compile from the spec, run, summarise (what RunSweep does per variant).
void BM_VariantWhole(benchmark::State& state) {
  LoadResult base = LoadMechanismText(FourBarText(), "parametric-four-bar.json");
  if (!base.ok()) throw std::runtime_error("cannot load the four-bar");
  const SweepOptions options;
  int64_t i = 0;
  for (auto _ : state) {
    const VariantSummary v = RunVariant(*base.model, {{"a", CrankLength(i++)}}, options);
    benchmark::DoNotOptimize(v.rows);
  }
}
BENCHMARK(BM_VariantWhole)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace mechkin

BENCHMARK_MAIN();
