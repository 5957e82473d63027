#include "model/compile.hpp"

#include <cctype>
#include <cmath>

#include "model/compiler.hpp"

namespace mechkin {

Compiler::Compiler(const MechanismSpec& spec, const ParameterOverrides& overrides, DiagnosticLog* out,
                   std::shared_ptr<const ExpressionCache> expressions)
    : spec_(spec), overrides_(overrides), out_(*out), expressions_(std::move(expressions)) {
  if (!expressions_ || expressions_->spec() != &spec) {
    recording_ = std::make_shared<ExpressionCache>(spec);
    expressions_ = recording_;
  }
  slot_values_.assign(expressions_->num_slots(), 0.0);
  slot_known_.assign(expressions_->num_slots(), 0);
}

std::optional<Model> Compiler::Run() {
  CompileHeader();
  CompileParameters();
  CompileUnits();
  by_markers_ = spec_.UsesMarkers();
  out_.SetPlace(Section::Ground);
  CompileMarkers(kGround, spec_.ground_markers);
  model_.ground_shapes = CompileShapes(spec_.ground_shapes);
  for (const BodySpec& b : spec_.bodies) Place(Section::Bodies, b.pointer), CompileBody(b);
  for (const JointSpec& j : spec_.joints) Place(Section::Joints, j.pointer), CompileJoint(j);
  if (by_markers_) PlaceByMarkers();
  for (const JointSpec& j : spec_.joints) Place(Section::Joints, j.pointer), CompileJointLimits(j);
  for (const CouplerSpec& c : spec_.couplers) Place(Section::Couplers, c.pointer), CompileCoupler(c);
  for (const DriverSpec& d : spec_.drivers) Place(Section::Drivers, d.pointer), CompileDriver(d);
  CompileAnalysis();
  for (const OutputSpec& o : spec_.outputs) Place(Section::Outputs, o.pointer), CompileOutput(o);
  for (const OutputSpec* o : pending_reductions_) Place(Section::Outputs, o->pointer), CompileReduction(*o);
  CompileExpect();
  CompileGravity();
  CompileView();
  for (const LoadSpec& l : spec_.loads) Place(Section::Loads, l.pointer), CompileLoad(l);
  if (out_.has_errors() || !spec_.valid) return std::nullopt;
  Place(Section::WholeModel, "");
  model_.characteristic_length = CharacteristicLength(model_);
  WarnFarPoints();
  WarnOddLengths();
  WarnStrayJointPoints();
  CheckDriverSpans();
  CheckLoadSpans();
  if (out_.has_errors()) return std::nullopt;
  model_.expressions = expressions_;
  return std::move(model_);
}

// The element index is the pointer's last token ("/bodies/3" → 3).
void Compiler::Place(Section section, const std::string& element_pointer) {
  const size_t slash = element_pointer.rfind('/');
  int index = 0;
  if (slash != std::string::npos && slash + 1 < element_pointer.size())
    index = std::atoi(element_pointer.c_str() + slash + 1);
  out_.SetPlace(section, index);
}

// ---- Values ---------------------------------------------------------------

std::optional<double> Compiler::Value(const Scalar& s) {
  switch (s.kind) {
    case Scalar::Kind::Number:
      return s.number;
    case Scalar::Kind::Expression:
      return ConstantExpression(s.text, s.pointer);
    case Scalar::Kind::Invalid:
      break;
  }
  Error(s.pointer, s.text, s.fix);
  return std::nullopt;
}

// An expression over the parameters (no t): "crank*cos(30*pi/180)". One naming a
// parameter that failed is not evaluated (that parameter has its error).
std::optional<double> Compiler::ConstantExpression(const std::string& text, const std::string& p) {
  if (UsesFailedParameter(text)) return std::nullopt;
  if (const auto cached = CachedConstant(text)) return cached;
  try {  // not cached, or it fails: parse with the values, for the exact diagnostic
    const Expression e = Expression::Parse(text, &symbols_, /*allow_time=*/false);
    const double d = e.Eval(0).c[0];
    if (std::isfinite(d)) return d;
    Error(p, "'" + Shorten(text) + "' evaluates to " + std::to_string(d), "check the expression and the parameters");
  } catch (const ExpressionError& err) {
    Error(p, "bad expression at column " + std::to_string(err.column) + ": " + err.what(), UnknownNameFix(err));
  } catch (const std::exception& err) {
    Error(p, "'" + Shorten(text) + "' cannot be evaluated: " + err.what(),
          "check the expression and the parameters' values");
  }
  return std::nullopt;
}

// The value from the spec's expression parsed once (expression_cache.hpp), when it
// parses and evaluates to a finite number with every parameter it uses resolved;
// otherwise nullopt and the caller takes the diagnosing path. The same number as
// parsing with the values substituted: the same nodes, constants as slots.
std::optional<double> Compiler::CachedConstant(const std::string& text) {
  const ExpressionCache::Constant* c = expressions_->FindConstant(&text);
  if (c && c->expression.text() != text) c = nullptr;  // keyed by address: make sure it is this text
  try {
    if (!c && recording_)
      c = recording_->RecordConstant(&text, Expression::ParseWithSlots(text, expressions_->slots(), false));
    if (!c) return std::nullopt;
    for (int slot : c->slots)
      if (!slot_known_[slot]) return std::nullopt;
    const double d = c->expression.EvalWithSlots(0, slot_values_).c[0];
    if (std::isfinite(d)) return d;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

// A parameter-free function of time, parsed once per spec.
std::shared_ptr<const Expression> Compiler::CachedTimeFunction(const std::string& text) {
  if (auto e = expressions_->FindTimeFunction(&text); e && e->text() == text) return e;
  if (!recording_ || !NamesUsed(text).empty()) return nullptr;
  try {
    auto e = std::make_shared<const Expression>(Expression::Parse(text));
    recording_->RecordTimeFunction(&text, e);
    return e;
  } catch (const std::exception&) {
    return nullptr;
  }
}

const std::vector<std::string>& Compiler::NamesUsed(const std::string& text) {
  if (const auto* names = expressions_->FindNames(&text)) return *names;
  if (recording_) return recording_->RecordNames(&text);
  names_scratch_ = Expression::Names(text);
  return names_scratch_;
}

bool Compiler::UsesFailedParameter(const std::string& text) const {
  if (failed_parameters_.empty()) return false;
  for (const std::string& name : Expression::Names(text))
    if (failed_parameters_.count(name)) return true;
  return false;
}

// "did you mean 'crank'?" for a mistyped parameter.
std::string Compiler::UnknownNameFix(const ExpressionError& err) const {
  if (err.unknown_name.empty()) return "";
  std::vector<std::string> names;
  for (const auto& kv : symbols_) names.push_back(kv.first);
  const std::string guess = DidYouMean(err.unknown_name, names);
  if (!guess.empty()) return "did you mean '" + guess + "'?";
  return names.empty() ? "declare it in the top-level \"parameters\"" : "parameters: " + Join(names);
}

std::optional<int> Compiler::Integer(const std::optional<Scalar>& s, const std::string& key) {
  if (!s) return std::nullopt;
  const auto d = Value(*s);
  if (!d) return std::nullopt;
  if (*d == std::floor(*d) && std::abs(*d) <= 1e9) return static_cast<int>(*d);
  Error(s->pointer, "'" + key + "' must be an integer of magnitude below 1e9, not " + std::to_string(*d));
  return std::nullopt;
}

std::optional<Vec3> Compiler::Vector(const std::optional<Vector3Spec>& v, bool nonzero) {
  if (!v) return std::nullopt;
  return VectorValue(*v, nonzero);
}

std::optional<Vec3> Compiler::VectorValue(const Vector3Spec& v, bool nonzero) {
  if (!v.error.empty()) {
    Error(v.pointer, v.error);
    return std::nullopt;
  }
  Vec3 out;
  for (int k = 0; k < 3; ++k) {
    const auto c = Value(v.c[k]);
    if (!c) return std::nullopt;
    out[k] = *c;
  }
  const std::string& key = v.key;
  if (nonzero && (!std::isfinite(out.norm()) || out.cwiseAbs().maxCoeff() > 1e150)) {
    Error(v.pointer, "'" + key + "' is too large to normalize", "give a direction with components of ordinary size");
    return std::nullopt;
  }
  if (nonzero && !(out.norm() > 1e-150)) {
    Error(v.pointer, "'" + key + "' has zero length", "give a non-zero direction vector");
    return std::nullopt;
  }
  return out;
}

// A point in the file's length unit, in metres. Coordinates beyond 1e12 m
// (a typo, or values whose squares overflow) are refused.
std::optional<Vec3> Compiler::LengthVector(const std::optional<Vector3Spec>& spec) {
  auto v = Vector(spec, false);
  if (!v) return v;
  *v *= length_;
  for (int k = 0; k < 3; ++k)
    if (std::abs((*v)[k]) > kMaxCoordinate) {
      Error(spec->pointer + "/" + std::to_string(k),
            "coordinate " + FormatNumber((*v)[k] / length_) + " " + model_.units.length_name + " is beyond 1e12 m",
            "check the number and the length unit (units/length)");
      return std::nullopt;
    }
  return v;
}

// Reference to a body by name: ground gives kGround; a body that failed, nullopt.
std::optional<BodyIndex> Compiler::BodyRef(const std::optional<std::string>& name, const std::string& key,
                                           const std::string& ptr) {
  if (!name) return std::nullopt;
  if (*name == "ground") return kGround;
  const auto it = body_index_.find(*name);
  if (it == body_index_.end()) {
    std::vector<std::string> names = {"ground"};
    for (const auto& kv : body_index_) names.push_back(kv.first);
    const std::string guess = DidYouMean(*name, names);
    Error(ptr + "/" + key, "unknown body '" + Shorten(*name) + "'",
          (guess.empty() ? "" : "did you mean '" + guess + "'? ") + "valid bodies: " + Join(names));
    return std::nullopt;
  }
  if (it->second == -2) return std::nullopt;
  return it->second;
}

// ---- Sections ---------------------------------------------------------------

void Compiler::CompileHeader() {
  out_.SetPlace(Section::Header);
  if (auto v = Integer(spec_.version, "mechkin"); v && *v != 1)
    Error("/mechkin", "unsupported format version " + std::to_string(*v), "this mechkin reads version 1");
  model_.name = spec_.name;
  model_.description = spec_.description;
  model_.source = spec_.source;
}

namespace {

// The accepted name `name` spells with other separators ("Nmm", "N.m", "lbf-in" for
// N*mm, N*m, lbf*in), else "": a better guess than the nearest by edits ("Nmm" is
// one edit from N*m too). Case is kept: MN is not mN.
std::string UnitSpelledOtherwise(const std::string& name, const std::vector<std::string>& names) {
  auto plain = [](const std::string& s) {
    std::string out;
    for (char c : s)
      if (std::isalnum(static_cast<unsigned char>(c))) out += c;
    return out;
  };
  for (const std::string& n : names)
    if (plain(n) == plain(name)) return n;
  return "";
}

}  // namespace

void Compiler::CompileUnits() {
  out_.SetPlace(Section::Units);
  if (spec_.units) {
    const UnitsSpec& u = *spec_.units;
    auto unit = [&](const std::optional<std::string>& name, const char* key, auto to_si,
                    const std::vector<std::string>& names, std::string* unit_name, double* factor) {
      if (!name) return;
      if (auto f = to_si(*name)) {
        *unit_name = *name;
        *factor = *f;
        return;
      }
      const bool named_force = std::string(key) == "force" || std::string(key) == "torque";
      std::string g = named_force ? UnitSpelledOtherwise(*name, names) : "";  // "Nmm": N*mm
      if (g.empty()) g = DidYouMean(*name, names);
      Error(std::string("/units/") + key, std::string("unknown ") + key + " unit '" + Shorten(*name) + "'",
            (g.empty() ? "" : "did you mean '" + g + "'? ") + "use one of " + Join(names));
    };
    Units& m = model_.units;
    unit(u.mass, "mass", MassUnitToSi, MassUnitNames(), &m.mass_name, &m.mass_to_si);
    unit(u.length, "length", LengthUnitToSi, LengthUnitNames(), &m.length_name, &m.length_to_si);
    unit(u.angle, "angle", AngleUnitToSi, AngleUnitNames(), &m.angle_name, &m.angle_to_si);
    unit(u.force, "force", ForceUnitToSi, ForceUnitNames(), &m.force_name, &m.named_force_to_si);
    unit(u.torque, "torque", TorqueUnitToSi, TorqueUnitNames(), &m.torque_name, &m.named_torque_to_si);
  }
  length_ = model_.units.length_to_si;
  angle_ = model_.units.angle_to_si;
}

void Compiler::CompileAnalysis() {
  out_.SetPlace(Section::Analysis);
  if (!spec_.analysis) return;
  const AnalysisSpec& a = *spec_.analysis;
  auto s = Value(a.start);
  auto e = Value(a.end);
  auto n = Integer(a.steps, "steps");
  if (s && e && !(*e > *s)) Error("/analysis/end", "'end' must be greater than 'start'", "set end > start");
  if (n && *n < 1) Error("/analysis/steps", "'steps' must be at least 1", "give the number of intervals (rows = steps + 1)");
  if (n && *n > kMaxSteps) Error("/analysis/steps", SpanProblem(0, 1, *n), "use fewer steps");
  if (s && e && n && SpanProblem(*s, *e, *n).empty()) model_.analysis = Analysis{*s, *e, *n, {}, {}};
  if (a.branch && model_.analysis) CompileBranch(*a.branch, &*model_.analysis);
}

// "branch": {"joints": {"D": -40}}: revolute angles / prismatic slides from the design
// pose (a marker joint: from its markers' coincidence); "flip": ["D"]: the other closure.
void Compiler::CompileBranch(const BranchSpec& b, Analysis* an) {
  for (const auto& [name, value] : b.joints) {
    const auto joint = BranchJoint(name, value.pointer);
    if (!joint) continue;
    const JointDescriptor& t = *model_.joints[*joint].type;
    const auto v = Value(value);
    if (!v) continue;
    // A hint beyond one turn (or beyond the coordinates' 1e12 m) names no branch the
    // assembly can compare with: 1e308 was silently ignored.
    const bool turn = t.coordinates == JointCoordinates::Angle;
    const double si = *v * (turn ? angle_ : length_);
    if (!(std::abs(si) <= (turn ? 2 * M_PI * (1 + 1e-12) : kMaxCoordinate))) {
      Error(value.pointer, "branch hint " + FormatNumber(*v) + " " + (turn ? model_.units.angle_name : model_.units.length_name) +
                               (turn ? " is more than one turn from the design pose" : " is beyond 1e12 m"),
            turn ? "give the joint's angle from the design pose within one turn (360 deg)" : "check the number and its unit");
      continue;
    }
    an->branch_joints.emplace_back(*joint, si);
  }
  for (const auto& [name, p] : b.flip)
    if (auto j = BranchJoint(name, p)) an->branch_flips.push_back(*j);
}

// A joint a branch may be named by: a revolute or prismatic joint of the file.
std::optional<int> Compiler::BranchJoint(const std::string& name, const std::string& p) {
  const auto it = joint_index_.find(name);
  if (it == joint_index_.end() || it->second < 0) {
    std::vector<std::string> names;
    for (const auto& kv : joint_index_) names.push_back(kv.first);
    const std::string g = DidYouMean(name, names);
    Error(p, "unknown joint '" + Shorten(name) + "'", g.empty() ? "valid joints: " + Join(names) : "did you mean '" + g + "'?");
    return std::nullopt;
  }
  const JointDescriptor& t = *model_.joints[it->second].type;
  if (t.coordinates != JointCoordinates::Angle && t.coordinates != JointCoordinates::Slide) {
    Error(p, "branch hints are revolute angles or prismatic slides; '" + name + "' is " + t.name,
          "hint a revolute or prismatic joint of the branch");
    return std::nullopt;
  }
  return it->second;
}

void Compiler::CompileExpect() {
  out_.SetPlace(Section::Expect);
  if (!spec_.expect) return;
  const ExpectSpec& e = *spec_.expect;
  model_.expect.grubler = Integer(e.grubler, "grubler");
  model_.expect.mobility = Integer(e.mobility, "mobility");
  model_.expect.redundant = Integer(e.redundant, "redundant");
  model_.expect.idle = Integer(e.idle, "idle");
  model_.expect.driven = e.driven;
  if (const auto c = Value(e.min_clearance)) model_.expect.min_clearance = *c * length_;
  CompileBounds(e.min, true);
  CompileBounds(e.max, false);
}

// "min"/"max": {name: v}, v in the column's unit in the file's units (kept so).
void Compiler::CompileBounds(const std::vector<std::pair<std::string, Scalar>>& bounds, bool is_min) {
  const std::string base = is_min ? "/expect/min/" : "/expect/max/";
  for (const auto& [key, scalar] : bounds) {
    MotionBound b;
    b.key = key;
    b.is_min = is_min;
    const std::optional<double> v = Value(scalar);
    const bool named = ResolveColumnName(key, base + key, is_min ? "expect min" : "expect max", &b.column);
    if (!v || !named) continue;
    b.value = *v;
    model_.expect.bounds.push_back(b);
  }
}

// "gravity": [gx, gy, gz] in length/s².
void Compiler::CompileGravity() {
  out_.SetPlace(Section::Gravity);
  if (auto g = Vector(spec_.gravity, false)) model_.gravity = *g * length_;
}

// "view": the page's settings, checked by the reader; plot columns by `view`.
void Compiler::CompileView() {
  if (!spec_.view) return;
  const ViewSpec& v = *spec_.view;
  if (v.up) model_.view.up = *v.up == "x" ? Vec3::UnitX() : *v.up == "z" ? Vec3::UnitZ() : Vec3::UnitY();
  model_.view.plots = v.plots;
  model_.view.paused = v.paused;
}

// ---- Entry points -----------------------------------------------------------

std::optional<Model> CompileModel(std::shared_ptr<const MechanismSpec> spec, const ParameterOverrides& overrides,
                                  DiagnosticLog* out, std::shared_ptr<const ExpressionCache> expressions) {
  std::optional<Model> model = Compiler(*spec, overrides, out, std::move(expressions)).Run();
  if (model) model->spec = std::move(spec);
  return model;
}

LoadResult Compile(std::shared_ptr<const MechanismSpec> spec, const ParameterOverrides& overrides) {
  return Compile(std::move(spec), overrides, nullptr);
}

LoadResult Compile(std::shared_ptr<const MechanismSpec> spec, const ParameterOverrides& overrides,
                   std::shared_ptr<const ExpressionCache> expressions) {
  DiagnosticLog list;
  LoadResult result;
  result.model = CompileModel(std::move(spec), overrides, &list, std::move(expressions));
  result.errors = std::move(list.errors);
  result.warnings = std::move(list.warnings);
  if (!result.errors.empty()) result.model.reset();
  return result;
}

LoadResult Compile(const MechanismSpec& spec, const ParameterOverrides& overrides) {
  return Compile(std::make_shared<const MechanismSpec>(spec), overrides);
}

}  // namespace mechkin
