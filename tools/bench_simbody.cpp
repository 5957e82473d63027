// mechkin against Simbody 3.7 (Debian's libsimbody-dev), side by side in one
// binary, on the bundled spatial slider-crank (R-S-U-P, crank 360°/s):
//   mechkin: position, velocity, acceleration and jerk per step (default tolerance);
//   Simbody: prescribeQ + projectQ (same tolerance), prescribeU + projectU,
//            realize(Acceleration) — position, velocity and acceleration only;
//            started either from the last pose (`Simbody`) or, as mechkin's own
//            predictor does, from a cubic extrapolation of the last four poses and
//            speeds (`SimbodyExtrapolated`, the fair comparison).
// Before timing, both are checked to describe the same mechanism: the slider
// positions at t = 0.3 s must agree to 1e-8 m.
// Run with --benchmark_enable_random_interleaving=true --benchmark_repetitions=5.
#include <benchmark/benchmark.h>

#include <Simbody.h>
#include <cmath>
#include <cstdio>

#include "analysis/kinematic_analysis.hpp"
#include "analysis/load.hpp"

namespace {

constexpr int kSteps = 360;
constexpr double kTol = 1e-10;
const SimTK::Vec3 kPin(0.1, 0, 0), kWrist(0.395127091267, 0.02, 0.05);

// q = 2πt for the crank's pin.
class CrankDriver : public SimTK::Motion::Custom::Implementation {
 public:
  SimTK::Motion::Level getLevel(const SimTK::State&) const override { return SimTK::Motion::Position; }
  void calcPrescribedPosition(const SimTK::State& s, int, SimTK::Real* q) const override { q[0] = 2 * SimTK::Pi * s.getTime(); }
  void calcPrescribedPositionDot(const SimTK::State&, int, SimTK::Real* qd) const override { qd[0] = 2 * SimTK::Pi; }
  void calcPrescribedPositionDotDot(const SimTK::State&, int, SimTK::Real* qdd) const override { qdd[0] = 0; }
};

struct SimbodySliderCrank {
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::MobilizedBody::Slider slider;
  SimTK::State state;

  SimbodySliderCrank() {
    using namespace SimTK;
    const Body::Rigid body(MassProperties(1, Vec3(0), UnitInertia(1)));
    MobilizedBody::Pin crank(matter.Ground(), Transform(), body, Transform());
    MobilizedBody::Ball rod(crank, Transform(kPin), body, Transform());
    slider = MobilizedBody::Slider(matter.Ground(), Transform(kWrist), body, Transform());
    Constraint::Ball(rod, kWrist - kPin, slider, Vec3(0));
    Constraint::ConstantAngle(rod, UnitVec3(-0.067612340378281, 0.997711667481428, 0), slider, UnitVec3(0, 0, 1));
    Motion::Custom(crank, new CrankDriver);
    state = system.realizeTopology();
  }
  // History of the last four accepted Q and U (newest first) for the extrapolated start.
  SimTK::Vector q_hist[4], u_hist[4];
  int accepted = 0;

  // The cubic through the last four equally spaced values, one step ahead:
  // x(t+h) ≈ 4x₀ − 6x₁ + 4x₂ − x₃ (fewer values: lower orders). Written into `out`
  // element by element: SimTK::Vector expressions allocate their temporaries, which
  // would charge Simbody's step for heap traffic mechkin's predictor does not have.
  static void Extrapolate(const SimTK::Vector* h, int n, SimTK::Vector& out) {
    for (int i = 0; i < out.size(); ++i) {
      if (n >= 4) out[i] = 4 * h[0][i] - 6 * h[1][i] + 4 * h[2][i] - h[3][i];
      else if (n == 3) out[i] = 3 * h[0][i] - 3 * h[1][i] + h[2][i];
      else if (n == 2) out[i] = 2 * h[0][i] - h[1][i];
      else out[i] = h[0][i];
    }
  }
  // Shifts the history by one (same-size assignments: no allocation) and stores the accepted state.
  void Remember() {
    for (int k = 3; k > 0; --k) { q_hist[k] = q_hist[k - 1]; u_hist[k] = u_hist[k - 1]; }
    q_hist[0] = state.getQ();
    u_hist[0] = state.getU();
    if (accepted < 4) ++accepted;
  }
  void Step(double t, bool extrapolate = false) {
    using namespace SimTK;
    if (extrapolate && accepted > 0) {
      Extrapolate(q_hist, accepted, state.updQ());
      Extrapolate(u_hist, accepted, state.updU());
    }
    state.setTime(t);
    system.realize(state, Stage::Time);
    system.prescribeQ(state);
    system.projectQ(state, kTol);
    system.realize(state, Stage::Position);
    system.prescribeU(state);
    system.projectU(state, kTol);
    system.realize(state, Stage::Acceleration);
    if (extrapolate) Remember();
  }
  double SliderX() const { return slider.getBodyOriginLocation(state)[0]; }
};

mechkin::Model LoadSliderCrank() {
  mechkin::LoadResult r = mechkin::LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/spatial-slider-crank.json");
  return std::move(*r.model);
}

// Simbody's slider x after 108 steps to t = 0.3 s.
double SimbodySliderX(bool extrapolate) {
  SimbodySliderCrank sb;
  for (int k = 0; k <= 108; ++k) sb.Step(0.3 * k / 108, extrapolate);
  return sb.SliderX();
}

// The same mechanism: the slider's x at t = 0.3 s from both.
bool SameMechanism() {
  mechkin::Model m = LoadSliderCrank();
  m.analysis = mechkin::Analysis{};
  m.analysis->end = 0.3;
  m.analysis->steps = 108;
  double x_mechkin = 0;
  mechkin::RunKinematicAnalysis(m, mechkin::AnalysisOptions{}, [&](const mechkin::SystemState& s, const mechkin::StepDiagnostics&) {
    x_mechkin = s.bodies[2].r[0][0];
    return true;
  });
  const double x_last = SimbodySliderX(false), x_extrapolated = SimbodySliderX(true);
  std::printf("slider x at t = 0.3 s: mechkin %.12f, Simbody %.12f, Simbody (extrapolated start) %.12f\n", x_mechkin,
              x_last, x_extrapolated);
  return std::abs(x_mechkin - x_last) < 1e-8 && std::abs(x_mechkin - x_extrapolated) < 1e-8;
}

void Mechkin(benchmark::State& st) {
  mechkin::Model m = LoadSliderCrank();
  m.analysis = mechkin::Analysis{};
  m.analysis->steps = kSteps;
  mechkin::AnalysisOptions o;
  o.order = 3;
  o.keep_step_diagnostics = false;
  int rows = 0;
  for (auto _ : st) {
    const auto rep = mechkin::RunKinematicAnalysis(m, o, [&](const mechkin::SystemState&, const mechkin::StepDiagnostics&) {
      ++rows;
      return true;
    });
    if (!rep.complete) st.SkipWithError(rep.message.c_str());
  }
  st.counters["us_per_step"] = benchmark::Counter(rows / 1e6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void RunSimbody(benchmark::State& st, bool extrapolate) {
  SimbodySliderCrank sb;
  int rows = 0;
  for (auto _ : st) {
    sb.accepted = 0;  // each run starts from the design pose's history, as mechkin's does
    for (int k = 0; k <= kSteps; ++k) sb.Step(static_cast<double>(k) / kSteps, extrapolate);
    rows += kSteps + 1;
  }
  st.counters["us_per_step"] = benchmark::Counter(rows / 1e6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
void Simbody(benchmark::State& st) { RunSimbody(st, false); }
void SimbodyExtrapolated(benchmark::State& st) { RunSimbody(st, true); }

BENCHMARK(Mechkin)->Unit(benchmark::kMillisecond);
BENCHMARK(Simbody)->Unit(benchmark::kMillisecond);
BENCHMARK(SimbodyExtrapolated)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  if (!SameMechanism()) {
    std::fprintf(stderr, "the two models disagree: not comparing\n");
    return 1;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
