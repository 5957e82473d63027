// Outputs, loads and functions of time.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "model/compiler.hpp"

namespace mechkin {

std::optional<TimeFunction> Compiler::CompileFunction(const FunctionSpec& f, double scale) {
  if (f.kind == FunctionSpec::Kind::Invalid) return std::nullopt;  // reported by the reader
  if (f.kind == FunctionSpec::Kind::Table) return CompileTable(f, scale);
  if (UsesFailedParameter(f.text)) return std::nullopt;
  if (auto cached = CachedTimeFunction(f.text)) return TimeFunction(std::move(cached), scale);
  try {
    auto e = std::make_shared<Expression>(Expression::Parse(f.text, &symbols_));
    return TimeFunction(e, scale);
  } catch (const ExpressionError& err) {
    const std::string fix = UnknownNameFix(err);
    Error(f.pointer, std::string("bad expression at column ") + std::to_string(err.column) + ": " + err.what(),
          !fix.empty() && !symbols_.empty()
              ? fix
              : "expressions use t, numbers, + - * / ^, parentheses, pi and sin cos tan asin acos atan atan2 exp log sqrt");
    return std::nullopt;
  }
}

// A table's spline, with a warning where the smooth interpolation rings.
std::optional<TimeFunction> Compiler::CompileTable(const FunctionSpec& f, double scale) {
  const Interpolation how = f.interpolation == "linear" ? Interpolation::Linear
                            : f.interpolation == "cubic" ? Interpolation::Cubic
                                                         : Interpolation::Quintic;
  try {
    auto spline = std::make_shared<TableSpline>(f.times, f.values, how);
    int k = 0;
    const double over = spline->MaxOvershoot(&k), range = spline->ValueRange();
    if (range > 0 && over > 0.05 * range) {
      std::ostringstream o;
      o << "the smooth interpolation overshoots the data by " << over << " (" << std::lround(100 * over / range)
        << " % of the table's range) between t = " << spline->knot(k) << " and " << spline->knot(k + 1) << " s";
      Warn(f.pointer + "/table/" + std::to_string(k), o.str(),
           "add rows where the data turns sharply, or use \"interpolation\": \"linear\" (velocity then jumps at the rows)");
    }
    return TimeFunction(spline, scale);
  } catch (const std::exception& e) {
    Error(f.pointer + "/table", e.what());
    return std::nullopt;
  }
}

void Compiler::CompileOutput(const OutputSpec& o) {
  const std::optional<std::string> name = o.name ? o.name : DefaultOutputName(o);
  bool ok = name && o.type;
  if (name) ok = CheckOutputName(*name, o.pointer) && ok;
  if (!ok) return;
  if (*o.type == "reduction") return pending_reductions_.push_back(&o);  // after every output
  Output out;
  if (!CompileOutputGeometry(o, &out)) return;
  out.name = *name;
  model_.outputs.push_back(out);
}

bool Compiler::CheckOutputName(const std::string& name, const std::string& ptr) {
  bool ok = true;
  if (output_names_.count(name)) {
    Error(ptr + "/name", "duplicate output name '" + name + "'", "give every output a unique name");
    ok = false;
  } else if (body_index_.count(name)) {
    Error(ptr + "/name", "output name '" + name + "' is also a body name", "table columns would clash; rename it");
    ok = false;
  } else if (name == "t" || name == "newton_iterations" || name == "residual" || name == "condition" ||
             name.rfind("error_bound", 0) == 0) {
    Error(ptr + "/name", "output name '" + name + "' is the name of a built-in table column",
          "rename the output (t, newton_iterations, residual, condition and error_bound* are reserved)");
    ok = false;
  }
  output_names_.insert(name);
  return ok;
}

bool Compiler::CompileOutputGeometry(const OutputSpec& o, Output* out) {
  const std::string& type = *o.type;
  const std::string& ptr = o.pointer;
  if (type == "point") {
    out->kind = OutputKind::Point;
    auto b = BodyRef(o.body, "body", ptr);
    if (o.marker) {  // a marker's point, already in body coordinates
      const auto m = b ? Marker(*b, o.marker, ptr + "/marker") : std::nullopt;
      if (!m) return false;
      out->body1 = *b;
      out->point1 = m->origin;
    } else {
      auto p = LengthVector(o.point);
      if (!b || !p) return false;
      out->body1 = *b;
      out->point1 = LocalPoint(*b, *p);
    }
    if (o.frame) {
      auto f = BodyRef(o.frame, "frame", ptr);
      if (!f) return false;
      out->frame = *f;
    }
    return true;
  }
  if (type == "velocity_ratio") return out->kind = OutputKind::VelocityRatio, CompileVelocityRatio(o, out);
  if (type == "orientation") return out->kind = OutputKind::Orientation, CompileOrientationOutput(o, out);
  if (type == "joint") return out->kind = OutputKind::JointCoordinate, CompileJointOutput(o, out);
  if (type == "angle") return out->kind = OutputKind::Angle, CompileAngleOutput(o, out);
  if (type == "clearance") return out->kind = OutputKind::Clearance, CompileClearanceOutput(o, out);
  if (type == "expression") return out->kind = OutputKind::Expression, CompileExpressionOutput(o, out);
  out->kind = OutputKind::Distance;
  auto b1 = BodyRef(o.body1, "body1", ptr);
  auto b2 = BodyRef(o.body2, "body2", ptr);
  auto p1 = LengthVector(o.point1);
  auto p2 = LengthVector(o.point2);
  if (!b1 || !b2 || !p1 || !p2) return false;
  out->body1 = *b1;
  out->body2 = *b2;
  out->point1 = LocalPoint(*b1, *p1);
  out->point2 = LocalPoint(*b2, *p2);
  return true;
}

bool Compiler::CompileJointOutput(const OutputSpec& o, Output* out) {
  const std::string& ptr = o.pointer;
  const auto index = FindJoint(o.joint, ptr, false);
  if (!index || *index < 0) return false;
  const Joint& j = model_.joints[*index];
  if (j.type->coordinates == JointCoordinates::None) {
    Error(ptr + "/joint", "'" + j.name + "' is a distance link: its length does not change",
          "use a distance output between its two points, or an angle output");
    return false;
  }
  if (o.sequence && j.type->coordinates != JointCoordinates::Orientation) {
    Error(ptr + "/sequence", "'sequence' applies to spherical joints; '" + j.name + "' is " + j.type->name,
          "remove it");
    return false;
  }
  out->sequence = "ZYX";
  if (o.sequence && !CompileSequence(o, out)) return false;
  out->joint = *index;
  out->body1 = j.body1;
  out->body2 = j.body2;
  return true;
}

// {"type": "velocity_ratio", "output", "input"}: d(output)/d(input); `output` an
// earlier one-coordinate output (revolute or prismatic joint, distance, angle),
// `input` such an output or a driver.
bool Compiler::CompileVelocityRatio(const OutputSpec& o, Output* out) {
  const std::string& ptr = o.pointer;
  if (!o.output || !o.input) return false;
  const std::string &of = *o.output, &in = *o.input;
  std::vector<std::string> scalar;
  int of_index = -1, in_output = -1, in_driver = -1;
  for (size_t k = 0; k < model_.outputs.size(); ++k) {
    if (!IsScalarOutput(model_.outputs[k])) continue;
    scalar.push_back(model_.outputs[k].name);
    if (model_.outputs[k].name == of) of_index = static_cast<int>(k);
    if (model_.outputs[k].name == in) in_output = static_cast<int>(k);
  }
  for (size_t k = 0; k < model_.drivers.size(); ++k)
    if (model_.drivers[k].name == in) in_driver = static_cast<int>(k);
  const std::string fix = "name an earlier output with one coordinate (revolute or prismatic joint, distance, "
                          "angle)" + (scalar.empty() ? std::string() : ": " + Join(scalar));
  if (of_index < 0) Error(ptr + "/output", "'" + Shorten(of) + "' is not such an output", fix);
  if (in_output < 0 && in_driver < 0)
    Error(ptr + "/input", "'" + Shorten(in) + "' is neither such an output nor a driver", fix + ", or a driver");
  if (of_index < 0 || (in_output < 0 && in_driver < 0)) return false;
  out->ratio_of = of_index;
  out->ratio_input_output = in_output;
  out->ratio_input_driver = in_output < 0 ? in_driver : -1;
  return true;
}

bool Compiler::IsScalarOutput(const Output& o) const {
  if (o.kind == OutputKind::Distance || o.kind == OutputKind::Angle) return true;
  if (o.kind != OutputKind::JointCoordinate) return false;
  const JointCoordinates c = model_.joints[o.joint].type->coordinates;
  return c == JointCoordinates::Angle || c == JointCoordinates::Slide;
}

// {"type": "orientation", "body", "relative_to"?, "sequence"}.
bool Compiler::CompileOrientationOutput(const OutputSpec& o, Output* out) {
  auto b = BodyRef(o.body, "body", o.pointer);
  std::optional<BodyIndex> rel = kGround;
  if (o.relative_to) rel = BodyRef(o.relative_to, "relative_to", o.pointer);
  if (!b || !rel || !CompileSequence(o, out)) return false;
  out->body1 = *rel;
  out->body2 = *b;
  return true;
}

bool Compiler::CompileSequence(const OutputSpec& o, Output* out) {
  if (!o.sequence) return false;
  const std::string& seq = *o.sequence;
  static const std::vector<std::string> kSequences = {
      "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ",
      "axis-angle", "euler-parameters"};
  if (std::find(kSequences.begin(), kSequences.end(), seq) == kSequences.end()) {
    const std::string g = DidYouMean(seq, kSequences);
    Error(o.pointer + "/sequence", "unknown sequence '" + Shorten(seq) + "'",
          (g.empty() ? "" : "did you mean '" + g + "'? ") + "sequences: " + Join(kSequences) +
              " (rotation sequences are intrinsic: ZYX = yaw about z, then pitch about the new y, then roll)");
    return false;
  }
  out->sequence = seq;
  return true;
}

// {"type": "angle", "body1", "vector1", "body2", "vector2", "about"?}: directions in
// global design coordinates, stored as unit vectors fixed in their bodies.
bool Compiler::CompileAngleOutput(const OutputSpec& o, Output* out) {
  const std::string& ptr = o.pointer;
  auto b1 = BodyRef(o.body1, "body1", ptr);
  auto b2 = BodyRef(o.body2, "body2", ptr);
  std::vector<Vec3> global;  // the directions as written, for the parallel check
  auto direction = [&](const std::optional<Vector3Spec>& spec, std::optional<BodyIndex> body) -> std::optional<Vec3> {
    auto v = Vector(spec, true);
    if (!v) return std::nullopt;
    if (!(v->norm() > 0)) {
      Error(spec->pointer, "'" + spec->key + "' is the zero vector", "give a direction, e.g. [1, 0, 0]");
      return std::nullopt;
    }
    global.push_back(v->normalized());
    if (!body) return std::nullopt;
    return Vec3((Pose(*body).second.transpose() * v->normalized()).normalized());
  };
  auto v1 = direction(o.vector1, b1);
  auto v2 = direction(o.vector2, b2);
  if (!b1 || !b2 || !v1 || !v2) return false;
  out->body1 = *b1;
  out->body2 = *b2;
  out->vector1 = *v1;
  out->vector2 = *v2;
  if (o.about) {
    auto a = direction(o.about, b1);
    if (!a) return false;
    for (size_t k = 0; k + 1 < global.size(); ++k)
      if (global.back().cross(global[k]).norm() < 1e-6) {  // at the design pose
        Error(ptr + "/about", "'about' is parallel to one of the two vectors: the signed angle about it is undefined",
              "choose an axis across both vectors (e.g. their common normal)");
        return false;
      }
    out->about = *a;
    out->signed_about = true;
  }
  return true;
}

}  // namespace mechkin

namespace mechkin {

namespace {

// Outputs an expression can read by their name alone: one coordinate each.
bool SingleValued(const Model& model, const Output& o) {
  switch (o.kind) {
    case OutputKind::Distance:
    case OutputKind::Angle:
    case OutputKind::Clearance:
    case OutputKind::Expression:
    case OutputKind::VelocityRatio:
      return true;
    case OutputKind::JointCoordinate: {
      const JointCoordinates c = model.joints[o.joint].type->coordinates;
      return c == JointCoordinates::Angle || c == JointCoordinates::Slide;
    }
    default:
      return false;
  }
}

int OutputIndex(const Model& model, const std::string& name) {
  for (size_t k = 0; k < model.outputs.size(); ++k)
    if (model.outputs[k].name == name) return static_cast<int>(k);
  return -1;
}

}  // namespace

// A name of an expression output: an earlier single-valued output, or "P.x" (.y, .z)
// of an earlier point output. Returns false (reported) when it is neither.
bool Compiler::ResolveExpressionName(const std::string& name, const std::string& ptr, ExpressionInput* in) {
  in->output = OutputIndex(model_, name);
  if (in->output >= 0 && SingleValued(model_, model_.outputs[in->output])) return true;
  if (in->output >= 0) {
    const bool point = model_.outputs[in->output].kind == OutputKind::Point;
    Error(ptr, "output '" + name + "' has several coordinates",
          point ? "name one of them: " + name + ".x, " + name + ".y or " + name + ".z"
                : "expressions read single-valued outputs (joint angles or slides, distances, angles, clearances, "
                  "expressions) and point coordinates (P.x)");
    return false;
  }
  const size_t dot = name.find('.');
  if (dot != std::string::npos) {
    const int base = OutputIndex(model_, name.substr(0, dot));
    const std::string comp = name.substr(dot + 1);
    if (base >= 0 && model_.outputs[base].kind == OutputKind::Point && (comp == "x" || comp == "y" || comp == "z")) {
      *in = {base, comp == "x" ? 0 : comp == "y" ? 1 : 2};
      return true;
    }
  }
  UnknownExpressionName(name, ptr);
  return false;
}

void Compiler::UnknownExpressionName(const std::string& name, const std::string& ptr) {
  std::vector<std::string> known;
  for (const Output& o : model_.outputs) known.push_back(o.name);
  for (const auto& kv : symbols_) known.push_back(kv.first);
  for (const OutputSpec& later : spec_.outputs)
    if (later.name && *later.name == name.substr(0, name.find('.')) && OutputIndex(model_, *later.name) < 0) {
      Error(ptr, "output '" + *later.name + "' comes after this expression (or failed to compile)",
            "list the outputs an expression reads before it");
      return;
    }
  const std::string guess = DidYouMean(name, known);
  Error(ptr, "unknown name '" + name + "' in the expression",
        guess.empty() ? "expressions read t, pi, the parameters and earlier outputs (a point's coordinates as P.x)"
                      : "did you mean '" + guess + "'?");
}

// "value": parsed once, the parameters as constants (file units), each other name a
// slot filled per row with that output's value and time derivatives (its jet).
bool Compiler::CompileExpressionOutput(const OutputSpec& o, Output* out) {
  if (!o.value) return false;
  const std::string ptr = o.pointer + "/value";
  ExpressionSlots slots;
  for (const std::string& name : Expression::DottedNames(*o.value)) {
    if (slots.count(name) || symbols_.count(name)) continue;
    ExpressionInput in;
    if (!ResolveExpressionName(name, ptr, &in)) return false;
    slots[name] = static_cast<int>(out->inputs.size());
    out->inputs.push_back(in);
  }
  try {
    out->expression = std::make_shared<Expression>(Expression::ParseOverColumns(*o.value, symbols_, slots));
  } catch (const ExpressionError& err) {
    Error(ptr, std::string("bad expression at column ") + std::to_string(err.column) + ": " + err.what(),
          "expressions use numbers, + - * / ^, parentheses, t, pi, sin cos tan asin acos atan atan2 exp log sqrt, "
          "the parameters and earlier outputs");
    return false;
  }
  return true;
}

}  // namespace mechkin

namespace mechkin {

// A reduction's `of` or an `expect` bound's key: a single-valued output, or "P.x" (.y,
// .z) of a point output — any output of the file, since both are read after the run.
// `what` names the place in messages ("'of'", "expect min"). False (reported) when not.
bool Compiler::ResolveColumnName(const std::string& name, const std::string& ptr, const std::string& what,
                                 OutputColumn* in) {
  in->output = OutputIndex(model_, name);
  if (in->output >= 0 && SingleValued(model_, model_.outputs[in->output])) return true;
  const size_t dot = name.find('.');
  const int base = in->output >= 0 ? in->output : dot == std::string::npos ? -1 : OutputIndex(model_, name.substr(0, dot));
  const bool point = base >= 0 && model_.outputs[base].kind == OutputKind::Point;
  if (point && in->output < 0) {
    const std::string comp = name.substr(dot + 1);
    if (comp == "x" || comp == "y" || comp == "z") return *in = {base, comp == "x" ? 0 : comp == "y" ? 1 : 2}, true;
  }
  if (base >= 0) {
    Error(ptr, what + " names output '" + name + "', which has several coordinates",
          point ? "name one of them: " + model_.outputs[base].name + ".x, .y or .z"
                : "name a single-valued output (a joint angle or slide, a distance, an angle, a clearance, an "
                  "expression, a velocity ratio) or a point's coordinate (P.x)");
    return false;
  }
  std::vector<std::string> known;
  for (const Output& o : model_.outputs) known.push_back(o.name);
  const bool reduction = std::any_of(model_.reductions.begin(), model_.reductions.end(),
                                     [&](const Reduction& r) { return r.name == name; });
  const std::string guess = DidYouMean(name, known);
  Error(ptr, reduction ? what + " names the reduction '" + name + "': reductions read the table's columns"
                       : what + " names no output '" + name + "'",
        guess.empty() ? "name a column output of the file (a point's coordinate as P.x)"
                      : "did you mean '" + guess + "'?");
  return false;
}

// {"type": "reduction", "of", "reduce", "t"}: after every output, so `of` may name any
// of them. `t` goes with "at" only and lies in the analysis span.
void Compiler::CompileReduction(const OutputSpec& o) {
  const std::string& ptr = o.pointer;
  static const std::vector<std::string> kinds = {"min", "max", "rms", "mean", "at", "sse"};
  Reduction r;
  r.name = *o.name;
  r.of = o.of.value_or("");
  bool ok = o.of && ResolveColumnName(*o.of, ptr + (o.of_columns.empty() ? "/of" : "/of/0"), "'of'", &r.column);
  const auto kind = o.reduce ? std::find(kinds.begin(), kinds.end(), *o.reduce) : kinds.end();
  if (o.reduce && kind == kinds.end()) {
    const std::string g = DidYouMean(*o.reduce, kinds);
    Error(ptr + "/reduce", "unknown reduction '" + Shorten(*o.reduce) + "'",
          (g.empty() ? "" : "did you mean '" + g + "'? ") + "use one of " + Join(kinds));
    ok = false;
  }
  if (!o.reduce || kind == kinds.end()) return;
  r.kind = static_cast<ReduceKind>(kind - kinds.begin());
  if (r.kind == ReduceKind::Sse) {
    if (ok && CompileTargets(o, &r)) model_.reductions.push_back(r);
    return;
  }
  if (!o.of_columns.empty()) {
    Error(ptr + "/of", "an array of columns goes with \"reduce\": \"sse\" only", "name one column");
    ok = false;
  }
  if (o.targets) {
    Error(ptr + "/targets", "'targets' goes with \"reduce\": \"sse\" only", "remove 'targets' or use \"sse\"");
    ok = false;
  }
  if (r.kind == ReduceKind::At && !o.t) {
    Error(ptr, "a reduction \"at\" needs 't'", "add \"t\": the time (s) to read the column at");
    ok = false;
  } else if (r.kind != ReduceKind::At && o.t) {
    Error(ptr + "/t", "'t' goes with \"reduce\": \"at\" only", "remove 't' (a \"" + *o.reduce + "\" is over the whole run)");
    ok = false;
  } else if (o.t) {
    const std::optional<double> t = Value(o.t);
    if (!t) return;
    ok = TimeInRun(*t, ptr + "/t") && ok;
    r.t = *t;
  }
  if (ok) model_.reductions.push_back(r);
}

bool Compiler::TimeInRun(double t, const std::string& ptr) {
  const Analysis* a = model_.analysis ? &*model_.analysis : nullptr;
  if (!a || (t >= a->start && t <= a->end)) return true;
  Error(ptr, "t = " + FormatNumber(t) + " s is outside the run (" + FormatNumber(a->start) + " to " +
                 FormatNumber(a->end) + " s)",
        "give a time within /analysis start and end");
  return false;
}

// "sse": the columns of "of" and the "targets" table, one row per time with one value
// per column (docs/format.md "Targets").
bool Compiler::CompileTargets(const OutputSpec& o, Reduction* r) {
  const std::string& ptr = o.pointer;
  bool ok = true;
  r->columns = {r->column};
  r->column_names = {r->of};
  for (size_t k = 1; k < o.of_columns.size(); ++k) {
    OutputColumn c;
    ok = ResolveColumnName(o.of_columns[k], ptr + "/of/" + std::to_string(k), "'of'", &c) && ok;
    r->columns.push_back(c);
    r->column_names.push_back(o.of_columns[k]);
  }
  if (o.t) {
    Error(ptr + "/t", "'t' goes with \"reduce\": \"at\" only", "an \"sse\" reads its times from \"targets\": {\"t\"}");
    ok = false;
  }
  if (!o.targets) {
    Error(ptr, "a reduction \"sse\" needs 'targets'",
          "add \"targets\": {\"t\": [times], \"values\": [one value per time, or per time an array per column]}");
    return false;
  }
  const OutputSpec::Targets& tg = *o.targets;
  if (tg.values.size() != tg.t.size()) {
    Error(ptr + "/targets/values", "'values' has " + std::to_string(tg.values.size()) + " entries for " +
                                       std::to_string(tg.t.size()) + " times",
          "give one entry per time in 't'");
    return false;
  }
  for (size_t i = 0; i < tg.t.size(); ++i) {
    ok = TimeInRun(tg.t[i], ptr + "/targets/t/" + std::to_string(i)) && ok;
    if (tg.values[i].size() != r->columns.size()) {
      Error(ptr + "/targets/values/" + std::to_string(i),
            "a target row has " + std::to_string(tg.values[i].size()) + " values for " +
                std::to_string(r->columns.size()) + " columns in 'of'",
            "give one value per column of 'of', in its order");
      ok = false;
    }
  }
  r->target_t = tg.t;
  r->target_values = tg.values;
  return ok;
}

}  // namespace mechkin
