// `mechkin convert`: the shared pieces (numbers, expression texts, the document's
// layout) and the entry point; the two directions are convert_markers.cpp and
// convert_global.cpp.
#include "io/convert.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>

#include "io/convert_internal.hpp"
#include "model/frames.hpp"

namespace mechkin {

namespace convert {

const BodySpec* Context::Body(BodyIndex b) const {
  if (b == kGround) return nullptr;
  for (const BodySpec& body : spec.bodies)
    if (body.name && *body.name == model.bodies[b].name) return &body;
  return nullptr;
}

std::pair<Vec3, Mat3> Context::Pose(BodyIndex b) const {
  if (b == kGround) return {Vec3::Zero(), Mat3::Identity()};
  return {model.bodies[b].position, CalcA(model.bodies[b].euler)};
}

void Context::Note(const std::string& pointer, const std::string& what) const {
  notes->push_back(pointer + ": " + what);
}

Context MakeContext(const Model& model, std::vector<std::string>* notes) {
  Context ctx{model, *model.spec, 1, 1, notes, {}, {}, {}};
  ctx.unit = model.units.length_to_si;
  ctx.scale = model.characteristic_length / ctx.unit;
  ctx.notes = notes;
  ctx.body_index["ground"] = kGround;
  for (int b = 0; b < model.num_bodies(); ++b) ctx.body_index[model.bodies[b].name] = b;
  for (size_t j = 0; j < model.joints.size(); ++j) ctx.joint_index[model.joints[j].name] = static_cast<int>(j);
  for (size_t o = 0; o < model.outputs.size(); ++o) ctx.output_index[model.outputs[o].name] = static_cast<int>(o);
  return ctx;
}

Json Number(double v, double scale) {
  if (std::abs(v) < 1e-13 * scale) v = 0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  const double tidy = std::strtod(buf, nullptr);
  if (std::abs(tidy - v) <= 2 * std::numeric_limits<double>::epsilon() * std::abs(v)) v = tidy;  // ≤ 2 ulp
  if (v == std::round(v) && std::abs(v) < 1e15) return Json(static_cast<long long>(v));
  return Json(v);
}

Json NumberVector(const Vec3& v, double scale) {
  return Json::array({Number(v.x(), scale), Number(v.y(), scale), Number(v.z(), scale)});
}

// A value of the file copied as written (a literal is not tidied).
Json ScalarJson(const Scalar& s) {
  if (s.kind == Scalar::Kind::Expression) return Json(s.text);
  if (s.number == std::round(s.number) && std::abs(s.number) < 1e15) return Json(static_cast<long long>(s.number));
  return Json(s.number);
}

Json VectorJson(const Vector3Spec& v) { return Json::array({ScalarJson(v.c[0]), ScalarJson(v.c[1]), ScalarJson(v.c[2])}); }

namespace {

std::string ShortestText(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string Text(const Scalar& s) { return s.kind == Scalar::Kind::Expression ? s.text : ShortestText(s.number); }

// An operand that needs no parentheses after a binary + or −: a name or a plain
// number (the expression grammar: docs/format.md "Parameters").
bool IsAtom(const std::string& t) {
  if (t.empty()) return false;
  char* end = nullptr;
  std::strtod(t.c_str(), &end);
  if (end == t.c_str() + t.size() && t[0] != '-' && t[0] != '+') return true;
  for (char c : t)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return !std::isdigit(static_cast<unsigned char>(t[0]));
}

// A sum or difference outside parentheses (a unary sign included).
bool HasOuterSign(const std::string& t) {
  int depth = 0;
  for (char c : t) {
    depth += c == '(' ? 1 : c == ')' ? -1 : 0;
    if (depth == 0 && (c == '+' || c == '-')) return true;
  }
  return false;
}

std::string Operand(const Scalar& s) {
  const std::string t = Text(s);
  return IsAtom(t) || !HasOuterSign(t) ? t : "(" + t + ")";
}

bool IsZero(const Scalar& s) { return s.kind == Scalar::Kind::Number && s.number == 0; }

std::string Negated(const std::string& t) { return IsAtom(t) ? "-" + t : "-(" + t + ")"; }

// `whole` without its ending `tail` ("X - P" less " - P": X).
std::optional<std::string> StripTrailing(const std::string& whole, const std::string& tail) {
  if (whole.size() <= tail.size() || whole.compare(whole.size() - tail.size(), tail.size(), tail) != 0)
    return std::nullopt;
  return whole.substr(0, whole.size() - tail.size());
}

// "P + R" less "P": R (+ and − are the grammar's lowest, left-associative
// operators, so "P + R" is P plus the value of R whatever R's own terms).
std::optional<std::string> StripLeading(const std::string& whole, const std::string& head) {
  if (whole.size() <= head.size() || whole.compare(0, head.size(), head) != 0) return std::nullopt;
  std::string rest = whole.substr(head.size());
  if (rest.size() > 2 && rest.front() == '(' && rest.back() == ')' && !HasOuterSign(rest) &&
      rest.find(')') == rest.size() - 1)
    rest = rest.substr(1, rest.size() - 2);  // the parentheses Sum put around it
  return rest;
}

Json TextJson(const std::string& t) {
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (!t.empty() && end == t.c_str() + t.size() && std::isfinite(v)) return ScalarJson(Scalar::Of(v));
  return Json(t);
}

}  // namespace

// Sum undoes Difference and Difference undoes Sum textually, so that a file
// converted there and back keeps its own expressions (and its numbers' exact values).
Json Difference(const Scalar& a, const Scalar& b, double scale) {
  if (a.kind == Scalar::Kind::Number && b.kind == Scalar::Kind::Number) return Number(a.number - b.number, scale);
  if (IsZero(b)) return ScalarJson(a);
  if (IsZero(a)) return Json(Negated(Text(b)));
  if (Text(a) == Text(b)) return Json(0);
  if (auto rest = StripLeading(Text(a), Text(b) + " + "); rest && a.kind == Scalar::Kind::Expression)
    return TextJson(*rest);
  return Json(Text(a) + " - " + Operand(b));
}

Json Sum(const Scalar& a, const Scalar& b, double scale) {
  if (a.kind == Scalar::Kind::Number && b.kind == Scalar::Kind::Number) return Number(a.number + b.number, scale);
  if (IsZero(b)) return ScalarJson(a);
  if (IsZero(a)) return ScalarJson(b);
  if (Text(b) == Negated(Text(a))) return Json(0);
  if (auto rest = StripTrailing(Text(b), " - " + Operand(a)); rest && b.kind == Scalar::Kind::Expression)
    return TextJson(*rest);
  return Json(Text(a) + " + " + Operand(b));
}

bool UsesParameters(const Scalar& s) { return s.kind == Scalar::Kind::Expression; }

bool UsesParameters(const std::optional<Vector3Spec>& v) {
  return v && (UsesParameters(v->c[0]) || UsesParameters(v->c[1]) || UsesParameters(v->c[2]));
}

bool UsesParameters(const std::optional<OrientationSpec>& o) {
  if (!o) return false;
  bool uses = false;
  switch (o->form) {
    case OrientationSpec::Form::AxisAngle: return UsesParameters(o->axis) || UsesParameters(o->angle);
    case OrientationSpec::Form::EulerParameters:
      for (const Scalar& s : o->euler) uses = uses || UsesParameters(s);
      return uses;
    case OrientationSpec::Form::Matrix:
      for (const auto& row : o->matrix)
        for (const Scalar& s : row) uses = uses || UsesParameters(s);
      return uses;
  }
  return uses;
}

bool LiteralIdentity(const std::optional<OrientationSpec>& o) {
  if (!o) return true;
  if (UsesParameters(o)) return false;
  switch (o->form) {
    case OrientationSpec::Form::AxisAngle: return o->angle.number == 0;
    case OrientationSpec::Form::EulerParameters:
      return o->euler[0].number > 0 && o->euler[1].number == 0 && o->euler[2].number == 0 && o->euler[3].number == 0;
    case OrientationSpec::Form::Matrix:
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (o->matrix[i][j].number != (i == j ? 1.0 : 0.0)) return false;
      return true;
  }
  return false;
}

void InsertBefore(Json* object, const std::string& before, const std::string& key, Json value) {
  if (!object->contains(before)) {
    (*object)[key] = std::move(value);
    return;
  }
  Json out = Json::object();
  for (auto& item : object->items()) {
    if (item.key() == before) out[key] = std::move(value);
    if (item.key() != key) out[item.key()] = std::move(item.value());
  }
  *object = std::move(out);
}

namespace {

constexpr size_t kLineWidth = 110;

std::string Inline(const Json& j) {
  if (j.is_object()) {
    std::string s = "{";
    for (const auto& item : j.items()) s += (s.size() > 1 ? ", " : "") + Json(item.key()).dump() + ": " + Inline(item.value());
    return s + "}";
  }
  if (j.is_array()) {
    std::string s = "[";
    for (const auto& e : j) s += (s.size() > 1 ? ", " : "") + Inline(e);
    return s + "]";
  }
  return j.dump();
}

// `used`: the columns of the line before the value (indent and key).
std::string Pretty(const Json& j, size_t indent, size_t used, bool top) {
  const std::string flat = Inline(j);
  if ((!top && used + flat.size() <= kLineWidth) || !(j.is_object() || j.is_array()) || j.empty()) return flat;
  const std::string pad(indent + 2, ' ');
  std::string s = j.is_object() ? "{\n" : "[\n";
  bool first = true;
  for (const auto& item : j.items()) {
    s += first ? "" : ",\n";
    first = false;
    const std::string key = j.is_object() ? Json(item.key()).dump() + ": " : "";
    s += pad + key + Pretty(item.value(), indent + 2, pad.size() + key.size(), false);
  }
  return s + "\n" + std::string(indent, ' ') + (j.is_object() ? "}" : "]");
}

}  // namespace

std::string Dump(const Json& doc) { return Pretty(doc, 0, 0, true) + "\n"; }

}  // namespace convert

FileForm FormOf(const MechanismSpec& spec) {
  for (const JointSpec& j : spec.joints)
    if (j.marker1 || j.marker2) return FileForm::Markers;
  return FileForm::Global;
}

ConvertResult ConvertMechanism(const std::string& text, const Model& model, FileForm to) {
  ConvertResult result;
  if (!model.spec) {
    result.error = "the model keeps no spec to convert";
    return result;
  }
  convert::Json doc;
  try {
    doc = convert::Json::parse(text);
  } catch (const std::exception& e) {
    result.error = std::string("the file cannot be read again as JSON: ") + e.what();
    return result;
  }
  const convert::Context ctx = convert::MakeContext(model, &result.notes);
  const bool ok = to == FileForm::Markers ? convert::ToMarkers(ctx, &doc, &result.error)
                                          : convert::ToGlobal(ctx, &doc, &result.error);
  if (ok) result.text = convert::Dump(doc);
  return result;
}

}  // namespace mechkin
