#include "analysis/clearance_sweep.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "analysis/check_report.hpp"

namespace mechkin {
namespace {

std::vector<double> DriverValuesOf(const SystemState& s) {
  std::vector<double> v;
  for (const Jet& d : s.driver_values) v.push_back(d.c[0]);
  return v;
}

// A first contact between rows (the watch's) lowers its pair's minimum to 0 there.
void TakeContacts(const std::vector<ContactHit>& hits, ClearanceSweep* sweep) {
  for (const ContactHit& h : hits)
    for (ClearanceMinimum& m : sweep->pairs)
      if (m.pair.output == h.output && h.output >= 0 && !h.at_start && m.clearance > 0) {
        m.clearance = 0;
        m.t = h.t;
        m.driver_values = h.driver_values;
        m.point1 = m.point2 = h.point;
      }
}

}  // namespace

ClearanceSweep SweepClearance(const Model& model, const AnalysisOptions& options) {
  std::vector<ClearancePair> pairs = ClearanceOutputPairs(model);
  if (pairs.empty()) pairs = ShapedBodyPairs(model);
  ClearanceSweep sweep;
  for (const ClearancePair& p : pairs) {
    ClearanceMinimum m;
    m.pair = p;
    m.clearance = std::numeric_limits<double>::infinity();
    sweep.pairs.push_back(m);
  }
  const ClearanceEvaluator eval(model, pairs);
  AnalysisOptions run = options;
  run.on_contact_stop = false;
  run.keep_step_diagnostics = false;
  const AnalysisReport rep = RunKinematicAnalysis(model, run, [&](const SystemState& s, const StepDiagnostics&) {
    for (int k = 0; k < eval.size(); ++k) {
      const ClearanceValue v = eval.Evaluate(s, k, false);
      ClearanceMinimum& m = sweep.pairs[k];
      if (!(v.distance < m.clearance)) continue;
      m.clearance = v.distance;
      m.t = s.t;
      m.driver_values = DriverValuesOf(s);
      m.point1 = v.point1;
      m.point2 = v.point2;
    }
    return true;
  });
  TakeContacts(rep.contacts, &sweep);
  sweep.rows = rep.rows;
  sweep.complete = rep.complete;
  if (!rep.complete) sweep.note = rep.message.substr(0, rep.message.find('\n'));
  for (size_t k = 0; k < sweep.pairs.size(); ++k)
    if (sweep.tightest < 0 || sweep.pairs[k].clearance < sweep.pairs[sweep.tightest].clearance)
      sweep.tightest = static_cast<int>(k);
  if (sweep.rows == 0) sweep.tightest = -1;
  return sweep;
}

std::string ClearanceWhere(const Model& model, const ClearanceMinimum& m) {
  std::ostringstream o;
  o.precision(10);
  const double L = 1 / model.units.length_to_si;
  o << "`" << model.BodyName(m.pair.body1) << "` and `" << model.BodyName(m.pair.body2) << "`: " << m.clearance * L
    << " " << model.units.length_name << " at t = " << m.t << " s";
  for (size_t d = 0; d < model.drivers.size() && d < m.driver_values.size(); ++d) {
    const bool angle = IsAngleDriver(model.drivers[d]);
    o << (d ? ", " : " (") << "driver `" << model.drivers[d].name << "` = "
      << m.driver_values[d] / (angle ? model.units.angle_to_si : model.units.length_to_si) << " "
      << (angle ? model.units.angle_name : model.units.length_name);
  }
  if (!model.drivers.empty()) o << ")";
  return o.str();
}

// `expect: {"min_clearance"}` and `check --clearance`: the sweep, and the expectation
// held when the tightest pair keeps at least the clearance asked.
void AddClearanceCheck(const Model& m, CheckReport* r, const InterruptPoll& stop) {
  if (!r->valid || !m.analysis) return;
  AnalysisOptions options;
  options.interrupted = stop;
  const ClearanceSweep sweep = SweepClearance(m, options);
  r->clearance = ClearanceSection{};
  ClearanceSection& c = *r->clearance;
  const double L = 1 / m.units.length_to_si;
  c.length_unit = m.units.length_name;
  c.complete = sweep.complete;
  c.note = sweep.note;
  c.rows = sweep.rows;
  for (const ClearanceMinimum& p : sweep.pairs)
    c.pairs.push_back({m.BodyName(p.pair.body1), m.BodyName(p.pair.body2),
                       p.pair.output >= 0 ? m.outputs[p.pair.output].name : "", p.clearance * L, p.t,
                       ClearanceWhere(m, p)});
  c.tightest = sweep.tightest;
  if (!m.expect.min_clearance) return;
  ExpectationResult e;
  e.key = "min_clearance";
  e.expected = ExpectValue::Of(*m.expect.min_clearance * L);
  if (sweep.tightest >= 0) {
    const ClearanceMinimum& t = sweep.pairs[sweep.tightest];
    e.actual = ExpectValue::Of(t.clearance * L);
    e.held = t.clearance >= *m.expect.min_clearance && sweep.complete;
    e.where = ClearanceWhere(m, t) + (sweep.complete ? "" : "; the sweep stopped early: " + sweep.note);
  } else {
    e.where = sweep.pairs.empty() ? "no pair of bodies with shapes to measure" : "the sweep made no row: " + sweep.note;
  }
  r->expectations.push_back(e);
}

}  // namespace mechkin
