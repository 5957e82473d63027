#include "analysis/contact_watch.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/assembly.hpp"
#include "analysis/kinematic_analysis.hpp"

namespace mechkin {
namespace {

constexpr double kContactResolution = 1e-9;  // s: the bisection's bracket (§13)
constexpr int kSearchBudget = 64;            // trial solves per pair and step between two clear rows
// The chord of the relative motion understates a curved path: search where the
// rows' clearances are less than this many chords.
constexpr double kPathMargin = 1.5;

std::vector<ClearancePair> SolvedPairs(const Model& model, const std::vector<int>& needed) {
  std::vector<ClearancePair> out;
  auto solved = [&](BodyIndex b) {
    return b == kGround || needed.empty() || std::find(needed.begin(), needed.end(), b) != needed.end();
  };
  for (const ClearancePair& p : ClearanceOutputPairs(model))
    if (solved(p.body1) && solved(p.body2)) out.push_back(p);
  return out;
}

// Body2's pose in body1's frame: rotation and origin.
std::pair<Mat3, Vec3> Relative(const SystemState& s, const ClearancePair& p) {
  const BodyKinematics &a = s.Kin(p.body1), &b = s.Kin(p.body2);
  return {a.A.transpose() * b.A, a.A.transpose() * (b.r[0] - a.r[0])};
}

std::string DriverValues(const Model& model, const std::vector<double>& values) {
  std::ostringstream o;
  o.precision(12);
  for (size_t d = 0; d < model.drivers.size() && d < values.size(); ++d) {
    const bool angle = IsAngleDriver(model.drivers[d]);
    o << (d == 0 ? " (" : ", ") << "driver `" << model.drivers[d].name << "` = "
      << values[d] / (angle ? model.units.angle_to_si : model.units.length_to_si) << " "
      << (angle ? model.units.angle_name : model.units.length_name);
  }
  if (!model.drivers.empty()) o << ")";
  return o.str();
}

}  // namespace

ContactWatch::ContactWatch(const Model& model, const std::vector<int>& needed_bodies)
    : model_(model), eval_(std::make_unique<ClearanceEvaluator>(model, SolvedPairs(model, needed_bodies))) {
  distance_.assign(eval_->size(), 0.0);
}

std::vector<ContactHit> ContactWatch::Start(const SystemState& s) {
  std::vector<ContactHit> hits;
  for (int k = 0; k < eval_->size(); ++k) {
    const ClearanceValue v = eval_->Evaluate(s, k, false);
    distance_[k] = v.distance;
    if (v.distance > 0) continue;
    const ClearancePair& p = eval_->pairs()[k];
    ContactHit hit{s.t, p.output, p.body1, p.body2, 0.5 * (v.point1 + v.point2), v.distance, true, {}};
    for (const Jet& d : s.driver_values) hit.driver_values.push_back(d.c[0]);
    hits.push_back(hit);
  }
  return hits;
}

std::vector<ContactHit> ContactWatch::Check(KinematicsWorkspace& ws, const SystemState& prev, const SystemState& s,
                                            int predictor_order) {
  predictor_order_ = predictor_order;
  std::vector<ContactHit> hits;
  for (int k = 0; k < eval_->size(); ++k) {
    const double before = distance_[k];
    distance_[k] = eval_->Evaluate(s, k, false).distance;
    if (!(before > 0)) continue;  // in contact at the last row: not a new contact
    // The probes (copies of the poses) only where a contact is possible: rows far
    // apart allocate nothing here.
    if (distance_[k] <= 0) {
      hits.push_back(Locate(ws, prev, k, Probe{prev, before}, Probe{s, distance_[k]}));
      continue;
    }
    if (!MayTouchBetween(k, prev, before, s, distance_[k])) continue;
    int budget = kSearchBudget;
    if (const auto bracket = Search(ws, prev, k, Probe{prev, before}, Probe{s, distance_[k]}, &budget))
      hits.push_back(Locate(ws, prev, k, bracket->first, bracket->second));
  }
  std::sort(hits.begin(), hits.end(), [](const ContactHit& x, const ContactHit& y) { return x.t < y.t; });
  return hits;
}

// No point of body2's shapes (within its reach ρ of its origin) moves relative to
// body1 by more than δ = |Δc| + 2 sin(θ/2) ρ along the chord from a to b (Δc: its
// origin's move, θ: the relative turn); the shapes cannot meet on that chord when
// the two clearances add up to more than δ.
bool ContactWatch::MayTouchBetween(int pair, const SystemState& a, double da, const SystemState& b,
                                   double db) const {
  const ClearancePair& p = eval_->pairs()[pair];
  const auto [Ra, ca] = Relative(a, p);
  const auto [Rb, cb] = Relative(b, p);
  const double cos_turn = std::clamp(0.5 * ((Rb * Ra.transpose()).trace() - 1), -1.0, 1.0);
  const double chord = (cb - ca).norm() + 2 * std::sin(0.5 * std::acos(cos_turn)) * eval_->Reach(p.body2);
  return da + db <= kPathMargin * chord;
}

// Depth first in time order between two clear poses: halve while the bodies may
// touch between, until a trial pose touches (the bracket before it) or the budget
// or the resolution runs out.
std::optional<std::pair<ContactWatch::Probe, ContactWatch::Probe>> ContactWatch::Search(
    KinematicsWorkspace& ws, const SystemState& prev, int pair, const Probe& a, const Probe& b, int* budget) const {
  if (*budget <= 0 || b.state.t - a.state.t <= kContactResolution ||
      !MayTouchBetween(pair, a.state, a.distance, b.state, b.distance))
    return std::nullopt;
  --*budget;
  const Probe mid = Solve(ws, prev, 0.5 * (a.state.t + b.state.t), pair);
  if (mid.distance <= 0) return std::make_pair(a, mid);
  if (auto early = Search(ws, prev, pair, a, mid, budget)) return early;
  return Search(ws, prev, pair, mid, b, budget);
}

// Bisection on the sign of the clearance over [a, b] (a clear, b touching) to
// kContactResolution, then the secant of the two clearances inside the bracket; the
// contact point is between the closest points at that time.
ContactHit ContactWatch::Locate(KinematicsWorkspace& ws, const SystemState& prev, int pair, Probe a, Probe b) const {
  while (b.state.t - a.state.t > kContactResolution) {
    Probe mid = Solve(ws, prev, 0.5 * (a.state.t + b.state.t), pair);
    if (mid.distance > 0) a = std::move(mid);
    else b = std::move(mid);
  }
  const double t = a.state.t + (b.state.t - a.state.t) * a.distance / (a.distance - b.distance);
  const ClearancePair& p = eval_->pairs()[pair];
  const Probe at = Solve(ws, prev, t, pair);
  const ClearanceValue v = eval_->Evaluate(at.state, pair, false);
  ContactHit hit{t, p.output, p.body1, p.body2, 0.5 * (v.point1 + v.point2), 0, false, {}};
  for (const Jet& d : at.state.driver_values) hit.driver_values.push_back(d.c[0]);
  return hit;
}

// The exact motion at t: a tight position solve from the Taylor prediction off
// `prev` (the run's branch), as joint limits are located.
ContactWatch::Probe ContactWatch::Solve(KinematicsWorkspace& ws, const SystemState& prev, double t, int pair) const {
  SolveOptions tight;
  tight.tolerance = 1e-14;
  tight.max_iterations = 100;
  Probe probe{prev, 0};
  PredictPose(t - prev.t, predictor_order_, &probe.state);
  EvalDriverFunctions(model_, t, &probe.state);
  AimRotationDrivers(ws.system(), &probe.state);
  SolvePosition(ws, tight, &probe.state, false);
  probe.state.t = t;
  probe.distance = eval_->Evaluate(probe.state, pair, false).distance;
  return probe;
}

std::string ContactMessage(const Model& model, const ContactHit& hit, int rows_done, bool stops) {
  std::ostringstream o;
  o.precision(12);
  const double L = 1 / model.units.length_to_si;
  o << "bodies `" << model.BodyName(hit.body1) << "` and `" << model.BodyName(hit.body2) << "` "
    << (hit.at_start ? "are in contact at the start, t = " : "come into contact at t = ") << hit.t << " s"
    << DriverValues(model, hit.driver_values) << " at [" << hit.point.x() * L << ", " << hit.point.y() * L << ", "
    << hit.point.z() * L << "] " << model.units.length_name;
  if (hit.at_start) o << " (clearance " << hit.clearance * L << " " << model.units.length_name << ")";
  if (hit.output >= 0) o << ", clearance output `" << model.outputs[hit.output].name << "`";
  if (stops) o << "; the run stops there after " << rows_done << " rows (`--on-contact report` goes on and notes it)";
  return o.str();
}

bool WatchContacts(ContactWatch* watch, KinematicsWorkspace& ws, const SystemState& prev, const SystemState& s,
                   int step, int predictor_order, bool stop, AnalysisReport* rep) {
  if (!watch || watch->empty()) return false;
  const std::vector<ContactHit> hits = step == 0 ? watch->Start(s) : watch->Check(ws, prev, s, predictor_order);
  for (const ContactHit& hit : hits) {
    rep->contacts.push_back(hit);
    if (stop) {
      rep->stop = StopKind::Contact;
      rep->message = ContactMessage(ws.system().model(), hit, rep->rows, true);
      return true;
    }
    rep->notes.push_back(ContactMessage(ws.system().model(), hit, rep->rows, false));
  }
  return false;
}

}  // namespace mechkin
