#include "analysis/branches.hpp"

#include <cmath>
#include <random>

#include "analysis/assembly.hpp"
#include "kinematics/position.hpp"

namespace mechkin {

namespace {


// Every axis-carrying joint with its two axes pointing the same way.
bool AxesAsDrawn(const Model& m, const SystemState& s) {
  for (const Joint& j : m.joints) {
    if (j.type->frames != JointFrameRule::Axis) continue;
    if ((s.Kin(j.body1).A * j.frame1.h).dot(s.Kin(j.body2).A * j.frame2.h) < 0) return false;
  }
  return true;
}

}  // namespace

BranchCount CountBranches(const Model& model, int restarts, unsigned long seed, const std::function<bool()>& stop) {
  BranchCount out;
  if (model.num_bodies() > 200 || model.num_bodies() == 0) return out;
  const ConstraintSystem sys(model, true);
  SystemState design(sys);
  SolveOptions solve;
  solve.max_iterations = 100;
  int iterations = 0;
  std::string why;
  design.SetDesignPose(model);
  std::vector<SystemState> found;
  if (AssembleDesignPose(sys, solve, &design, &iterations, &why)) found.push_back(design);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double L = model.characteristic_length;
  const std::vector<int> rows = AllRows(sys);
  int tried = 0;
  for (; tried < restarts && !(stop && stop()); ++tried) {
    SystemState s = design;
    for (auto& b : s.bodies) {
      const Vec3 move(unit(rng), unit(rng), unit(rng)), axis(unit(rng), unit(rng), unit(rng));
      const Vec4 p = QuatMultiply(b.p, QuatFromAxisAngle(axis.normalized(), M_PI * unit(rng)));
      b.SetPose(b.r[0] + L * move, p.normalized());
    }
    if (!AssembleMinNorm(sys, rows, solve, &s).success) continue;
    ++out.converged;
    if (!AxesAsDrawn(model, s)) continue;
    bool known = false;
    for (const auto& f : found) known = known || PoseDistance(f, s, L) < 1e-6;
    if (!known) found.push_back(s);
  }
  out.restarts = tried;
  out.branches = static_cast<int>(found.size());
  for (const auto& f : found) out.distances.push_back(PoseDistance(f, design, L));
  return out;
}

}  // namespace mechkin
