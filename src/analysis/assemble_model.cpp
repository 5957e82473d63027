#include "analysis/assemble_model.hpp"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/assembly.hpp"
#include "kinematics/position.hpp"

namespace mechkin {

namespace {

constexpr int kDenseBodies = 200;    // up to: the dense polish
constexpr double kClosed = 1e-10;    // scaled residual of an assembled pose (the runs' default tolerance)

BodyIndex OtherBody(const Joint& j, BodyIndex b) { return j.body1 == b ? j.body2 : j.body1; }

// Tree joints from `from` up to (not past) the body at depth `stop_depth`.
void Climb(const Model& m, const std::vector<int>& depth, BodyIndex* b, int stop_depth, std::vector<int>* joints) {
  while (*b != kGround && depth[*b] > stop_depth) {
    const int j = m.assembly->tree_joint[*b];
    joints->push_back(j);
    *b = OtherBody(m.joints[j], *b);
  }
}

// Each loop's path: the tree joints from its joint's body1 up to the common
// ancestor, then down to body2 (linear in the path's length).
void FindLoopPaths(Model* m) {
  AssemblyRecord& rec = *m->assembly;
  const int n = m->num_bodies();
  std::vector<int> depth(n, -1);
  for (int b = 0; b < n; ++b) {
    std::vector<int> chain;
    BodyIndex u = b;
    while (u != kGround && depth[u] < 0 && rec.tree_joint[u] >= 0) chain.push_back(u), u = OtherBody(m->joints[rec.tree_joint[u]], u);
    int d = u == kGround ? 0 : depth[u] < 0 ? 0 : depth[u];
    if (u != kGround && depth[u] < 0) depth[u] = 0;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) depth[*it] = ++d;
  }
  auto depth_of = [&](BodyIndex b) { return b == kGround ? 0 : depth[b]; };
  for (AssemblyLoop& loop : rec.loops) {
    const Joint& j = m->joints[loop.joint];
    BodyIndex a = j.body1, b = j.body2;
    std::vector<int> up, down;
    Climb(*m, depth, &a, depth_of(b), &up);
    Climb(*m, depth, &b, depth_of(a), &down);
    while (a != b && a != kGround && b != kGround && m->assembly->tree_joint[a] >= 0 &&
           m->assembly->tree_joint[b] >= 0) {
      Climb(*m, depth, &a, depth_of(a) - 1, &up);
      Climb(*m, depth, &b, depth_of(b) - 1, &down);
    }
    loop.path = up;
    loop.path.insert(loop.path.end(), down.rbegin(), down.rend());
  }
}

// Per joint: its miss at pose s in metres (an angle row counts as L × angle).
std::vector<double> JointMisses(const ConstraintSystem& sys, const SystemState& s) {
  Eigen::VectorXd phi;
  CalcPhi(sys, s, &phi);
  const double L = sys.model().characteristic_length;
  std::vector<double> miss(sys.model().joints.size(), 0.0);
  for (size_t k = 0; k < sys.entries().size(); ++k) {
    const ConstraintEntry& e = sys.entries()[k];
    if (e.from_driver || e.from_coupler) continue;
    const Constraint& c = *e.constraint;
    const double scale = c.LengthPower() == 0 ? L : 1.0;
    for (int r = 0; r < c.size(); ++r) {
      const double m = std::abs(c.Misfit(MakeInput(sys, s, k), r, phi[e.first_row + r])) * scale;
      miss[e.source] = std::max(miss[e.source], m);
    }
  }
  return miss;
}

double LoopMiss(const AssemblyLoop& loop, const std::vector<double>& miss) {
  double m = miss[loop.joint];
  for (int j : loop.path) m = std::max(m, miss[j]);
  return m;
}

// Levenberg–Marquardt in minimum-norm form on the scaled system: dq_s =
// J_sᵀ (J_s J_sᵀ + λI)⁻¹ r_s, λ shrunk after a step that lowers ‖r_s‖₂ and grown
// until one does (a far start — links drawn straight along their markers — needs
// the gradient-like steps of a large λ first). Sparse throughout, the pattern of
// J_s J_sᵀ analysed once: a chain's is banded, so an iteration is linear in it.
SolveSummary SparseMinNorm(const ConstraintSystem& sys, const std::vector<int>& rows, const SolveOptions& options,
                           SystemState* s) {
  SparseJacobian jac(sys, Formulation::Omega, rows);
  const Eigen::VectorXd w = RowScales(sys, rows), c = DimensionlessColumnScales(sys);
  const int m = static_cast<int>(rows.size());
  Eigen::SparseMatrix<double> identity(m, m);
  identity.setIdentity();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  Eigen::VectorXd phi, rs(m);
  auto scaled_residual = [&](const SystemState& state) {
    CalcPhi(sys, state, &phi);
    for (int k = 0; k < m; ++k) rs[k] = phi[rows[k]] * w[k];
  };
  SolveSummary sum;
  double lambda = 1e-3;
  bool analysed = false;
  scaled_residual(*s);
  for (sum.iterations = 0; sum.iterations < options.max_iterations; ++sum.iterations) {
    if (rs.lpNorm<Eigen::Infinity>() <= options.tolerance) break;
    jac.Fill(sys, *s);
    const Eigen::SparseMatrix<double> Js = w.asDiagonal() * jac.matrix() * c.asDiagonal();
    const Eigen::SparseMatrix<double> N = Js * Js.transpose();
    const Eigen::VectorXd r0 = rs;
    const double merit = r0.squaredNorm();
    const SystemState saved = *s;
    bool accepted = false;
    for (int tries = 0; tries < 30 && !accepted; ++tries, lambda *= 4) {
      const Eigen::SparseMatrix<double> M = N + lambda * identity;
      if (!analysed) ldlt.analyzePattern(M), analysed = true;
      ldlt.factorize(M);
      Eigen::VectorXd dq = -(Js.transpose() * ldlt.solve(r0));
      for (int b = 0; b < sys.num_bodies(); ++b) dq.segment<3>(6 * b) *= c[6 * b];
      *s = saved;
      ApplyStep(dq, s);
      scaled_residual(*s);
      accepted = rs.squaredNorm() < merit;
    }
    if (!accepted) {
      *s = saved;
      scaled_residual(*s);
      sum.message = "no further decrease of the residual (stalled)";
      break;
    }
    lambda = std::max(lambda / 16, 1e-12);
  }
  for (auto& b : s->bodies) b.UpdateDerived(0);
  sum.residual = rs.lpNorm<Eigen::Infinity>();
  sum.success = sum.residual <= options.tolerance;
  return sum;
}

std::string InFileUnits(const Model& m, double metres) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(1);
  const double v = metres / m.units.length_to_si;
  if (std::abs(v) < 10) o.precision(4);
  o << v << " " << m.units.length_name;
  return o.str();
}

std::string LoopJoints(const Model& m, const AssemblyLoop& loop) {
  std::string s;
  for (int j : loop.path) s += m.joints[j].name + ", ";
  return s + m.joints[loop.joint].name;
}

// A loop of point joints (revolute, spherical, universal, distance) is a polygon
// whose sides are fixed: the links between consecutive joint points of each body
// and the distance links. It cannot close when one side exceeds the others' sum.
std::string PolygonShortfall(const Model& m, const AssemblyLoop& loop) {
  std::vector<int> joints = loop.path;
  joints.push_back(loop.joint);
  std::vector<std::pair<double, BodyIndex>> sides;  // length, body (kGround - 1: a distance link)
  const Joint& close = m.joints[loop.joint];        // walking body1 → path → body2 → this joint
  BodyIndex walk = close.body1;
  Vec3 last = close.frame1.origin;
  for (int j : joints) if (!m.joints[j].type->HoldsPoints()) return "";
  // Sides along the path from body1, then the closing joint.
  for (int j : loop.path) {
    const Joint& jt = m.joints[j];
    const bool from1 = jt.body1 == walk;
    const Vec3 here = from1 ? jt.frame1.origin : jt.frame2.origin;
    sides.emplace_back((here - last).norm(), walk);
    if (jt.type->scalar == JointScalar::Length) sides.emplace_back(jt.length, kGround - 1);
    walk = from1 ? jt.body2 : jt.body1;
    last = from1 ? jt.frame2.origin : jt.frame1.origin;
  }
  sides.emplace_back((close.frame2.origin - last).norm(), close.body2);
  if (close.type->scalar == JointScalar::Length) sides.emplace_back(close.length, kGround - 1);
  double total = 0;
  size_t longest = 0;
  for (size_t k = 0; k < sides.size(); ++k) {
    total += sides[k].first;
    if (sides[k].first > sides[longest].first) longest = k;
  }
  const double rest = total - sides[longest].first, big = sides[longest].first;
  if (big <= rest * (1 + 1e-9)) return "";
  const std::string name = LoopName(m, loop);
  if (sides[longest].second == kGround)
    return name + " cannot close: the links reach " + InFileUnits(m, rest) + ", the pivots are " +
           InFileUnits(m, big) + " apart";
  const std::string what = sides[longest].second == kGround - 1 ? std::string("a distance link")
                                                                 : "the " + m.BodyName(sides[longest].second);
  return name + " cannot close: " + what + " spans " + InFileUnits(m, big) + ", the other links reach only " +
         InFileUnits(m, rest);
}

// The loop that cannot close: one whose sides forbid it, else the worst-missing one.
Diagnostic LoopFailure(const Model& m, const std::vector<double>& miss) {
  const AssemblyRecord& rec = *m.assembly;
  const std::string fix = "check the link lengths (the markers' points) of the loop's bodies";
  for (const AssemblyLoop& loop : rec.loops) {
    const std::string why = PolygonShortfall(m, loop);
    if (!why.empty())
      return {"/joints/" + std::to_string(loop.joint), why + " (joints " + LoopJoints(m, loop) + ")", fix};
  }
  const AssemblyLoop* worst = nullptr;
  for (const AssemblyLoop& loop : rec.loops)
    if (!worst || LoopMiss(loop, miss) > LoopMiss(*worst, miss)) worst = &loop;
  if (!worst) return {"", "the bodies cannot be placed so that every joint closes", fix};
  return {"/joints/" + std::to_string(worst->joint),
          "the loop " + LoopName(m, *worst) + " (joints " + LoopJoints(m, *worst) + ") cannot close: its joints still miss by " +
              InFileUnits(m, LoopMiss(*worst, miss)),
          fix + ", the joints' axes, and the drivers' design values"};
}

}  // namespace

// The cycle of bodies read from the one after ground (or from the first body), in
// the direction of the lower-numbered neighbour: "crank–coupler–rocker".
std::string LoopName(const Model& m, const AssemblyLoop& loop) {
  std::vector<BodyIndex> cycle;
  BodyIndex walk = m.joints[loop.joint].body1;
  cycle.push_back(walk);
  for (int j : loop.path) walk = OtherBody(m.joints[j], walk), cycle.push_back(walk);
  const auto start = std::min_element(cycle.begin(), cycle.end());  // ground (−1) first if in the loop
  std::rotate(cycle.begin(), start, cycle.end());
  if (cycle.front() == kGround) {
    cycle.erase(cycle.begin());
    if (!cycle.empty() && cycle.front() > cycle.back()) std::reverse(cycle.begin(), cycle.end());
  } else if (cycle.size() > 2 && cycle.back() < cycle[1]) {
    std::reverse(cycle.begin() + 1, cycle.end());
  }
  std::string s;
  for (BodyIndex b : cycle) s += (s.empty() ? "" : "\u2013") + m.BodyName(b);
  return s.empty() ? m.joints[loop.joint].name : s;
}

bool AssembleModel(Model* model, Diagnostic* error) {
  if (!model->assembly || model->assembly->assembled) return true;
  FindLoopPaths(model);
  const ConstraintSystem sys(*model, true);
  SystemState s(sys);
  s.SetDesignPose(*model);
  // A driver of a joint on markers is held at 0 (its markers coincide): its value is
  // measured from there, so the assembled pose does not depend on the sketch.
  for (size_t d = 0; d < model->drivers.size(); ++d) {
    const Driver& driver = model->drivers[d];
    const bool on_markers = driver.joint >= 0 && model->joints[driver.joint].on_markers;
    s.driver_values[d] = Jet::Constant(on_markers ? 0.0 : DesignDriverValue(*model, driver));
  }
  AimRotationDrivers(sys, &s);
  AssemblyRecord& rec = *model->assembly;
  std::vector<double> miss = JointMisses(sys, s);
  for (AssemblyLoop& loop : rec.loops) loop.error_before = LoopMiss(loop, miss);
  SolveOptions solve;
  solve.tolerance = 1e-12;
  solve.max_iterations = 300;
  const std::vector<int> rows = AllRows(sys);
  SolveSummary r = SparseMinNorm(sys, rows, solve, &s);
  rec.iterations += r.iterations;
  // Near the solution the dense minimum-norm Gauss–Newton (a rank-revealing
  // factorization) polishes small models to round-off.
  if (model->num_bodies() <= kDenseBodies && r.residual < 1e-6) {
    r = AssembleMinNorm(sys, rows, solve, &s);
    rec.iterations += r.iterations;
  }
  if (!(r.residual <= kClosed)) {
    *error = LoopFailure(*model, JointMisses(sys, s));
    return false;
  }
  std::string why;
  if (!AssembleHintedBranch(sys, solve, &s, &rec.iterations, &why) ||
      !AssembleFlippedBranch(sys, solve, &s, &rec.iterations, &why)) {
    *error = {"/analysis/branch", why, "give a hint nearer the wanted assembly, or check the hinted joints"};
    return false;
  }
  miss = JointMisses(sys, s);
  for (AssemblyLoop& loop : rec.loops) loop.error_after = LoopMiss(loop, miss);
  for (int b = 0; b < model->num_bodies(); ++b) {
    model->bodies[b].position = s.bodies[b].r[0];
    model->bodies[b].euler = s.bodies[b].p;
  }
  // The design pose is now on the chosen branch: the run must not apply the choice again.
  if (model->analysis) model->analysis->branch_joints.clear(), model->analysis->branch_flips.clear();
  rec.assembled = true;
  return true;
}

}  // namespace mechkin
