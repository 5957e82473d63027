// Cost of one clearance evaluation (one pair of bodies, one row: FCL's distance with
// the closest points and the rate, analysis/clearance.hpp) by shape kinds. Body 2
// visits 64 poses around body 1 (clear, 5–50 mm apart, turned), one per iteration.
//   ./build/tools/bench_clearance
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "analysis/clearance.hpp"
#include "analysis/load.hpp"
#include "constraints/system.hpp"

namespace mechkin {
namespace {

using nlohmann::json;

json ShapeOf(const std::string& kind) {
  if (kind == "sphere") return {{"type", "sphere"}, {"radius", 20}};
  if (kind == "capsule") return {{"type", "capsule"}, {"radius", 10}, {"length", 60}, {"axis", {1, 0, 0}}};
  if (kind == "box") return {{"type", "box"}, {"size", {60, 20, 20}}};
  json pts = json::array();  // a faceted ball: the 26 directions of a 3×3×3 grid, radius 20
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) {
          const double n = 20 / std::sqrt(x * x + y * y + z * z);
          pts.push_back({n * x, n * y, n * z});
        }
  return {{"type", "convex"}, {"points", pts}};
}

Model TwoBodies(const std::string& k1, const std::string& k2) {
  const json doc = {{"mechkin", 1},
                    {"units", {{"length", "mm"}, {"angle", "deg"}}},
                    {"bodies",
                     {{{"name", "a"}, {"position", {0, 0, 0}}, {"shape", ShapeOf(k1)}},
                      {{"name", "b"}, {"position", {100, 0, 0}}, {"shape", ShapeOf(k2)}}}},
                    {"joints", json::array()},
                    {"outputs", {{{"type", "clearance"}, {"body1", "a"}, {"body2", "b"}}}}};
  LoadResult r = LoadMechanismText(doc.dump(), "bench");
  if (!r.ok()) {
    std::fprintf(stderr, "bench_clearance: the two-body model does not load\n");
    std::exit(1);
  }
  return std::move(*r.model);
}

void PairPerRow(benchmark::State& st, const std::string& k1, const std::string& k2) {
  const Model model = TwoBodies(k1, k2);
  const ConstraintSystem sys(model, true);
  std::vector<SystemState> poses;
  for (int k = 0; k < 64; ++k) {
    SystemState s(sys);
    const double a = 2 * M_PI * k / 64, gap = 0.005 + 0.045 * (k % 8) / 7.0;  // m
    s.bodies[1].SetPose(Vec3((0.065 + gap) * std::cos(a), (0.065 + gap) * std::sin(a), 0.01 * std::sin(3 * a)),
                        QuatFromAxisAngle(Vec3(0.3, 0.4, 0.866).normalized(), a));
    s.bodies[1].r[1] = Vec3(0.1, -0.2, 0.05);
    s.bodies[1].w[0] = Vec3(1, 2, 0.5);
    for (auto& b : s.bodies) b.UpdateDerived(1);
    poses.push_back(std::move(s));
  }
  const ClearanceEvaluator eval(model, ClearanceOutputPairs(model));
  size_t k = 0;
  double sum = 0;
  for (auto _ : st) {
    const ClearanceValue v = eval.Evaluate(poses[k++ % poses.size()], 0, true);
    sum += v.distance;
    benchmark::DoNotOptimize(sum);
  }
  st.SetLabel("per pair per row");
}

BENCHMARK_CAPTURE(PairPerRow, sphere_sphere, std::string("sphere"), std::string("sphere"));
BENCHMARK_CAPTURE(PairPerRow, capsule_capsule, std::string("capsule"), std::string("capsule"));
BENCHMARK_CAPTURE(PairPerRow, sphere_box, std::string("sphere"), std::string("box"));
BENCHMARK_CAPTURE(PairPerRow, capsule_box, std::string("capsule"), std::string("box"));
BENCHMARK_CAPTURE(PairPerRow, box_box, std::string("box"), std::string("box"));
BENCHMARK_CAPTURE(PairPerRow, convex_box, std::string("convex"), std::string("box"));

}  // namespace
}  // namespace mechkin

BENCHMARK_MAIN();
