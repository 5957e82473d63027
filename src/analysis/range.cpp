#include "analysis/range.hpp"

#include <cstdio>
#include <cmath>
#include <memory>

#include "analysis/assembly.hpp"
#include "analysis/motion.hpp"

namespace mechkin {

namespace {

TimeFunction Linear(double offset, double slope) {
  char text[96];
  std::snprintf(text, sizeof text, "%.17g + %.17g*t", offset, slope);
  return TimeFunction(std::make_shared<Expression>(Expression::Parse(text)), 1.0);
}

// One direction: driver d from its design value by `sign`·span over t ∈ [0, 1].
RangeEnd Sweep(const Model& model, int d, double sign, double span, const RangeOptions& options, DriverRange* out) {
  Model m = model;
  for (size_t k = 0; k < m.drivers.size(); ++k)
    m.drivers[k].function = Linear(DesignDriverValue(model, model.drivers[k]), k == static_cast<size_t>(d) ? sign * span : 0);
  m.analysis = Analysis{};
  m.analysis->start = 0;
  m.analysis->end = 1;
  m.analysis->steps = options.steps;
  AnalysisOptions a;
  a.order = 1;
  a.tolerance = options.tolerance;
  a.keep_step_diagnostics = false;
  a.interrupted = options.interrupted;
  const double to_file = 1 / (IsAngleDriver(model.drivers[d]) ? model.units.angle_to_si : model.units.length_to_si);
  const double v0 = DesignDriverValue(model, model.drivers[d]);
  // Only what the range reads, step by step: the largest condition and the last row's
  // time (the whole table and every step's diagnostics took > 1 GB at --steps 1e7).
  double last_t = 0;
  int rows = 0;
  const AnalysisReport report = RunKinematicAnalysis(m, a, [&](const SystemState&, const StepDiagnostics& st) {
    if (st.condition > out->max_condition)
      out->max_condition = st.condition, out->value_at_max_condition = (v0 + sign * span * st.t) * to_file;
    last_t = st.t;
    ++rows;
    return true;
  });
  const MotionStop stop = StopOf(report);
  RangeEnd end;
  if (report.stop == StopKind::Interrupted) {
    end.kind = "interrupted";  // not reported: CalcRange ends the report before this driver
  } else if (report.complete) {
    end.kind = IsAngleDriver(model.drivers[d]) ? "full turn" : "open";
    end.value = (v0 + sign * span) * to_file;
  } else if (report.stop == StopKind::JointLimit && !report.joint_limits.empty()) {
    // A joint's limits end the interval where the run located the crossing.
    end.kind = "joint limit";
    end.value = report.joint_limits.front().driver_values[d] * to_file;
  } else if (report.limit && report.limit->fold) {
    end.kind = "limit";
    end.value = report.limit->driver_values[d] * to_file;
  } else if (report.singular) {
    end.kind = "branch point";
    end.value = report.singular->driver_values[d] * to_file;
  } else {
    end.kind = "failed";
    end.value = rows > 0 ? (v0 + sign * span * last_t) * to_file : v0 * to_file;
  }
  end.message = report.complete ? "" : stop.Summary();
  return end;
}

}  // namespace

RangeReport CalcRange(const Model& model, const RangeOptions& options) {
  RangeReport rep;
  if (model.drivers.empty()) {
    rep.message = "the file has no drivers: add one to ask for its range";
    return rep;
  }
  for (size_t d = 0; d < model.drivers.size(); ++d) {
    const Driver& drv = model.drivers[d];
    if (!options.driver.empty() && drv.name != options.driver) continue;
    DriverRange r;
    r.driver = drv.name;
    r.unit = IsAngleDriver(drv) ? model.units.angle_name : model.units.length_name;
    r.design_value = DesignDriverValue(model, drv) / (IsAngleDriver(drv) ? model.units.angle_to_si : model.units.length_to_si);
    const double span = IsAngleDriver(drv) ? 2 * M_PI
                                     : (options.span > 0 ? options.span * model.units.length_to_si
                                                         : 4 * model.characteristic_length);
    r.upper = Sweep(model, static_cast<int>(d), 1, span, options, &r);
    if (r.upper.kind == "full turn") r.lower = r.upper, r.lower.value = r.design_value - (r.upper.value - r.design_value);
    else if (r.upper.kind != "interrupted") r.lower = Sweep(model, static_cast<int>(d), -1, span, options, &r);
    rep.interrupted = r.upper.kind == "interrupted" || r.lower.kind == "interrupted";
    if (rep.interrupted) break;
    rep.drivers.push_back(r);
  }
  if (rep.interrupted) {
    rep.ok = true;
    rep.message = "interrupted";
    return rep;
  }
  if (rep.drivers.empty()) {
    std::string names;
    for (const auto& d : model.drivers) names += (names.empty() ? "" : ", ") + d.name;
    rep.message = "no driver '" + options.driver + "' (drivers: " + names + ")";
    return rep;
  }
  rep.ok = true;
  return rep;
}

}  // namespace mechkin
