// Per-variant cost of a sweep: Compile of mechanisms/parametric-four-bar.json's spec
// with one parameter override per iteration (what `sweep`, `tolerance`, the
// sensitivity sides and Python's with_parameters pay per variant), against the full
// read (JSON text → spec) + compile that every variant paid before the spec layer.
// Run: ./build/tools/bench_compile
#include <benchmark/benchmark.h>

#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>

#include "model/compile.hpp"
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

}  // namespace
}  // namespace mechkin

BENCHMARK_MAIN();
