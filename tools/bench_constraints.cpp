// Cost of evaluating the constraint system: Φ, the sparse Jacobian (ω' version)
// and all right-hand sides (ν, γ, η, σ), for the bundled spatial slider-crank
// and the 50-loop chain (101 bodies). Run: ./build/tools/bench_constraints
#include <benchmark/benchmark.h>

#include <random>

#include "constraints/system.hpp"
#include "model/loader.hpp"
#include "solvers/position.hpp"

namespace mechkin {
namespace {

struct Fixture {
  Model model;
  std::unique_ptr<ConstraintSystem> sys;
  std::unique_ptr<SystemState> state;
  std::unique_ptr<SparseJacobian> jac;
  explicit Fixture(const std::string& file) {
    LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/" + file);
    if (!r.ok()) throw std::runtime_error("cannot load " + file);
    model = std::move(*r.model);
    sys = std::make_unique<ConstraintSystem>(model, true);
    state = std::make_unique<SystemState>(*sys);
    std::mt19937 g(1);
    std::uniform_real_distribution<double> u(-1, 1);
    for (auto& b : state->bodies) {
      for (int k = 1; k <= 4; ++k) b.r[k] = Vec3(u(g), u(g), u(g));
      for (int k = 0; k < 4; ++k) b.w[k] = Vec3(u(g), u(g), u(g));
      b.UpdateDerived(4);
    }
    EvalDriverFunctions(model, 0.1, state.get());
    jac = std::make_unique<SparseJacobian>(*sys, Formulation::Omega, AllRows(*sys));
  }
};

void Evaluate(benchmark::State& st, const char* file) {
  Fixture f(file);
  Eigen::VectorXd phi(f.sys->num_rows()), rhs(f.sys->num_rows());
  for (auto _ : st) {
    CalcPhi(*f.sys, *f.state, &phi);
    f.jac->Fill(*f.sys, *f.state);
    for (int k = 1; k <= 4; ++k) {
      CalcRhs(*f.sys, *f.state, k, Formulation::Omega, &rhs);
      benchmark::DoNotOptimize(rhs.data());
    }
    benchmark::DoNotOptimize(phi.data());
  }
  st.counters["equations"] = f.sys->num_rows();
}

void Phi(benchmark::State& st, const char* file) {
  Fixture f(file);
  Eigen::VectorXd phi(f.sys->num_rows());
  for (auto _ : st) {
    CalcPhi(*f.sys, *f.state, &phi);
    benchmark::DoNotOptimize(phi.data());
  }
}

void Jacobian(benchmark::State& st, const char* file) {
  Fixture f(file);
  for (auto _ : st) {
    f.jac->Fill(*f.sys, *f.state);
    benchmark::ClobberMemory();
  }
}

BENCHMARK_CAPTURE(Evaluate, slider_crank_all, "spatial-slider-crank.json");
BENCHMARK_CAPTURE(Phi, slider_crank_phi, "spatial-slider-crank.json");
BENCHMARK_CAPTURE(Jacobian, slider_crank_jacobian, "spatial-slider-crank.json");
BENCHMARK_CAPTURE(Evaluate, chain101_all, "chain-50-loops.json");
BENCHMARK_CAPTURE(Phi, chain101_phi, "chain-50-loops.json");
BENCHMARK_CAPTURE(Jacobian, chain101_jacobian, "chain-50-loops.json");

}  // namespace
}  // namespace mechkin

BENCHMARK_MAIN();
