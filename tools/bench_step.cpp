// Factorization and whole-step cost of the driven analysis (issue: speed).
// A full step = position (Newton from the Taylor predictor), velocity,
// acceleration and jerk, tolerance 1e-10 of the mechanism size.
//   ./build/tools/bench_step                       (slider-crank, chains N = 1, 10, 100, 1000)
// Chain files are generated with tools/make_chain.py into the build folder.
#include <benchmark/benchmark.h>

#include <cstdlib>

#include <filesystem>

#include "analysis/kinematic_analysis.hpp"
#include "mobility/mobility.hpp"
#include "analysis/load.hpp"
#include "kinematics/newton.hpp"
#include "kinematics/workspace.hpp"

namespace mechkin {
namespace {

Model LoadOrDie(const std::string& path) {
  LoadResult r = LoadMechanismFile(path);
  if (!r.ok()) {
    std::fprintf(stderr, "cannot load %s\n", path.c_str());
    std::exit(1);
  }
  return std::move(*r.model);
}

std::string ChainFile(int n) {
  const std::string path = "chain-" + std::to_string(n) + ".json";
  const std::string cmd = "python3 " + std::string(MECHKIN_SOURCE_DIR) + "/tools/make_chain.py " + std::to_string(n) + " " + path;
  if (std::system(cmd.c_str()) != 0) std::exit(1);
  return path;
}

Model ForFile(const benchmark::State& st, const std::string& which) {
  if (which == "slider") return LoadOrDie(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/spatial-slider-crank.json");
  return LoadOrDie(ChainFile(static_cast<int>(st.range(0))));
}

// Whole step: the analysis over `steps` rows, reported per row.
void WholeStep(benchmark::State& st, const std::string& which) {
  Model m = ForFile(st, which);
  const int steps = which == "slider" ? 360 : 40;
  m.analysis = Analysis{};
  m.analysis->end = which == "slider" ? 1.0 : 0.4;
  m.analysis->steps = steps;
  AnalysisOptions o;
  o.order = 3;
  int rows = 0;
  for (auto _ : st) {
    const AnalysisReport rep = RunKinematicAnalysis(m, o, [&](const SystemState&, const StepDiagnostics&) { ++rows; return true; });
    if (!rep.complete) st.SkipWithError(rep.message.c_str());
  }
  // Time per step (the one-off assembly is amortized over the rows).
  st.SetItemsProcessed(rows);
  st.counters["s_per_step"] = benchmark::Counter(static_cast<double>(rows), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void Factorization(benchmark::State& st, const std::string& which) {
  const Model m = ForFile(st, which);
  const ConstraintSystem sys(m, true);
  SystemState s(sys);
  NewtonSolver newton(sys, AllRows(sys));
  for (auto _ : st) benchmark::DoNotOptimize(newton.Factorize(s));
}

// One step's parts on the slider-crank at t = 0.3 s (mid-motion, a dense right-hand
// side). DenseSolves: back-solve, transposed solve, the two condition estimates, the
// factorization. StepParts: Φ, the Jacobian alone, the right-hand sides of the three
// derivative orders, the three orders solved (RHS + back-solve each), ‖J_s‖_F.
void AtMidMotion(benchmark::State& st, int which) {
  Model m = LoadOrDie(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/spatial-slider-crank.json");
  m.analysis->end = 0.3;
  m.analysis->steps = 108;
  const ConstraintSystem sys(m, true);
  SystemState pose(sys);
  RunKinematicAnalysis(m, AnalysisOptions{}, [&](const SystemState& s, const StepDiagnostics&) { pose = s; return true; });
  KinematicsWorkspace ws(sys, AllRows(sys), WorkspaceOptions{});
  NewtonSolver& newton = ws.newton();
  newton.Factorize(pose);
  SparseJacobian jac(sys, Formulation::Omega, AllRows(sys));
  jac.Fill(sys, pose);
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(6 * sys.num_bodies(), 1, 2), x(b.size()), v(sys.num_rows());
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(b.size());
  for (auto _ : st) {
    switch (which) {
      case 0: newton.BackSolve(b, &x); break;
      case 1: newton.SolveLinearTranspose(b, &x); break;
      case 2: benchmark::DoNotOptimize(newton.ConditionEstimate()); break;
      case 3: benchmark::DoNotOptimize(newton.SharperConditionEstimate(2)); break;
      case 4: newton.Factorize(pose); break;
      case 5: CalcPhi(sys, pose, &v); break;
      case 6: jac.Fill(sys, pose); break;
      case 7:
        for (int k = 1; k <= 3; ++k) CalcRhs(sys, pose, k, Formulation::Omega, &v);
        break;
      case 8: SolveDerivatives(ws, 3, &pose); break;
      case 9: benchmark::DoNotOptimize(DimensionlessNorm(jac.matrix(), newton.scales(), ones)); break;
    }
    benchmark::DoNotOptimize(x.data());
    benchmark::DoNotOptimize(v.data());
  }
}
BENCHMARK_CAPTURE(AtMidMotion, DenseSolves/back_solve, 0);
BENCHMARK_CAPTURE(AtMidMotion, DenseSolves/transposed_solve, 1);
BENCHMARK_CAPTURE(AtMidMotion, DenseSolves/condition_estimate, 2);
BENCHMARK_CAPTURE(AtMidMotion, DenseSolves/sharper_estimate_2, 3);
BENCHMARK_CAPTURE(AtMidMotion, DenseSolves/factorize, 4);
BENCHMARK_CAPTURE(AtMidMotion, StepParts/phi, 5);
BENCHMARK_CAPTURE(AtMidMotion, StepParts/jacobian_fill, 6);
BENCHMARK_CAPTURE(AtMidMotion, StepParts/rhs_orders_1_to_3, 7);
BENCHMARK_CAPTURE(AtMidMotion, StepParts/derivatives_1_to_3, 8);
BENCHMARK_CAPTURE(AtMidMotion, StepParts/dimensionless_norm, 9);

// The whole `check` report (load + rank mobility, redundancy, idle freedoms, driving
// status, suggestions) of every bundled mechanism: no time analysis needed.
void CheckReport(benchmark::State& st, const std::string& file) {
  for (auto _ : st) {
    const Model m = LoadOrDie(file);
    benchmark::DoNotOptimize(CalcMobility(m).mobility);
  }
}

int RegisterCheckBenchmarks() {
  for (const auto& e : std::filesystem::directory_iterator(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms"))
    if (e.path().extension() == ".json")
      benchmark::RegisterBenchmark(("CheckReport/" + e.path().stem().string()).c_str(), CheckReport, e.path().string())
          ->Unit(benchmark::kMillisecond);
  return 0;
}
const int kRegistered = RegisterCheckBenchmarks();

BENCHMARK_CAPTURE(Factorization, slider_crank, std::string("slider"));
BENCHMARK_CAPTURE(Factorization, chain, std::string("chain"))->Arg(1)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(WholeStep, slider_crank, std::string("slider"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(WholeStep, chain, std::string("chain"))->Arg(1)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mechkin

BENCHMARK_MAIN();
