#include "analysis/joint_limits.hpp"

#include <cmath>
#include <sstream>

#include "analysis/assembly.hpp"

namespace mechkin {

bool LimitOnRotation(const JointDescriptor* t) { return t->limit == JointLimit::Angle; }

// The rotation driver's angle θ = atan2(g₁ᵀf₂, f₁ᵀf₂) (§3.9) continued from ref, or
// the slide h₁ᵀd (§3.8) between the joint frames.
double LimitedCoordinate(const Joint& j, const SystemState& s, double ref) {
  const BodyKinematics &a = s.Kin(j.body1), &b = s.Kin(j.body2);
  if (!LimitOnRotation(j.type))
    return (a.A * j.frame1.h).dot(b.Point(j.frame2.origin) - a.Point(j.frame1.origin));
  const Vec3 f2 = b.A * j.frame2.f;
  return UnwrapAngle((a.A * j.frame1.g).dot(f2), (a.A * j.frame1.f).dot(f2), ref);
}

// θ̇ = h·(ω₂ − ω₁) on the joint's manifold; ṡ = ḣ₁ᵀd + h₁ᵀḋ.
double LimitedCoordinateRate(const Joint& j, const SystemState& s) {
  const BodyKinematics &a = s.Kin(j.body1), &b = s.Kin(j.body2);
  const Vec3 h = a.A * j.frame1.h;
  if (LimitOnRotation(j.type)) return h.dot(b.A * b.w[0] - a.A * a.w[0]);
  const Vec3 d = b.Point(j.frame2.origin) - a.Point(j.frame1.origin);
  const Vec3 dd = b.PointDerivative(j.frame2.origin, 1) - a.PointDerivative(j.frame1.origin, 1);
  return a.VectorDerivative(j.frame1.h, 1).dot(d) + h.dot(dd);
}

JointLimitWatch::JointLimitWatch(const Model& model) : model_(model) {
  for (size_t k = 0; k < model.joints.size(); ++k)
    if (model.joints[k].limits) joints_.push_back(static_cast<int>(k));
  values_.assign(joints_.size(), 0.0);
}

std::optional<int> JointLimitWatch::Start(const SystemState& s) {
  std::optional<int> outside;
  for (size_t k = 0; k < joints_.size(); ++k) {
    const Joint& j = model_.joints[joints_[k]];
    values_[k] = LimitedCoordinate(j, s, 0.0);
    const double lo = j.limits->first, hi = j.limits->second;
    if (!outside && (values_[k] < lo || values_[k] > hi)) outside = joints_[k];
  }
  return outside;
}

void JointLimitWatch::Accept(const SystemState& s) {
  for (size_t k = 0; k < joints_.size(); ++k) values_[k] = LimitedCoordinate(model_.joints[joints_[k]], s, values_[k]);
}

std::optional<JointLimitHit> JointLimitWatch::Check(KinematicsWorkspace& ws, const SystemState& prev,
                                                    const SystemState& s, int predictor_order) {
  std::optional<JointLimitHit> first;
  for (size_t k = 0; k < joints_.size(); ++k) {
    const Joint& j = model_.joints[joints_[k]];
    const double before = values_[k], now = LimitedCoordinate(j, s, before);
    const double lo = j.limits->first, hi = j.limits->second;
    const bool up = before <= hi && now > hi, down = before >= lo && now < lo;
    if (!up && !down) continue;
    const double bound = up ? hi : lo;
    JointLimitHit hit = Locate(ws, prev, s.t, now - bound, joints_[k], bound, before, predictor_order);
    hit.upper = up;
    if (!first || hit.t < first->t) first = hit;
  }
  return first;
}

// Newton in time on q(t) − bound from the secant guess, kept inside the bracket
// (prev.t, t_hi] by bisection when a step leaves it; each trial a tight solve from
// the Taylor prediction off `prev` (the run's branch) and the velocity solve.
JointLimitHit JointLimitWatch::Locate(KinematicsWorkspace& ws, const SystemState& prev, double t_hi, double q_hi,
                                      int joint, double bound, double ref, int predictor_order) const {
  const Joint& j = model_.joints[joint];
  SolveOptions tight;
  tight.tolerance = 1e-14;
  tight.max_iterations = 100;
  double a = prev.t, b = t_hi, qa = ref - bound;
  double t = a + (b - a) * qa / (qa - q_hi);
  SystemState probe = prev;
  for (int it = 0; it < 50; ++it) {
    probe = prev;
    PredictPose(t - prev.t, predictor_order, &probe);
    EvalDriverFunctions(model_, t, &probe);
    AimRotationDrivers(ws.system(), &probe);
    SolvePosition(ws, tight, &probe, false);
    SolveDerivatives(ws, 1, &probe);
    const double q = LimitedCoordinate(j, probe, ref) - bound;
    if (std::abs(q) <= 1e-14 * (1 + std::abs(bound))) break;
    if ((q > 0) == (qa > 0)) a = t, qa = q;
    else b = t;
    const double rate = LimitedCoordinateRate(j, probe);
    double next = rate != 0 ? t - q / rate : 0.5 * (a + b);
    if (!(next > a && next < b)) next = 0.5 * (a + b);
    const bool converged = std::abs(next - t) <= 1e-15 * (1 + std::abs(t));
    t = next;
    if (converged) break;
  }
  JointLimitHit hit;
  hit.t = t;
  hit.joint = joint;
  hit.bound = bound;
  EvalDriverFunctions(model_, t, &probe);
  for (const Jet& d : probe.driver_values) hit.driver_values.push_back(d.c[0]);
  return hit;
}

std::string JointLimitMessage(const Model& model, const JointLimitHit& hit, int rows_done, bool stops) {
  const Joint& j = model.joints[hit.joint];
  const bool rot = LimitOnRotation(j.type);
  const double to_file = 1 / (rot ? model.units.angle_to_si : model.units.length_to_si);
  std::ostringstream o;
  o.precision(12);
  o << "joint `" << j.name << "` reaches its " << (hit.upper ? "upper" : "lower") << " limit " << hit.bound * to_file
    << " " << (rot ? model.units.angle_name : model.units.length_name) << " at t = " << hit.t << " s";
  for (size_t d = 0; d < model.drivers.size() && d < hit.driver_values.size(); ++d) {
    const bool angle = IsAngleDriver(model.drivers[d]);
    o << (d == 0 ? " (" : ", ") << "driver `" << model.drivers[d].name << "` = "
      << hit.driver_values[d] / (angle ? model.units.angle_to_si : model.units.length_to_si) << " "
      << (angle ? model.units.angle_name : model.units.length_name);
  }
  if (!model.drivers.empty()) o << ")";
  if (stops) o << "; the run stops there after " << rows_done << " rows (`--on-limit report` goes on and notes it)";
  return o.str();
}

}  // namespace mechkin
