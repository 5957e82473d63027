#include "analysis/assembly.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "kinematics/position.hpp"

namespace mechkin {

namespace {

Vec3 DesignPoint(const Model& m, BodyIndex b, const Vec3& s) {
  return b == kGround ? s : Vec3(m.bodies[b].position + CalcA(m.bodies[b].euler) * s);
}
Vec3 DesignVector(const Model& m, BodyIndex b, const Vec3& v) {
  return b == kGround ? v : Vec3(CalcA(m.bodies[b].euler) * v);
}

}  // namespace

// A joint on markers measures from the markers' coincidence, so the pose drawn has
// the coordinate it shows: θ = atan2(g_iᵀf_j, f_iᵀf_j) (constraints.md §3.9) in
// (−π, π], or the slide h_iᵀd_ij (§3.8). The assembly then keeps the drawn branch.
double DesignDriverValue(const Model& m, const Driver& d) {
  if (d.kind == DriverKind::Distance)
    return (DesignPoint(m, d.body2, d.point2) - DesignPoint(m, d.body1, d.point1)).norm();
  if (d.joint < 0 || !m.joints[d.joint].on_markers) return 0;  // frames from the design pose: 0 there
  if (d.kind == DriverKind::JointRotation) {
    const Vec3 fj = DesignVector(m, d.body2, d.frame2.f);
    return std::atan2(DesignVector(m, d.body1, d.frame1.g).dot(fj), DesignVector(m, d.body1, d.frame1.f).dot(fj));
  }
  return DesignVector(m, d.body1, d.frame1.h)
      .dot(DesignPoint(m, d.body2, d.frame2.origin) - DesignPoint(m, d.body1, d.frame1.origin));
}

// A coupler's rotation on a joint that a rotation driver drives is aimed at the
// driver's value too (its whole turns); its other rotations keep their references,
// carried over whole turns from step to step (UpdateAngleReferences, §3.11).
void AimCoupler(const ConstraintSystem& sys, const ConstraintEntry& en, size_t e, SystemState* s) {
  const Model& m = sys.model();
  int angle = 0;
  for (const CouplerCoordinate& cc : m.couplers[en.source].coordinates) {
    if (!cc.rotation) continue;
    for (size_t d = 0; d < m.drivers.size(); ++d)
      if (m.drivers[d].kind == DriverKind::JointRotation && m.drivers[d].joint == cc.joint)
        s->angle_ref[angle == 0 ? e : en.extra_angle_slot + angle - 1] = s->driver_values[d].c[0];
    ++angle;
  }
}

void AimRotationDrivers(const ConstraintSystem& sys, SystemState* s) {
  for (size_t e = 0; e < sys.entries().size(); ++e) {
    const ConstraintEntry& en = sys.entries()[e];
    if (en.from_driver && en.constraint->HasAngle()) s->angle_ref[e] = s->driver_values[en.source].c[0];
    if (en.from_coupler) AimCoupler(sys, en, e, s);
  }
}

std::string DescribeResiduals(const ConstraintSystem& sys, const SystemState& s, const std::vector<int>& solved,
                              const Eigen::VectorXd& solved_scales, int count) {
  // A solve that ran block by block has no whole active set: list over all rows
  // then, so the list is never empty (issue 23 item 10).
  const bool whole = !solved.empty() && solved_scales.size() == static_cast<Eigen::Index>(solved.size());
  const std::vector<int> rows = whole ? solved : AllRows(sys);
  const Eigen::VectorXd scales = whole ? solved_scales : RowScales(sys, rows);
  if (rows.empty()) return " none (no equations)";
  Eigen::VectorXd phi;
  CalcPhi(sys, s, &phi);
  std::vector<std::pair<double, int>> r;
  for (size_t k = 0; k < rows.size(); ++k) r.emplace_back(std::abs(phi[rows[k]]) * scales[k], rows[k]);
  std::sort(r.rbegin(), r.rend());
  const Units& u = sys.model().units;
  std::ostringstream o;
  for (int k = 0; k < count && k < static_cast<int>(r.size()); ++k) {
    const auto [e, local] = sys.Locate(r[k].second);
    const Constraint& c = *sys.entries()[e].constraint;
    const double miss = c.Misfit(MakeInput(sys, s, e), local, phi[r[k].second]);
    o << "\n    " << sys.DescribeRow(r[k].second) << ": misses by ";
    if (c.LengthPower() == 0) o << std::abs(miss) / u.angle_to_si << " " << u.angle_name;
    else o << std::abs(miss) / u.length_to_si << " " << u.length_name;
  }
  return o.str();
}

bool AssembleDesignPose(const ConstraintSystem& sys, const SolveOptions& solve, SystemState* s, int* iterations,
                        std::string* message) {
  const Model& model = sys.model();
  for (size_t d = 0; d < model.drivers.size(); ++d)
    s->driver_values[d] = Jet::Constant(DesignDriverValue(model, model.drivers[d]));
  AimRotationDrivers(sys, s);
  if (6 * sys.num_bodies() > 1200) return true;  // dense min-norm too costly: start from the file's pose
  SolveOptions rough = solve;
  rough.max_iterations = 100;
  const std::vector<int> all = AllRows(sys);
  const SolveSummary a = AssembleMinNorm(sys, all, rough, s);
  *iterations += a.iterations;
  if (a.success) return true;
  *message = "the design pose cannot be assembled (scaled residual " + std::to_string(a.residual) +
             "); the equations that cannot close:" + DescribeResiduals(sys, *s, all, RowScales(sys, all), 3) +
             "\n  Check the lengths and joint positions in the file.";
  return false;
}

double PoseDistance(const SystemState& a, const SystemState& b, double length) {
  double d = 0;
  for (size_t k = 0; k < a.bodies.size(); ++k) {
    d = std::max(d, (a.bodies[k].r[0] - b.bodies[k].r[0]).norm() / length);
    d = std::max(d, 2 * std::acos(std::min(1.0, std::abs(a.bodies[k].p.dot(b.bodies[k].p)))));
  }
  return d;
}

namespace {

// A revolute's angle (θ = atan2(g₁ᵀf₂, f₁ᵀf₂), the rotation driver's, constraints.md §3.9)
// or a prismatic's slide along h₁, at pose s.
double JointCoordinate(const SystemState& s, const Joint& j) {
  const BodyKinematics& k1 = s.Kin(j.body1);
  const BodyKinematics& k2 = s.Kin(j.body2);
  const Vec3 h1 = k1.A * j.frame1.h;
  if (j.type->coordinates == JointCoordinates::Slide)
    return ((k2.r[0] + k2.A * j.frame2.origin) - (k1.r[0] + k1.A * j.frame1.origin)).dot(h1);
  const Vec3 f1 = k1.A * j.frame1.f, f2 = k2.A * j.frame2.f;
  return std::atan2(h1.dot(f1.cross(f2)), f1.dot(f2));
}

// Turns (slides) body2 of joint j rigidly about (along) the joint's axis so that its
// coordinate reads `value` (body1 the other way when body2 is ground): the start
// of the hinted assembly is then already on the hinted side of every fold.
void SetJointCoordinate(const Joint& j, double value, SystemState* s) {
  const BodyKinematics& k1 = s->Kin(j.body1);
  const Vec3 h = k1.A * j.frame1.h, o = k1.r[0] + k1.A * j.frame1.origin;
  double delta = value - JointCoordinate(*s, j);
  if (j.type->coordinates == JointCoordinates::Angle) delta = std::remainder(delta, 2 * M_PI);
  const BodyIndex moved = j.body2 != kGround ? j.body2 : j.body1;
  if (j.body2 == kGround) delta = -delta;
  BodyKinematics& k = s->bodies[moved];
  if (j.type->coordinates == JointCoordinates::Slide) {
    k.SetPose(k.r[0] + delta * h, k.p);
    return;
  }
  const Vec4 turn = QuatFromAxisAngle(h, delta);
  k.SetPose(o + CalcA(turn) * (k.r[0] - o), QuatMultiply(turn, k.p).normalized());
}

// Joints and drivers closed from pose s (min-norm Gauss–Newton).
bool CloseAll(const ConstraintSystem& sys, const SolveOptions& rough, SystemState* s, int* iterations) {
  const SolveSummary r = AssembleMinNorm(sys, AllRows(sys), rough, s);
  *iterations += r.iterations;
  return r.success;
}

// The joints with the hinted coordinates held (the drivers set aside), then the
// joints and drivers again from there.
// With `keep_drivers` the drivers stay too: a least-squares compromise between the
// drivers and the hints (it cannot close exactly) that lands near the hinted branch.
bool HeldThenClosed(const ConstraintSystem& sys, const SolveOptions& rough,
                    const std::vector<std::pair<int, double>>& hints, bool keep_drivers, SystemState* s,
                    int* iterations) {
  const Model& model = sys.model();
  Model hinted = model;
  if (!keep_drivers) hinted.drivers.clear();
  const size_t first_hint = hinted.drivers.size();
  for (const auto& [joint, value] : hints) {
    const Joint& j = model.joints[joint];
    Driver d;
    d.name = "branch hint " + j.name;
    d.kind = j.type->coordinates == JointCoordinates::Angle ? DriverKind::JointRotation : DriverKind::JointTranslation;
    d.joint = joint;
    d.body1 = j.body1, d.body2 = j.body2, d.frame1 = j.frame1, d.frame2 = j.frame2;
    hinted.drivers.push_back(d);
  }
  const ConstraintSystem hsys(hinted, true);
  SystemState hs(hsys);
  hs.bodies = s->bodies;
  for (size_t k = 0; k < first_hint; ++k) hs.driver_values[k] = s->driver_values[k];
  for (size_t k = first_hint; k < hinted.drivers.size(); ++k) hs.driver_values[k] = Jet::Constant(hints[k - first_hint].second);
  AimRotationDrivers(hsys, &hs);
  const SolveSummary a = AssembleMinNorm(hsys, AllRows(hsys), rough, &hs);
  *iterations += a.iterations;
  if (!a.success && !keep_drivers) return false;
  for (size_t b = 0; b < s->bodies.size(); ++b) s->bodies[b].SetPose(hs.bodies[b].r[0], hs.bodies[b].p);
  return CloseAll(sys, rough, s, iterations);
}

// How far pose s is from the hints: Σ |coordinate − hint| (rad, or slide / size).
double HintGap(const Model& model, const SystemState& s, const std::vector<std::pair<int, double>>& hints) {
  double gap = 0;
  for (const auto& [joint, value] : hints) {
    const Joint& j = model.joints[joint];
    const double d = JointCoordinate(s, j) - value;
    gap += j.type->coordinates == JointCoordinates::Angle ? std::abs(std::remainder(d, 2 * M_PI)) : std::abs(d) / model.characteristic_length;
  }
  return gap;
}

// Signs of h₁·h₂ of the axis-carrying joints: an assembly that turns one over (a
// joint mounted backwards) is not a branch of the mechanism (analysis/branches.hpp).
std::vector<bool> AxesAlong(const Model& m, const SystemState& s) {
  std::vector<bool> out;
  for (const Joint& j : m.joints)
    if (j.type->frames == JointFrameRule::Axis)
      out.push_back((s.Kin(j.body1).A * j.frame1.h).dot(s.Kin(j.body2).A * j.frame2.h) > 0);
  return out;
}

// From pose s, four starts — the hinted joints' bodies turned to the hints then the
// hints held, the same start closed directly, the pose itself with the hints held,
// and the turned start with the hints and the drivers held together — and the
// assembly nearest the hints among those that close with every axis as it was.
bool HintedAssembly(const ConstraintSystem& sys, const SolveOptions& solve,
                    const std::vector<std::pair<int, double>>& hints, SystemState* s, int* iterations,
                    std::string* message) {
  const Model& model = sys.model();
  SolveOptions rough = solve;
  rough.max_iterations = 100;
  std::optional<SystemState> best;
  double best_gap = 0;
  const std::vector<bool> axes = AxesAlong(model, *s);
  for (int start = 0; start < 4; ++start) {
    SystemState t = *s;
    if (start != 2)
      for (const auto& [joint, value] : hints) SetJointCoordinate(model.joints[joint], value, &t);
    const bool closed = start == 1 ? CloseAll(sys, rough, &t, iterations)
                                   : HeldThenClosed(sys, rough, hints, start == 3, &t, iterations);
    if (!closed || AxesAlong(model, t) != axes) continue;
    const double gap = HintGap(model, t, hints);
    if (!best || gap < best_gap) best = t, best_gap = gap;
  }
  if (!best) {
    *message = "the mechanism cannot be assembled on the hinted branch at the drivers' design values "
               "(the joints cannot take the hinted coordinates)";
    return false;
  }
  *s = *best;
  return true;
}

}  // namespace

bool AssembleHintedBranch(const ConstraintSystem& sys, const SolveOptions& solve, SystemState* s, int* iterations,
                          std::string* message) {
  const Model& model = sys.model();
  if (!model.analysis || model.analysis->branch_joints.empty()) return true;
  return HintedAssembly(sys, solve, model.analysis->branch_joints, s, iterations, message);
}

// The other closure at joint J: hinted assemblies at J's coordinate ± 10°, ± 20° …
// (± 5 %, 10 % … of the mechanism's size for a slide), the first that lands on a
// pose with another coordinate of J.
bool AssembleFlippedBranch(const ConstraintSystem& sys, const SolveOptions& solve, SystemState* s, int* iterations,
                           std::string* message) {
  const Model& model = sys.model();
  if (!model.analysis) return true;
  const double L = model.characteristic_length;
  for (int joint : model.analysis->branch_flips) {
    const Joint& j = model.joints[joint];
    const bool turn = j.type->coordinates == JointCoordinates::Angle;
    const double c0 = JointCoordinate(*s, j), step = turn ? 10 * M_PI / 180 : 0.05 * L;
    bool flipped = false;
    for (int k = 1; k <= (turn ? 18 : 40) && !flipped; ++k)
      for (int sign : {1, -1}) {
        SystemState t = *s;
        std::string why;
        if (!HintedAssembly(sys, solve, {{joint, c0 + sign * k * step}}, &t, iterations, &why)) continue;
        const double d = turn ? std::remainder(JointCoordinate(t, j) - c0, 2 * M_PI) : (JointCoordinate(t, j) - c0) / L;
        if (std::abs(d) > 1e-6 && PoseDistance(t, *s, L) > 1e-6) {
          *s = t;
          flipped = true;
          break;
        }
      }
    if (!flipped) {
      *message = "'flip' of joint '" + j.name + "': no other closure of its loop was found at the drivers' design values";
      return false;
    }
  }
  return true;
}

namespace {

constexpr int kMaxContinuationSteps = 1000;

// Number of continuation increments: at most 10° per rotation driver and 5 % of
// the characteristic length per translation or distance driver. Computed in
// floating point and capped, so a far start never overflows an int.
double ContinuationSteps(const Model& model, const std::vector<double>& from, const std::vector<double>& to) {
  double worst = 0;
  for (size_t d = 0; d < model.drivers.size(); ++d)
    worst = std::max(worst, std::abs(to[d] - from[d]) /
                                (IsAngleDriver(model.drivers[d]) ? 10 * M_PI / 180 : 0.05 * model.characteristic_length));
  return std::max(1.0, std::ceil(worst));
}

// The pose depends on a rotation driver's value only modulo a full turn. When
// the ramp to `start` would be absurdly long (a far start time, thousands of
// turns), angles are ramped to the equivalent value nearest the design pose
// instead; the multi-turn angle is then set to the driver's true value.
std::vector<double> ContinuationTargets(const Model& model, const std::vector<double>& from, std::vector<double> to) {
  if (ContinuationSteps(model, from, to) <= kMaxContinuationSteps) return to;
  // A screw couples its angle to a slide: its turns cannot be dropped.
  for (const Joint& j : model.joints)
    if (j.type->scalar == JointScalar::Pitch) return to;
  for (size_t d = 0; d < model.drivers.size(); ++d)
    if (IsAngleDriver(model.drivers[d])) to[d] = from[d] + std::remainder(to[d] - from[d], 2 * M_PI);
  return to;
}

}  // namespace

// Where the continuation to the start values stopped, per moving driver: the last
// value reached and the one that failed, so the message names the limit's bracket.
static std::string DescribeReach(const Model& model, const std::vector<double>& from, const std::vector<double>& to,
                          double reached, double failed) {
  std::ostringstream o;
  o.precision(6);
  for (size_t d = 0; d < model.drivers.size(); ++d) {
    if (to[d] == from[d]) continue;
    const bool angle = model.drivers[d].kind == DriverKind::JointRotation || model.drivers[d].kind == DriverKind::BodyRotation;
    const double unit = angle ? model.units.angle_to_si : model.units.length_to_si;
    const std::string& name = angle ? model.units.angle_name : model.units.length_name;
    auto at = [&](double lambda) { return (from[d] + lambda * (to[d] - from[d])) / unit; };
    o << (o.tellp() > 0 ? "; " : ": ") << "driver `" << model.drivers[d].name << "` wants " << at(1) << " " << name
      << " at t = start but the mechanism follows it from " << at(0) << " only to " << at(reached) << " " << name
      << " (fails at " << at(failed) << " " << name
      << "): a limit of motion or singular position lies between these; start inside the range";
  }
  return o.str();
}

bool ContinueToStart(KinematicsWorkspace& ws, double start, const SolveOptions& solve, SystemState* s,
                     int* iterations, std::string* message, const std::function<void(const SystemState&)>& on_pose) {
  const ConstraintSystem& sys = ws.system();
  const Model& model = sys.model();
  EvalDriverFunctions(model, start, s);
  const std::vector<Jet> at_start = s->driver_values;
  std::vector<double> from, to;
  for (size_t d = 0; d < model.drivers.size(); ++d) {
    from.push_back(DesignDriverValue(model, model.drivers[d]));
    to.push_back(at_start[d].c[0]);
  }
  to = ContinuationTargets(model, from, to);
  const double steps = ContinuationSteps(model, from, to);
  if (steps > kMaxContinuationSteps) {
    *message = "the drivers' values at t = start are too far from the design pose to follow (" +
               std::to_string(static_cast<long long>(std::min(steps, 1e15))) +
               " increments): start the analysis nearer the design pose, or draw the design pose nearer the start";
    return false;
  }
  const int substeps = static_cast<int>(steps);
  SolveOptions o = solve;
  o.max_iterations = 50;
  for (int k = 1; k <= substeps + 1; ++k) {
    // The last pass sets the drivers' true values (multi-turn angles included).
    const double lambda = std::min(1.0, static_cast<double>(k) / substeps);
    for (size_t d = 0; d < model.drivers.size(); ++d)
      s->driver_values[d] = k > substeps ? at_start[d] : Jet::Constant(from[d] + lambda * (to[d] - from[d]));
    AimRotationDrivers(sys, s);
    const SolveSummary r = ws.newton().Solve(o, s);
    *iterations += r.iterations;
    if (!r.success) {
      *message = "cannot reach the drivers' values at t = start from the design pose (" + r.message + ")" +
                 DescribeReach(model, from, to, std::min(1.0, static_cast<double>(k - 1) / substeps), lambda) +
                 "; largest residuals:" + DescribeResiduals(sys, *s, ws.active(), ws.newton().scales(), 3);
      return false;
    }
    UpdateAngleReferences(sys, s);
    if (on_pose) on_pose(*s);
  }
  return true;
}

}  // namespace mechkin
