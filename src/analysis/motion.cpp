#include "analysis/motion.hpp"

#include <algorithm>
#include <stdexcept>

#include "analysis/orientation.hpp"
#include "analysis/run_request.hpp"
#include "constraints/constraint.hpp"

namespace mechkin {
namespace {

const char* kSuffix[] = {"", "_t", "_tt", "_ttt", "_tttt"};
const char* kPer[] = {"", "/s", "/s^2", "/s^3", "/s^4"};
const char* kXyz[] = {".x", ".y", ".z"};

std::string UnitOfOrder(const std::string& unit, int k) {
  return unit.empty() ? (k ? std::string("1") + kPer[k] : "") : unit + kPer[k];
}

// Jet of each vector component from its derivatives, so that products and norms
// of derivative series (slides, distances) follow the Leibniz rule.
std::array<Jet, 3> VecJet(const Vec3* d, int order) {
  std::array<Jet, 3> j;
  static constexpr double kInvFact[] = {1, 1, 0.5, 1.0 / 6, 1.0 / 24};
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k <= order; ++k) j[a].c[k] = d[k][a] * kInvFact[k];
  return j;
}

// A one-coordinate output measured in angle units (revolute joint or angle output).
bool IsAngleOutput(const Model& model, int output) {
  const Output& x = model.outputs[output];
  return x.kind == OutputKind::Angle ||
         (x.kind == OutputKind::JointCoordinate && model.joints[x.joint].type->coordinates == JointCoordinates::Angle);
}

// d = P2 − P1 of an output's two points: |d| on jets (SI).
Jet DistanceJet(const SystemState& s, const Output& op, int order) {
  Vec3 d[5];
  for (int k = 0; k <= order; ++k)
    d[k] = s.Kin(op.body2).PointDerivative(op.point2, k) - s.Kin(op.body1).PointDerivative(op.point1, k);
  const auto j = VecJet(d, order);
  return Sqrt(j[0] * j[0] + j[1] * j[1] + j[2] * j[2]);
}

// A joint's slide s = h_iᵀ(P_j − P_i), differentiated by the Leibniz rule on jets (SI).
Jet SlideJet(const SystemState& s, const Joint& jt, int order) {
  const BodyKinematics& b1 = s.Kin(jt.body1);
  const BodyKinematics& b2 = s.Kin(jt.body2);
  Vec3 d[5], hv[5];
  for (int k = 0; k <= order; ++k) {
    d[k] = b2.PointDerivative(jt.frame2.origin, k) - b1.PointDerivative(jt.frame1.origin, k);
    hv[k] = b1.VectorDerivative(jt.frame1.h, k);
  }
  const auto jd = VecJet(d, order), jh = VecJet(hv, order);
  return jh[0] * jd[0] + jh[1] * jd[1] + jh[2] * jd[2];
}

// Angle output between u = A1·v1 and w = A2·v2 on jets (derivatives by the chain rule):
//   unsigned: θ = atan2(|u × w|, u·w) in [0, π];
//   about a (fixed in body1): θ = atan2(a·(u × w), u·w − (a·u)(a·w)), the turn from u to w.
// *y, *x: the atan2 arguments' values (for continuity over turns). Throws JetDomainError
// for the unsigned angle's derivatives at 0 or π, where they do not exist.
Jet AngleJet(const SystemState& s, const Output& op, int order, double* y_out, double* x_out) {
  const BodyKinematics& b1 = s.Kin(op.body1);
  const BodyKinematics& b2 = s.Kin(op.body2);
  Vec3 uk[5], wk[5], ak[5];
  for (int k = 0; k <= order; ++k) {
    uk[k] = b1.VectorDerivative(op.vector1, k);
    wk[k] = b2.VectorDerivative(op.vector2, k);
    ak[k] = b1.VectorDerivative(op.about, k);
  }
  const auto u = VecJet(uk, order), w = VecJet(wk, order), a = VecJet(ak, order);
  const std::array<Jet, 3> c = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
  const Jet dot = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
  if (op.signed_about) {
    const Jet y = a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
    const Jet x = dot - (a[0] * u[0] + a[1] * u[1] + a[2] * u[2]) * (a[0] * w[0] + a[1] * w[1] + a[2] * w[2]);
    *y_out = y.c[0], *x_out = x.c[0];
    return Atan2(y, x);
  }
  *y_out = std::sqrt(c[0].c[0] * c[0].c[0] + c[1].c[0] * c[1].c[0] + c[2].c[0] * c[2].c[0]);
  *x_out = dot.c[0];
  return Atan2(Sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot);
}

bool Selected(bool all, const std::vector<std::string>& names, const std::string& name) {
  return all || std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

std::string ColumnDescriptor::Header() const { return unit.empty() ? name : name + " [" + unit + "]"; }

MotionLayout::MotionLayout(const Model& model, const TableOptions& options) : options_(options) {
  if (!options.si) {
    len_ = 1 / model.units.length_to_si;
    ang_ = 1 / model.units.angle_to_si;
  }
  columns_.push_back({"t", "s", "", Quantity::Time});
  Close(Segment::Kind::Time, -1, 0);
  for (int b = 0; b < model.num_bodies(); ++b)
    if (Selected(options.all_bodies, options.bodies, model.bodies[b].name)) {
      const int first = size();
      AddBody(model, b);
      Close(Segment::Kind::Body, b, first);
    }
  for (const auto& sel : options.bodies)
    if (!options.all_bodies && std::none_of(model.bodies.begin(), model.bodies.end(), [&](const Body& b) { return b.name == sel; }))
      throw std::invalid_argument("--bodies: no body named '" + sel + "'");
  for (size_t o = 0; o < model.outputs.size(); ++o)
    if (Selected(options.all_outputs, options.outputs, model.outputs[o].name)) {
      const int first = size();
      AddOutput(model, static_cast<int>(o));
      Close(Segment::Kind::Output, static_cast<int>(o), first);
    }
  for (const auto& sel : options.outputs)
    if (!options.all_outputs && std::none_of(model.outputs.begin(), model.outputs.end(), [&](const Output& o) { return o.name == sel; }))
      throw std::invalid_argument("--outputs: no output named '" + sel + "'");
  if (options.forces) {
    const int first = size();
    AddForces(model);
    Close(Segment::Kind::Forces, -1, first);
  }
  const int diagnostics = size();
  columns_.push_back({"newton_iterations", "", "", Quantity::NewtonIterations});
  columns_.push_back({"residual", "", "", Quantity::Residual});
  columns_.push_back({"condition", "", "", Quantity::Condition});
  for (int k = 0; k <= options.order; ++k)
    columns_.push_back({std::string("error_bound") + kSuffix[k], "", "", Quantity::ErrorBound, -1, -1, k});
  Close(Segment::Kind::Diagnostics, -1, diagnostics);
  const int sensitivities = size();
  AddSensitivities();
  if (size() > sensitivities) Close(Segment::Kind::Sensitivities, -1, sensitivities);
}

void MotionLayout::Close(Segment::Kind kind, int index, int first) {
  segments_.push_back({kind, index, first, size() - first});
}

// "piston.x/d(crank)" for every body and output column and every parameter, in
// the table's units per unit of the parameter as written in the file.
void MotionLayout::AddSensitivities() {
  const size_t base_columns = columns_.size();
  for (size_t p = 0; p < options_.sensitivity.size(); ++p)
    for (size_t c = 0; c < base_columns; ++c) {
      const ColumnDescriptor& b = columns_[c];
      if (b.quantity == Quantity::Time || b.quantity >= Quantity::DriverEffort) continue;
      ColumnDescriptor d = b;
      d.name = b.name + "/d(" + options_.sensitivity[p] + ")";
      d.unit = b.unit.empty() ? "1/" + options_.sensitivity[p] : b.unit + "/" + options_.sensitivity[p];
      d.wrt = static_cast<int>(p);
      d.base = static_cast<int>(c);
      columns_.push_back(d);
    }
}

void MotionLayout::AddSeries(Quantity q, const std::string& subject, int index, const std::string& name, int component,
                             const std::string& unit, int first_order) {
  for (int k = first_order; k <= options_.order; ++k)
    columns_.push_back({name + kSuffix[k], UnitOfOrder(unit, k), subject, q, index, component, k});
}

// Body columns, format-v1 order: x, y, z with derivatives; e0..e3; ωx, ωy, ωz
// with derivatives, where ".wx" is order 1 and ".wx_t" order 2.
void MotionLayout::AddBody(const Model& model, int b) {
  items_.push_back({true, b});
  const std::string& nm = model.bodies[b].name;
  const std::string L = options_.si ? "m" : model.units.length_name;
  const std::string A = options_.si ? "rad" : model.units.angle_name;
  for (int a = 0; a < 3; ++a) AddSeries(Quantity::BodyPosition, nm, b, nm + kXyz[a], a, L, 0);
  for (int a = 0; a < 4; ++a)
    columns_.push_back({nm + ".e" + std::to_string(a), "", nm, Quantity::EulerParameter, b, a, 0});
  for (int a = 0; a < 3; ++a)
    for (int k = 1; k <= options_.order; ++k)
      columns_.push_back({nm + ".w" + std::string(1, "xyz"[a]) + kSuffix[k - 1], UnitOfOrder(A, k), nm,
                          Quantity::AngularVelocity, b, a, k});
}

void MotionLayout::AddOutput(const Model& model, int o) {
  items_.push_back({false, o});
  const Output& out = model.outputs[o];
  const std::string L = options_.si ? "m" : model.units.length_name;
  const std::string A = options_.si ? "rad" : model.units.angle_name;
  if (out.kind == OutputKind::Point) {
    for (int a = 0; a < 3; ++a) AddSeries(Quantity::PointPosition, out.name, o, out.name + kXyz[a], a, L, 0);
  } else if (out.kind == OutputKind::Distance) {
    AddSeries(Quantity::Distance, out.name, o, out.name, -1, L, 0);
  } else if (out.kind == OutputKind::Angle) {
    AddSeries(Quantity::Angle, out.name, o, out.name, -1, A, 0);
  } else if (out.kind == OutputKind::VelocityRatio) {
    AddVelocityRatio(model, o);
  } else if (out.kind == OutputKind::Orientation) {
    AddOrientation(out, o, A);
  } else if (out.kind == OutputKind::Clearance) {
    AddClearance(out, o, L);
  } else if (out.kind == OutputKind::Expression) {
    AddSeries(Quantity::Expression, out.name, o, out.name, -1, "", 0);
  } else {
    AddJointCoordinates(model.joints[out.joint].type->coordinates, out, o, L, A);
  }
}

// A joint output's columns, as its descriptor's coordinates say.
void MotionLayout::AddJointCoordinates(JointCoordinates c, const Output& out, int o, const std::string& L,
                                       const std::string& A) {
  switch (c) {
    case JointCoordinates::Orientation:
      AddOrientation(out, o, A);
      break;
    case JointCoordinates::TwoAngles:
      for (int a = 0; a < 2; ++a)
        AddSeries(Quantity::JointAngle, out.name, o, out.name + ".angle" + std::to_string(a + 1), a, A, 0);
      break;
    case JointCoordinates::PlaneSlidesAndAngle:
      AddSeries(Quantity::JointSlide, out.name, o, out.name + ".slide1", 0, L, 0);
      AddSeries(Quantity::JointSlide, out.name, o, out.name + ".slide2", 1, L, 0);
      AddSeries(Quantity::JointAngle, out.name, o, out.name + ".angle", -1, A, 0);
      break;
    case JointCoordinates::Angle:
      AddSeries(Quantity::JointAngle, out.name, o, out.name, -1, A, 0);
      break;
    case JointCoordinates::Slide:
      AddSeries(Quantity::JointSlide, out.name, o, out.name, -1, L, 0);
      break;
    case JointCoordinates::AngleAndSlide:
    case JointCoordinates::None:  // compile refuses a distance link's output
      AddSeries(Quantity::JointAngle, out.name, o, out.name + ".angle", -1, A, 0);
      AddSeries(Quantity::JointSlide, out.name, o, out.name + ".slide", -1, L, 0);
      break;
  }
}

// The ratio's own derivatives need one order more of the motion: orders 0..order−1
// (at order 0 the column reads NaN). Unit: the output's unit per the input's.
void MotionLayout::AddVelocityRatio(const Model& model, int o) {
  const Output& out = model.outputs[o];
  const std::string L = options_.si ? "m" : model.units.length_name;
  const std::string A = options_.si ? "rad" : model.units.angle_name;
  const std::string num = IsAngleOutput(model, out.ratio_of) ? A : L;
  const bool input_angle = out.ratio_input_output >= 0 ? IsAngleOutput(model, out.ratio_input_output)
                                                       : IsAngleDriver(model.drivers[out.ratio_input_driver]);
  const std::string den = input_angle ? A : L;
  const std::string unit = num == den ? "" : num + "/" + den;
  for (int k = 0; k <= std::max(options_.order - 1, 0); ++k)
    columns_.push_back({out.name + kSuffix[k], UnitOfOrder(unit, k), out.name, Quantity::VelocityRatio, o, -1, k});
}

// Sequence angles name.angle1..3 (+ name.gimbal_lock), Euler parameters name.e0..e3,
// or the rotation vector name.rx..rz, each with its derivatives.
void MotionLayout::AddOrientation(const Output& out, int o, const std::string& A) {
  if (out.sequence == "euler-parameters") {
    for (int a = 0; a < 4; ++a)
      AddSeries(Quantity::OrientationParameter, out.name, o, out.name + ".e" + std::to_string(a), a, "", 0);
  } else if (out.sequence == "axis-angle") {
    for (int a = 0; a < 3; ++a)
      AddSeries(Quantity::RotationVector, out.name, o, out.name + ".r" + std::string(1, "xyz"[a]), a, A, 0);
  } else {
    for (int a = 0; a < 3; ++a)
      AddSeries(Quantity::OrientationAngle, out.name, o, out.name + ".angle" + std::to_string(a + 1), a, A, 0);
    columns_.push_back({out.name + ".gimbal_lock", "", out.name, Quantity::GimbalLock, o, -1, 0});
  }
}

// A force quantity and, with order ≥ 3, its rate ("_t").
void MotionLayout::AddRated(Quantity q, const std::string& subject, int index, const std::string& name, int component,
                            const std::string& unit) {
  columns_.push_back({name, unit, subject, q, index, component, 0});
  if (options_.order >= 3) columns_.push_back({name + "_t", unit + "/s", subject, q, index, component, 1});
}

// Forces, in the file's units (its named force and torque units, else force = mass ×
// length / s² and torque = force × length) or SI.
void MotionLayout::AddForces(const Model& model) {
  const Units u = model.units.TableUnits(options_.si);
  static const char* kGlobal[] = {"x", "y", "z"};
  static const char* kFrame[] = {"f", "g", "h"};
  for (size_t d = 0; d < model.drivers.size(); ++d) {
    const Driver& drv = model.drivers[d];
    const bool torque = drv.kind == DriverKind::JointRotation || drv.kind == DriverKind::BodyRotation;
    AddRated(Quantity::DriverEffort, drv.name, static_cast<int>(d), drv.name + ".effort", -1,
             torque ? u.TorqueName() : u.ForceName());
    AddRated(Quantity::DriverPower, drv.name, static_cast<int>(d), drv.name + ".power", -1, u.PowerName());
  }
  for (size_t j = 0; j < model.joints.size(); ++j) {
    const std::string& nm = model.joints[j].name;
    const int idx = static_cast<int>(j);
    for (int a = 0; a < 3; ++a) AddRated(Quantity::JointForce, nm, idx, nm + ".f" + kGlobal[a], a, u.ForceName());
    for (int a = 0; a < 3; ++a) AddRated(Quantity::JointMoment, nm, idx, nm + ".m" + kGlobal[a], a, u.TorqueName());
    for (int a = 0; a < 3; ++a) AddRated(Quantity::JointForceLocal, nm, idx, nm + ".f" + kFrame[a], a, u.ForceName());
    for (int a = 0; a < 3; ++a) AddRated(Quantity::JointMomentLocal, nm, idx, nm + ".m" + kFrame[a], a, u.TorqueName());
  }
  for (size_t c = 0; c < model.couplers.size(); ++c) {
    const Coupler& cp = model.couplers[c];
    const int idx = static_cast<int>(c);
    for (size_t k = 0; k < cp.coordinates.size(); ++k)
      AddRated(Quantity::CouplerEffort, cp.name, idx, cp.name + ".effort" + std::to_string(k + 1), static_cast<int>(k),
               cp.coordinates[k].rotation ? u.TorqueName() : u.ForceName());
    AddRated(Quantity::CouplerPower, cp.name, idx, cp.name + ".power", -1, u.PowerName());
  }
  columns_.push_back({"kinetic_energy", u.EnergyName(), "", Quantity::KineticEnergy});
  columns_.push_back({"potential_energy", u.EnergyName(), "", Quantity::PotentialEnergy});
  columns_.push_back({"energy_balance", u.PowerName(), "", Quantity::EnergyBalance});
}

int MotionLayout::Find(const std::string& name) const {
  for (size_t c = 0; c < columns_.size(); ++c)
    if (columns_[c].name == name) return static_cast<int>(c);
  return -1;
}

int MotionLayout::Find(Quantity q, int subject_index, int component, int order) const {
  for (size_t c = 0; c < columns_.size(); ++c) {
    const ColumnDescriptor& d = columns_[c];
    if (d.quantity == q && d.subject_index == subject_index && d.component == component && d.order == order &&
        d.wrt < 0)
      return static_cast<int>(c);
  }
  return -1;
}

int MotionLayout::SensitivityOf(int column, int parameter) const {
  for (size_t c = 0; c < columns_.size(); ++c)
    if (columns_[c].wrt == parameter && columns_[c].base == column) return static_cast<int>(c);
  return -1;
}

int MotionLayout::SensitivityOf(const std::string& column, const std::string& parameter) const {
  const auto& names = options_.sensitivity;
  const auto p = std::find(names.begin(), names.end(), parameter);
  const int base = Find(column);
  return p == names.end() || base < 0 ? -1 : SensitivityOf(base, static_cast<int>(p - names.begin()));
}

namespace {
int FindBySubject(const std::vector<ColumnDescriptor>& columns, Quantity q, const std::string& subject, int order) {
  for (size_t c = 0; c < columns.size(); ++c)
    if (columns[c].quantity == q && columns[c].subject == subject && columns[c].order == order && columns[c].wrt < 0)
      return static_cast<int>(c);
  return -1;
}
}  // namespace

int MotionLayout::EffortOf(const std::string& driver, int order) const {
  return FindBySubject(columns_, Quantity::DriverEffort, driver, order);
}

int MotionLayout::PowerOf(const std::string& driver, int order) const {
  return FindBySubject(columns_, Quantity::DriverPower, driver, order);
}

std::vector<int> MotionLayout::NeededBodies(const Model& model) const {
  std::vector<char> need(model.num_bodies(), 0), seen(model.outputs.size(), 0);
  std::vector<int> pending;  // outputs whose bodies are needed: the selected ones and what they read
  for (const Item& it : items_) {
    if (it.is_body) need[it.index] = 1;
    else pending.push_back(it.index);
  }
  while (!pending.empty()) {  // each output once: linear in the outputs and their inputs
    const int x = pending.back();
    pending.pop_back();
    if (seen[x]) continue;
    seen[x] = 1;
    const Output& o = model.outputs[x];
    for (BodyIndex b : {o.body1, o.body2, o.frame})
      if (b != kGround) need[b] = 1;
    for (int y : {o.ratio_of, o.ratio_input_output})
      if (y >= 0) pending.push_back(y);
    for (const ExpressionInput& in : o.inputs) pending.push_back(in.output);
  }
  std::vector<int> bodies;
  for (int b = 0; b < model.num_bodies(); ++b)
    if (need[b]) bodies.push_back(b);
  return bodies;
}

RowEvaluator::RowEvaluator(const Model& model, const MotionLayout& layout)
    : model_(model),
      layout_(layout),
      angle_ref_(model.outputs.size(), 0.0),
      angle_rate_(model.outputs.size(), 0.0),
      angle_driver_(model.outputs.size(), -1),
      orientation_ref_(model.outputs.size(), std::array<double, 4>{0, 0, 0, 0}),
      orientation_rate_(model.outputs.size(), std::array<double, 3>{0, 0, 0}) {
  for (size_t o = 0; o < model.outputs.size(); ++o)
    for (size_t d = 0; d < model.drivers.size(); ++d)
      if (model.outputs[o].kind == OutputKind::JointCoordinate && model.drivers[d].kind == DriverKind::JointRotation &&
          model.drivers[d].joint == model.outputs[o].joint)
        angle_driver_[o] = static_cast<int>(d);
  PrepareExpressions();
}

// A joint angle continuous from the design pose over any number of turns
// (format: "never wrapped"). The turn is chosen nearest a reference: for a
// driven joint the driver's own value, so the column equals the driver to
// round-off; otherwise the previous row's angle advanced by its angular velocity
// over the step, so steps of more than half a turn are followed too.
double RowEvaluator::JointAngle(const SystemState& s, int o, double raw_sin, double raw_cos) {
  double ref = angle_ref_[o];
  if (angle_driver_[o] >= 0) ref = s.driver_values[angle_driver_[o]].c[0];
  else if (!first_row_ && layout_.options().order >= 1) ref += angle_rate_[o] * (s.t - last_t_);
  angle_ref_[o] = UnwrapAngle(raw_sin, raw_cos, ref);
  return angle_ref_[o];
}

// Each segment's extractor writes at the segment's own offset; one that wrote another
// number of values than its segment holds is a defect of the layout, caught here
// rather than shifting every later column (tests run every layout through this).
void RowEvaluator::Evaluate(const SystemState& s, const StepDiagnostics& d, double* row) {
  if (file_units_) file_units_->Evaluate(s, d, file_row_.data());
  current_row_ = row;
  for (const MotionLayout::Segment& g : layout_.segments()) {
    double* const at = row + g.first;
    if (SegmentValues(g, s, d, at) != at + g.count)
      throw std::logic_error("motion layout: a segment's extractor disagrees with its " + std::to_string(g.count) +
                             " columns at column " + std::to_string(g.first));
  }
  last_t_ = s.t;
  first_row_ = false;
}

double* RowEvaluator::SegmentValues(const MotionLayout::Segment& g, const SystemState& s, const StepDiagnostics& d,
                                    double* at) {
  using Kind = MotionLayout::Segment::Kind;
  switch (g.kind) {
    case Kind::Time: *at = d.t; return at + 1;
    case Kind::Body: return BodyValues(s.bodies[g.index], at);
    case Kind::Output: return OutputValues(s, g.index, at);
    case Kind::Forces: return ForceValues(d.forces, at);
    case Kind::Diagnostics: return DiagnosticValues(d, at);
    case Kind::Sensitivities: SensitivityValues(d, at - g.first); return at + g.count;
  }
  return at;
}

double* RowEvaluator::DiagnosticValues(const StepDiagnostics& d, double* out) const {
  *out++ = d.iterations;
  *out++ = d.residual;
  *out++ = d.condition;
  for (int k = 0; k <= layout_.options().order; ++k) *out++ = d.error_bound[k];
  return out;
}

// The poses of the move carry no rates worth extrapolating: after each one the
// references are its angles and the rates zero, so the first row unwraps nearest
// the pose the move ended on (the same pose, solved at t = start).
void RowEvaluator::Follow(const SystemState& s) {
  follow_row_.resize(layout_.size());
  double* out = follow_row_.data();
  following_ = true;
  for (const auto& it : layout_.items())
    if (!it.is_body) out = OutputValues(s, it.index, out);
  following_ = false;
  std::fill(angle_rate_.begin(), angle_rate_.end(), 0.0);
  for (auto& r : orientation_rate_) r = {0, 0, 0};
  last_t_ = s.t;
  first_row_ = false;
  if (file_units_) file_units_->Follow(s);
}

void RowEvaluator::ContinueFrom(const RowEvaluator& base) {
  if (file_units_ && base.file_units_) file_units_->ContinueFrom(*base.file_units_);
  angle_ref_ = base.angle_ref_;
  orientation_ref_ = base.orientation_ref_;
  std::fill(angle_rate_.begin(), angle_rate_.end(), 0.0);
  for (auto& r : orientation_rate_) r = {0, 0, 0};
  first_row_ = false;
}

// d(column)/dp = [column(model₊, s₊) − column(model₋, s₋)] / 2h (analysis/sensitivity.hpp):
// each side evaluated by its own RowEvaluator, so angles stay continuous on both.
void RowEvaluator::SensitivityValues(const StepDiagnostics& d, double* row) {
  const SensitivitySolver* sens = d.sensitivity;
  const auto& cols = layout_.columns();
  if (!sens) {
    for (const auto& c : cols) if (c.wrt >= 0) row[&c - cols.data()] = std::nan("");
    return;
  }
  if (perturbed_.empty()) {
    TableOptions side_options = layout_.options();
    side_options.sensitivity.clear();
    side_options.forces = false;
    for (int p = 0; p < sens->size(); ++p)
      for (int sign : {1, -1}) {
        PerturbedRows pr;
        pr.layout = std::make_unique<MotionLayout>(sens->model(p, sign), side_options);
        pr.eval = std::make_unique<RowEvaluator>(sens->model(p, sign), *pr.layout);
        pr.eval->ContinueFrom(*this);
        pr.row.resize(pr.layout->size());
        for (const auto& c : cols)
          if (c.wrt == p) pr.column.push_back(pr.layout->Find(cols[c.base].name));
        perturbed_.push_back(std::move(pr));
      }
  }
  StepDiagnostics side_diag = d;
  side_diag.forces = nullptr;
  side_diag.sensitivity = nullptr;
  for (int p = 0; p < sens->size(); ++p) {
    PerturbedRows& plus = perturbed_[2 * p];
    PerturbedRows& minus = perturbed_[2 * p + 1];
    plus.eval->Evaluate(sens->state(p, 1), side_diag, plus.row.data());
    minus.eval->Evaluate(sens->state(p, -1), side_diag, minus.row.data());
    const double two_h = 2 * sens->step(p);
    size_t k = 0;
    for (size_t c = 0; c < cols.size(); ++c)
      if (cols[c].wrt == p) {
        row[c] = (plus.row[plus.column[k]] - minus.row[minus.column[k]]) / two_h;
        ++k;
      }
  }
}

double* RowEvaluator::BodyValues(const BodyKinematics& b, double* out) const {
  const int order = layout_.options().order;
  const double len = layout_.length_factor(), ang = layout_.angle_factor();
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k <= order; ++k) *out++ = b.r[k][a] * len;
  for (int a = 0; a < 4; ++a) *out++ = b.p[a];
  // Global angular velocity and derivatives from the body-frame ones (constraints.md §1.3):
  // ω = Aω', ω̇ = Aω̇', ω̈ = A(ω̈' + ω'×ω̇'), ω⃛ = A(ω⃛' + 2ω'×ω̈' + ω'×(ω'×ω̇')).
  Vec3 wg[4];
  wg[0] = b.A * b.w[0];
  wg[1] = b.A * b.w[1];
  wg[2] = b.A * (b.w[2] + b.w[0].cross(b.w[1]));
  wg[3] = b.A * (b.w[3] + 2 * b.w[0].cross(b.w[2]) + b.w[0].cross(b.w[0].cross(b.w[1])));
  for (int a = 0; a < 3; ++a)
    for (int k = 1; k <= order; ++k) *out++ = wg[k - 1][a] * ang;
  return out;
}

double* RowEvaluator::OutputValues(const SystemState& s, int o, double* out) {
  const int order = layout_.options().order;
  const double len = layout_.length_factor(), ang = layout_.angle_factor();
  const Output& op = model_.outputs[o];
  const BodyKinematics& b1 = s.Kin(op.body1);
  const BodyKinematics& b2 = s.Kin(op.body2);
  if (op.kind == OutputKind::Point) return PointValues(s, o, out);
  if (op.kind == OutputKind::VelocityRatio) return VelocityRatioValues(s, o, out);
  if (op.kind == OutputKind::Orientation) return OrientationValues(s, o, out);
  if (op.kind == OutputKind::Clearance) return ClearanceValues(s, o, out);
  if (op.kind == OutputKind::Expression) return ExpressionValues(s, o, out);
  if (op.kind == OutputKind::Distance) {
    const Jet dist = DistanceJet(s, op, order);
    for (int k = 0; k <= order; ++k) *out++ = dist.Derivative(k) * len;
    return out;
  }
  if (op.kind == OutputKind::Angle) return AngleValues(s, o, out);
  const Joint& jt = model_.joints[op.joint];
  const JointCoordinates c = jt.type->coordinates;
  if (c == JointCoordinates::Orientation) return OrientationValues(s, o, out);
  if (c == JointCoordinates::TwoAngles) return UniversalValues(s, o, out);
  if (c == JointCoordinates::PlaneSlidesAndAngle) {
    out = PlanarSlides(s, o, out);
    // and the angle about the normal, below, as for a revolute joint
  }
  if (c != JointCoordinates::Slide) {
    // θ = atan2(g_iᵀf_j, f_iᵀf_j), continuous from the design pose;
    // θ^(k) = h'_jᵀω_j'^(k−1) − h'_iᵀω_i'^(k−1) on the joint.
    const Vec3 fj = b2.A * jt.frame2.f;
    const double th = JointAngle(s, o, (b1.A * jt.frame1.g).dot(fj), (b1.A * jt.frame1.f).dot(fj));
    *out++ = th * ang;
    for (int k = 1; k <= order; ++k) *out++ = (jt.frame2.h.dot(b2.w[k - 1]) - jt.frame1.h.dot(b1.w[k - 1])) * ang;
    if (order >= 1) angle_rate_[o] = jt.frame2.h.dot(b2.w[0]) - jt.frame1.h.dot(b1.w[0]);
  }
  if (c != JointCoordinates::Angle && c != JointCoordinates::PlaneSlidesAndAngle) {
    const Jet sl = SlideJet(s, jt, order);
    for (int k = 0; k <= order; ++k) *out++ = sl.Derivative(k) * len;
  }
  return out;
}

// Angle outputs (AngleJet): the signed angle continuous over turns like a joint angle
// (absolute, not from the design); where the unsigned angle is 0 or π its derivatives
// do not exist and read NaN.
double* RowEvaluator::AngleValues(const SystemState& s, int o, double* out) {
  const int order = layout_.options().order;
  const double ang = layout_.angle_factor();
  const Output& op = model_.outputs[o];
  double y = 0, x = 0;
  try {
    const Jet th = AngleJet(s, op, order, &y, &x);
    if (op.signed_about && order >= 1) angle_rate_[o] = th.Derivative(1);
    *out++ = (op.signed_about ? JointAngle(s, o, y, x) : std::atan2(y, x)) * ang;
    for (int k = 1; k <= order; ++k) *out++ = th.Derivative(k) * ang;
  } catch (const JetDomainError&) {
    *out++ = std::atan2(y, x) * ang;
    for (int k = 1; k <= order; ++k) *out++ = std::nan("");
  }
  return out;
}

// Global, or in another body's frame: x_a = (A_f e_a)·(P − r_f) on jets.
double* RowEvaluator::PointValues(const SystemState& s, int o, double* out) const {
  const int order = layout_.options().order;
  const double len = layout_.length_factor();
  const Output& op = model_.outputs[o];
  const BodyKinematics& b = s.Kin(op.body1);
  if (op.frame == kGround) {
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k <= order; ++k) *out++ = b.PointDerivative(op.point1, k)[a] * len;
    return out;
  }
  const BodyKinematics& f = s.Kin(op.frame);
  Vec3 d[5], e[3][5];
  for (int k = 0; k <= order; ++k) {
    d[k] = b.PointDerivative(op.point1, k) - f.PointDerivative(Vec3::Zero(), k);
    for (int a = 0; a < 3; ++a) e[a][k] = f.VectorDerivative(Vec3::Unit(a), k);
  }
  const auto dj = VecJet(d, order);
  for (int a = 0; a < 3; ++a) {
    const auto ej = VecJet(e[a], order);
    const Jet x = ej[0] * dj[0] + ej[1] * dj[1] + ej[2] * dj[2];
    for (int k = 0; k <= order; ++k) *out++ = x.Derivative(k) * len;
  }
  return out;
}

// Derivatives (orders ≥ 1, SI) of a one-coordinate output; c[0] is not used.
Jet RowEvaluator::ScalarOutputJet(const SystemState& s, int o) const {
  const int order = layout_.options().order;
  const Output& op = model_.outputs[o];
  if (op.kind == OutputKind::Distance) return DistanceJet(s, op, order);
  if (op.kind == OutputKind::Angle) {
    double y, x;
    try {
      return AngleJet(s, op, order, &y, &x);
    } catch (const JetDomainError&) {
      Jet nan;
      for (auto& c : nan.c) c = std::nan("");
      return nan;
    }
  }
  const Joint& jt = model_.joints[op.joint];
  if (jt.type->coordinates == JointCoordinates::Slide) return SlideJet(s, jt, order);
  // Revolute: θ^(k) = h'_jᵀω_j'^(k−1) − h'_iᵀω_i'^(k−1).
  static constexpr double kInvFact[] = {1, 1, 0.5, 1.0 / 6, 1.0 / 24};
  Jet j;
  for (int k = 1; k <= order; ++k)
    j.c[k] = (jt.frame2.h.dot(s.Kin(jt.body2).w[k - 1]) - jt.frame1.h.dot(s.Kin(jt.body1).w[k - 1])) * kInvFact[k];
  return j;
}

// d(output)/d(input) = ȯ / i̇ and its derivatives: the quotient of the two
// derivative series (jets shifted by one order), in the table's units.
double* RowEvaluator::VelocityRatioValues(const SystemState& s, int o, double* out) const {
  const int order = layout_.options().order;
  const Output& op = model_.outputs[o];
  auto factor = [&](bool angle) { return angle ? layout_.angle_factor() : layout_.length_factor(); };
  const Jet num = ScalarOutputJet(s, op.ratio_of);
  Jet den;
  double den_factor;
  if (op.ratio_input_output >= 0) {
    den = ScalarOutputJet(s, op.ratio_input_output);
    den_factor = factor(IsAngleOutput(model_, op.ratio_input_output));
  } else {
    den = s.driver_values[op.ratio_input_driver];
    den_factor = factor(IsAngleDriver(model_.drivers[op.ratio_input_driver]));
  }
  Jet p, q;  // the derivative series, to order − 1
  for (int k = 0; k < order; ++k) p.c[k] = (k + 1) * num.c[k + 1], q.c[k] = (k + 1) * den.c[k + 1];
  const int columns = std::max(order - 1, 0) + 1;
  if (order == 0 || q.c[0] == 0) {
    for (int k = 0; k < columns; ++k) *out++ = std::nan("");
    return out;
  }
  const Jet r = p / q;
  const double scale = factor(IsAngleOutput(model_, op.ratio_of)) / den_factor;
  for (int k = 0; k < columns; ++k) *out++ = r.Derivative(k) * scale;
  return out;
}

// Orientation of body2 relative to body1 (analysis/orientation.hpp). Sequence angles
// are continued over turns from the previous row (its values advanced by their
// rates); at gimbal lock the first and third angles and their derivatives read NaN
// and the row's gimbal_lock column reads 1. Euler parameters keep the sign nearest
// the previous row's.
double* RowEvaluator::OrientationValues(const SystemState& s, int o, double* out) {
  const int order = layout_.options().order;
  const double ang = layout_.angle_factor();
  const Output& op = model_.outputs[o];
  const BodyKinematics& b1 = s.Kin(op.body1);
  const BodyKinematics& b2 = s.Kin(op.body2);
  // An orientation output relates the body frames; a spherical joint's output its two joint frames.
  Mat3 F1 = Mat3::Identity(), F2 = Mat3::Identity();
  if (op.kind == OutputKind::JointCoordinate) {
    const Joint& jt = model_.joints[op.joint];
    F1 << jt.frame1.f, jt.frame1.g, jt.frame1.h;
    F2 << jt.frame2.f, jt.frame2.g, jt.frame2.h;
  }
  auto& ref = orientation_ref_[o];
  if (op.sequence == "euler-parameters" || op.sequence == "axis-angle") {
    std::array<Jet, 4> q = RelativeEulerParameters(b1, QuatFromMatrix(F1), b2, QuatFromMatrix(F2), order);
    const double dot = ref[0] * q[0].c[0] + ref[1] * q[1].c[0] + ref[2] * q[2].c[0] + ref[3] * q[3].c[0];
    const bool flip = first_row_ ? q[0].c[0] < 0 : dot < 0;
    for (auto& c : q)
      if (flip) c = -c;
    for (int a = 0; a < 4; ++a) ref[a] = q[a].c[0];
    if (op.sequence == "euler-parameters") {
      for (int a = 0; a < 4; ++a)
        for (int k = 0; k <= order; ++k) *out++ = q[a].Derivative(k);
      return out;
    }
    const std::array<Jet, 3> v = RotationVector(q);
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k <= order; ++k) *out++ = v[a].Derivative(k) * ang;
    return out;
  }
  std::array<Jet, 3> a;
  const bool defined = SequenceAngles(RelativeRotation(b1, F1, b2, F2, order), op.sequence, &a);
  for (int c = 0; c < 3; ++c) {
    const bool value_defined = defined || c == 1;
    double value = a[c].c[0];
    if (value_defined && c != 1 && !first_row_)
      value = UnwrapAngle(std::sin(value), std::cos(value), ref[c] + orientation_rate_[o][c] * (s.t - last_t_));
    *out++ = value_defined ? value * ang : std::nan("");
    for (int k = 1; k <= order; ++k) *out++ = defined ? a[c].Derivative(k) * ang : std::nan("");
    if (value_defined) ref[c] = value;
    orientation_rate_[o][c] = defined && order >= 1 ? a[c].Derivative(1) : 0;
  }
  *out++ = defined ? 0 : 1;
  return out;
}

// Universal joint (frames: h1 = axis 1 on body1, f1 = axis 2 at the design; h2 = axis 2
// on body2, f2 = axis 1 at the design): angle 1 turns the cross about axis 1,
// atan2(g1·h2, f1·h2); angle 2 turns body2 about axis 2 relative to the cross,
// atan2(h2·(h1 × f2), h1·f2). Both 0 at the design, continuous over turns.
double* RowEvaluator::UniversalValues(const SystemState& s, int o, double* out) {
  const int order = layout_.options().order;
  const double ang = layout_.angle_factor();
  const Output& op = model_.outputs[o];
  const Joint& jt = model_.joints[op.joint];
  const BodyKinematics& b1 = s.Kin(jt.body1);
  const BodyKinematics& b2 = s.Kin(jt.body2);
  auto jet = [&](const BodyKinematics& b, const Vec3& v) {
    Vec3 d[5];
    for (int k = 0; k <= order; ++k) d[k] = b.VectorDerivative(v, k);
    return VecJet(d, order);
  };
  auto dot = [](const std::array<Jet, 3>& a, const std::array<Jet, 3>& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const auto f1 = jet(b1, jt.frame1.f), g1 = jet(b1, jt.frame1.g), h1 = jet(b1, jt.frame1.h);
  const auto f2 = jet(b2, jt.frame2.f), h2 = jet(b2, jt.frame2.h);
  const std::array<Jet, 3> h1xf2 = {h1[1] * f2[2] - h1[2] * f2[1], h1[2] * f2[0] - h1[0] * f2[2], h1[0] * f2[1] - h1[1] * f2[0]};
  const Jet angles[2] = {Atan2(dot(g1, h2), dot(f1, h2)), Atan2(dot(h2, h1xf2), dot(h1, f2))};
  auto& ref = orientation_ref_[o];
  for (int a = 0; a < 2; ++a) {
    double value = angles[a].c[0];
    if (!first_row_) value = UnwrapAngle(std::sin(value), std::cos(value), ref[a] + orientation_rate_[o][a] * (s.t - last_t_));
    ref[a] = value;
    orientation_rate_[o][a] = order >= 1 ? angles[a].Derivative(1) : 0;
    *out++ = value * ang;
    for (int k = 1; k <= order; ++k) *out++ = angles[a].Derivative(k) * ang;
  }
  return out;
}

// Planar joint: the slides of P2 − P1 along the first body's frame axes f1, g1.
double* RowEvaluator::PlanarSlides(const SystemState& s, int o, double* out) const {
  const int order = layout_.options().order;
  const double len = layout_.length_factor();
  const Joint& jt = model_.joints[model_.outputs[o].joint];
  const BodyKinematics& b1 = s.Kin(jt.body1);
  const BodyKinematics& b2 = s.Kin(jt.body2);
  Vec3 d[5], fv[5], gv[5];
  for (int k = 0; k <= order; ++k) {
    d[k] = b2.PointDerivative(jt.frame2.origin, k) - b1.PointDerivative(jt.frame1.origin, k);
    fv[k] = b1.VectorDerivative(jt.frame1.f, k);
    gv[k] = b1.VectorDerivative(jt.frame1.g, k);
  }
  const auto jd = VecJet(d, order), jf = VecJet(fv, order), jg = VecJet(gv, order);
  for (const auto* axis : {&jf, &jg}) {
    const Jet sl = (*axis)[0] * jd[0] + (*axis)[1] * jd[1] + (*axis)[2] * jd[2];
    for (int k = 0; k <= order; ++k) *out++ = sl.Derivative(k) * len;
  }
  return out;
}

// The force columns in layout order, converted from SI to the table's units.
double* RowEvaluator::ForceValues(const ForceResults* f, double* out) const {
  const Units& u = model_.units;
  const bool si = layout_.options().si, rates = layout_.options().order >= 3;
  const double F = si ? 1 : 1 / u.force_to_si(), M = si ? 1 : 1 / u.torque_to_si();
  const size_t nd = model_.drivers.size(), nj = model_.joints.size();
  auto put = [&](double v, double v1, double scale) {
    *out++ = f ? v * scale : 0;
    if (rates) *out++ = f ? v1 * scale : 0;
  };
  for (size_t d = 0; d < nd; ++d) {
    const bool torque = model_.drivers[d].kind == DriverKind::JointRotation || model_.drivers[d].kind == DriverKind::BodyRotation;
    put(f ? f->effort[d] : 0, f ? f->effort_rate[d] : 0, torque ? M : F);
    put(f ? f->power[d] : 0, f ? f->power_rate[d] : 0, M);  // power: torque unit / s
  }
  for (size_t j = 0; j < nj; ++j) {
    const Vec3 zero = Vec3::Zero();
    const std::array<std::pair<const Vec3*, const Vec3*>, 4> groups = {
        std::make_pair(f ? &f->force[j] : &zero, f ? &f->force_rate[j] : &zero),
        std::make_pair(f ? &f->moment[j] : &zero, f ? &f->moment_rate[j] : &zero),
        std::make_pair(f ? &f->force_joint[j] : &zero, f ? &f->force_joint_rate[j] : &zero),
        std::make_pair(f ? &f->moment_joint[j] : &zero, f ? &f->moment_joint_rate[j] : &zero)};
    for (int g = 0; g < 4; ++g)
      for (int a = 0; a < 3; ++a) put((*groups[g].first)[a], (*groups[g].second)[a], g % 2 == 0 ? F : M);
  }
  for (size_t c = 0; c < model_.couplers.size(); ++c) {
    const Coupler& cp = model_.couplers[c];
    for (size_t k = 0; k < cp.coordinates.size(); ++k)
      put(f ? f->coupler_effort[c][k] : 0, f ? f->coupler_effort_rate[c][k] : 0, cp.coordinates[k].rotation ? M : F);
    put(f ? f->coupler_power[c] : 0, f ? f->coupler_power_rate[c] : 0, M);
  }
  *out++ = f ? f->kinetic * M : 0;
  *out++ = f ? f->potential * M : 0;
  *out++ = f ? f->balance * M : 0;
  return out;
}

std::vector<double> Motion::Column(int col) const {
  std::vector<double> c(rows());
  for (int r = 0; r < rows(); ++r) c[r] = at(r, col);
  return c;
}

bool Motion::Append(const double* row, int size) {
  values_.insert(values_.end(), row, row + size);
  return true;
}

MotionStop StopOf(const AnalysisReport& report) {
  MotionStop stop;
  stop.kind = report.stop;
  stop.message = report.message;
  stop.singular = report.singular;
  return stop;
}

AnalysisReport RunIntoSink(const Model& model, const AnalysisOptions& options, const MotionLayout& layout,
                           RowSink* sink) {
  RowEvaluator eval(model, layout);
  std::vector<double> row(layout.size());
  return RunKinematicAnalysis(
      model, options,
      [&](const SystemState& s, const StepDiagnostics& d) {
        eval.Evaluate(s, d, row.data());
        return sink->Append(row.data(), layout.size());
      },
      [&](const SystemState& s) { eval.Follow(s); });
}

// The table decides what the solver computes, through the run request's policy.
Motion RunMotion(const Model& model, const AnalysisOptions& options, const TableOptions& table) {
  RunPlan plan{table, options};
  DecideComputation(model, &plan);
  return RunPlanned(model, plan);
}

}  // namespace mechkin

namespace mechkin {

// Where each expression input's order-k value sits in the row of the layout the
// inputs are read from, found once by the column descriptors.
void RowEvaluator::PrepareExpressions() {
  bool any = false;
  for (const Output& o : model_.outputs) any = any || o.kind == OutputKind::Expression;
  if (!any) return;
  const TableOptions& mine = layout_.options();
  if (mine.si || !mine.all_outputs) {
    TableOptions file;
    file.order = mine.order;
    file.all_bodies = false;
    file_layout_ = std::make_unique<MotionLayout>(model_, file);
    file_units_ = std::make_unique<RowEvaluator>(model_, *file_layout_);
    file_row_.resize(file_layout_->size());
  }
  const MotionLayout& src = file_layout_ ? *file_layout_ : layout_;
  std::vector<const MotionLayout::Segment*> block(model_.outputs.size(), nullptr);
  for (const auto& g : src.segments())
    if (g.kind == MotionLayout::Segment::Kind::Output) block[g.index] = &g;
  file_block_.assign(model_.outputs.size(), -1);
  for (size_t o = 0; o < block.size(); ++o) file_block_[o] = block[o] ? block[o]->first : -1;
  expression_offsets_.assign(model_.outputs.size(), {});
  for (size_t o = 0; o < model_.outputs.size(); ++o) {
    for (const ExpressionInput& in : model_.outputs[o].inputs) {
      std::array<int, kMaxOrder + 1> at;
      at.fill(-1);
      const MotionLayout::Segment& g = *block[in.output];
      const ColumnDescriptor& head = src.columns()[g.first];
      const int component = model_.outputs[in.output].kind == OutputKind::Point ? in.component : head.component;
      for (int c = g.first; c < g.first + g.count; ++c) {
        const ColumnDescriptor& d = src.columns()[c];
        if (d.quantity == head.quantity && d.component == component && d.order <= kMaxOrder) at[d.order] = c;
      }
      expression_offsets_[o].push_back(at);
    }
  }
}

// The expression's jet from its inputs' jets (file units, docs/format.md "Expression
// outputs"): exact time derivatives by Taylor arithmetic up to the lowest order every
// input has; higher orders, and a value outside a function's domain, read NaN.
double* RowEvaluator::ExpressionValues(const SystemState& s, int o, double* out) {
  static constexpr double kFact[] = {1, 1, 2, 6, 24};
  const int order = layout_.options().order;
  if (following_) return std::fill_n(out, order + 1, std::nan(""));
  if (file_units_) return std::copy_n(file_row_.data() + file_block_[o], order + 1, out);
  const Output& op = model_.outputs[o];
  expression_jets_.resize(std::max(expression_jets_.size(), op.inputs.size()));
  int known = order;
  for (size_t i = 0; i < op.inputs.size(); ++i) {
    Jet& j = expression_jets_[i];
    j = Jet{};
    for (int k = 0; k <= order; ++k) {
      const int at = expression_offsets_[o][i][k];
      if (at < 0) known = std::min(known, k - 1);
      else j.c[k] = current_row_[at] / kFact[k];
    }
  }
  Jet v;
  try {
    v = op.expression->EvalWithSlotJets(s.t, expression_jets_);
  } catch (const JetDomainError&) {
    known = -1;
  }
  for (int k = 0; k <= order; ++k) *out++ = k <= known ? v.Derivative(k) : std::nan("");
  return out;
}

}  // namespace mechkin
