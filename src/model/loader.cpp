#include "model/loader.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <algorithm>
#include <limits>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <functional>
#include <set>
#include <sstream>

#include "model/frames.hpp"
#include "model/stray_points.hpp"

namespace mechkin {

using nlohmann::json;

std::string Diagnostic::ToString() const {
  std::string s = (pointer.empty() ? std::string("(file)") : pointer) + ": " + message;
  if (!fix.empty()) s += " — " + fix;
  return s;
}

namespace {

std::string EscapeToken(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

// The names of a list, at most 12 of them (a 10,000-body file must not turn
// each misspelled reference into a megabyte of candidates).
std::string Join(const std::vector<std::string>& v) {
  constexpr size_t kShown = 12;
  std::string s;
  for (size_t i = 0; i < v.size() && i < kShown; ++i) s += (i ? ", " : "") + v[i];
  if (v.size() > kShown) s += ", … (" + std::to_string(v.size()) + " in all)";
  return s;
}

size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string DidYouMean(const std::string& word, const std::vector<std::string>& choices) {
  std::string best;
  size_t best_d = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& c : choices) {
    const size_t d = EditDistance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

std::string TypeName(const json& j) {
  switch (j.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return "a boolean";
    case json::value_t::string:
      return "a string";
    case json::value_t::array:
      return "an array";
    case json::value_t::object:
      return "an object";
    case json::value_t::number_float:
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
      return "a number";
    default:
      return "an unsupported value";
  }
}

std::string Shorten(const std::string& s) { return s.size() > 40 ? s.substr(0, 37) + "..." : s; }

// Walks one file, collecting diagnostics.
class Reader {
 public:
  explicit Reader(LoadResult* out) : out_(out) {}

  void Error(const std::string& ptr, const std::string& msg, const std::string& fix = "") {
    out_->errors.push_back({ptr, msg, fix});
  }
  void Warn(const std::string& ptr, const std::string& msg, const std::string& fix = "") {
    out_->warnings.push_back({ptr, msg, fix});
  }

  // Reports unknown and missing keys of `obj`. Returns false when obj is not an object.
  bool CheckObject(const json& obj, const std::string& ptr, const std::vector<std::string>& allowed,
                   const std::vector<std::string>& required, const std::string& what) {
    if (!obj.is_object()) {
      Error(ptr, what + " must be a JSON object, not " + TypeName(obj));
      return false;
    }
    for (const auto& item : obj.items()) {
      if (std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end()) {
        const std::string guess = DidYouMean(item.key(), allowed);
        Error(ptr + "/" + EscapeToken(item.key()), "unknown key '" + Shorten(item.key()) + "' in " + what,
              guess.empty() ? "allowed keys: " + Join(allowed) : "did you mean '" + guess + "'?");
      }
    }
    for (const auto& key : required)
      if (!obj.contains(key)) Error(ptr + "/" + key, "missing key '" + key + "' in " + what, "add it");
    return true;
  }

  std::optional<double> Number(const json& obj, const std::string& key, const std::string& ptr) {
    if (!obj.contains(key)) return std::nullopt;
    return ScalarValue(obj.at(key), ptr + "/" + key, "'" + key + "'");
  }

  // A number written as a JSON number or as an expression string over the
  // parameters (no t): "crank*cos(30*pi/180)".
  std::optional<double> ScalarValue(const json& v, const std::string& p, const std::string& what) {
    if (v.is_string()) return ConstantExpression(v.get<std::string>(), p);
    if (!v.is_number()) {
      Error(p, what + " must be a number or an expression string, not " + TypeName(v));
      return std::nullopt;
    }
    const double d = v.get<double>();
    if (!std::isfinite(d)) {
      Error(p, what + " is not a finite number", "use a finite value");
      return std::nullopt;
    }
    return d;
  }

  std::optional<double> ConstantExpression(const std::string& text, const std::string& p) {
    try {
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

  // "did you mean 'crank'?" for a mistyped parameter.
  std::string UnknownNameFix(const ExpressionError& err) const {
    if (err.unknown_name.empty()) return "";
    std::vector<std::string> names;
    for (const auto& kv : symbols_) names.push_back(kv.first);
    const std::string guess = DidYouMean(err.unknown_name, names);
    if (!guess.empty()) return "did you mean '" + guess + "'?";
    return names.empty() ? "declare it in the top-level \"parameters\"" : "parameters: " + Join(names);
  }

  ExpressionSymbols& symbols() { return symbols_; }

  std::optional<int> Integer(const json& obj, const std::string& key, const std::string& ptr) {
    if (!obj.contains(key)) return std::nullopt;
    const json& v = obj.at(key);
    if (v.is_number_integer() || v.is_number_unsigned()) {
      if (v.is_number_unsigned() ? v.get<unsigned long long>() > 1000000000ull
                                 : (v.get<long long>() > 1000000000ll || v.get<long long>() < -1000000000ll)) {
        Error(ptr + "/" + key, "'" + key + "' is out of range", "use an integer of magnitude below 1e9");
        return std::nullopt;
      }
      return static_cast<int>(v.get<long long>());
    }
    if (v.is_number_float() || v.is_string()) {
      const auto d = ScalarValue(v, ptr + "/" + key, "'" + key + "'");
      if (!d) return std::nullopt;
      if (*d == std::floor(*d) && std::abs(*d) <= 1e9) return static_cast<int>(*d);
      Error(ptr + "/" + key, "'" + key + "' must be an integer of magnitude below 1e9, not " + std::to_string(*d));
      return std::nullopt;
    }
    Error(ptr + "/" + key, "'" + key + "' must be an integer, not " + TypeName(v));
    return std::nullopt;
  }

  std::optional<std::string> String(const json& obj, const std::string& key, const std::string& ptr) {
    if (!obj.contains(key)) return std::nullopt;
    const json& v = obj.at(key);
    if (!v.is_string()) {
      Error(ptr + "/" + key, "'" + key + "' must be a string, not " + TypeName(v));
      return std::nullopt;
    }
    return v.get<std::string>();
  }

  // A name usable in table column headers.
  std::optional<std::string> Name(const json& obj, const std::string& ptr, const std::string& what) {
    auto s = String(obj, "name", ptr);
    if (!s) return std::nullopt;
    const bool ok =
        !s->empty() && s->size() <= 64 && (std::isalpha(static_cast<unsigned char>((*s)[0])) || (*s)[0] == '_') &&
        std::all_of(s->begin(), s->end(),
                    [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; });
    if (!ok) {
      Error(ptr + "/name", "invalid " + what + " name '" + Shorten(*s) + "'",
            "use 1-64 letters, digits, '_' or '-', starting with a letter or '_' (names become table columns)");
      return std::nullopt;
    }
    return s;
  }

  std::optional<Vec3> Vector(const json& obj, const std::string& key, const std::string& ptr, bool nonzero) {
    if (!obj.contains(key)) return std::nullopt;
    return VectorValue(obj.at(key), ptr + "/" + key, key, nonzero);
  }

  // A 3-vector value at pointer p (`key` names it in messages).
  std::optional<Vec3> VectorValue(const json& v, const std::string& p, const std::string& key, bool nonzero) {
    if (!v.is_array() || v.size() != 3) {
      Error(p, "'" + key + "' must be an array of 3 numbers [x, y, z], not " +
                   (v.is_array() ? "an array of " + std::to_string(v.size()) : TypeName(v)));
      return std::nullopt;
    }
    Vec3 out;
    for (int k = 0; k < 3; ++k) {
      const auto c = ScalarValue(v[k], p + "/" + std::to_string(k), "component");
      if (!c) return std::nullopt;
      out[k] = *c;
    }
    if (nonzero && (!std::isfinite(out.norm()) || out.cwiseAbs().maxCoeff() > 1e150)) {
      Error(p, "'" + key + "' is too large to normalize", "give a direction with components of ordinary size");
      return std::nullopt;
    }
    if (nonzero && !(out.norm() > 1e-150)) {
      Error(p, "'" + key + "' has zero length", "give a non-zero direction vector");
      return std::nullopt;
    }
    if (nonzero && !std::isfinite(out.norm())) {
      Error(p, "'" + key + "' is too large to normalise", "scale the direction down");
      return std::nullopt;
    }
    return out;
  }

  // Reference to a body by name: ground gives kGround.
  std::optional<BodyIndex> BodyRef(const json& obj, const std::string& key, const std::string& ptr,
                                   const std::map<std::string, BodyIndex>& bodies) {
    auto s = String(obj, key, ptr);
    if (!s) return std::nullopt;
    if (*s == "ground") return kGround;
    const auto it = bodies.find(*s);
    if (it == bodies.end()) {
      std::vector<std::string> names = {"ground"};
      for (const auto& kv : bodies) names.push_back(kv.first);
      const std::string guess = DidYouMean(*s, names);
      Error(ptr + "/" + key, "unknown body '" + Shorten(*s) + "'",
            (guess.empty() ? "" : "did you mean '" + guess + "'? ") + "valid bodies: " + Join(names));
      return std::nullopt;
    }
    return it->second;
  }

 private:
  LoadResult* out_;
  ExpressionSymbols symbols_;
};

struct JointTypeInfo {
  JointType type;
  const char* name;
  std::vector<std::string> geometry;  // required geometry keys
  std::vector<std::string> optional;
};

const std::vector<JointTypeInfo>& JointTypes() {
  static const std::vector<JointTypeInfo> kTypes = {
      {JointType::Revolute, "revolute", {"origin", "axis"}, {}},
      {JointType::Prismatic, "prismatic", {"origin", "axis"}, {}},
      {JointType::Screw, "screw", {"origin", "axis", "pitch"}, {}},
      {JointType::Cylindrical, "cylindrical", {"origin", "axis"}, {}},
      {JointType::Universal, "universal", {"origin", "axis1", "axis2"}, {}},
      {JointType::Spherical, "spherical", {"origin"}, {}},
      {JointType::Planar, "planar", {"origin", "normal"}, {}},
      {JointType::Distance, "distance", {"point1", "point2"}, {"length"}},
  };
  return kTypes;
}

// Orientation forms (format-v1 "orientation").
std::optional<Vec4> ReadOrientation(Reader& rd, const json& o, const std::string& ptr, double angle_scale) {
  if (!o.is_object()) {
    rd.Error(ptr, "'orientation' must be an object, not " + TypeName(o),
             "use {\"axis\": [x,y,z], \"angle\": a}, {\"euler_parameters\": [e0,e1,e2,e3]} or {\"matrix\": "
             "[[..],[..],[..]]}");
    return std::nullopt;
  }
  const std::vector<std::string> allowed = {"axis", "angle", "euler_parameters", "matrix"};
  rd.CheckObject(o, ptr, allowed, {}, "an orientation");
  const int forms = (o.contains("axis") || o.contains("angle")) + o.contains("euler_parameters") + o.contains("matrix");
  if (forms != 1) {
    rd.Error(ptr, forms == 0 ? "orientation gives no form" : "orientation gives more than one form",
             "give exactly one of axis+angle, euler_parameters, matrix");
    return std::nullopt;
  }
  if (o.contains("axis") || o.contains("angle")) {
    if (!o.contains("axis")) {
      rd.Error(ptr + "/axis", "missing key 'axis' next to 'angle'", "add the rotation axis");
      return std::nullopt;
    }
    if (!o.contains("angle")) {
      rd.Error(ptr + "/angle", "missing key 'angle' next to 'axis'", "add the rotation angle");
      return std::nullopt;
    }
    auto axis = rd.Vector(o, "axis", ptr, true);
    auto angle = rd.Number(o, "angle", ptr);
    if (!axis || !angle) return std::nullopt;
    return QuatFromAxisAngle(axis->normalized(), *angle * angle_scale);
  }
  if (o.contains("euler_parameters")) {
    const json& e = o.at("euler_parameters");
    const std::string p = ptr + "/euler_parameters";
    if (!e.is_array() || e.size() != 4) {
      rd.Error(p, "'euler_parameters' must be an array of 4 numbers [e0, e1, e2, e3] (scalar first)");
      return std::nullopt;
    }
    Vec4 q;
    for (int k = 0; k < 4; ++k) {
      const auto c = rd.ScalarValue(e[k], p + "/" + std::to_string(k), "component");
      if (!c) return std::nullopt;
      q[k] = *c;
    }
    if (!(q.norm() > 1e-12) || !std::isfinite(q.norm())) {
      rd.Error(p, "Euler parameters have (almost) zero length", "give a unit quaternion, e.g. [1, 0, 0, 0]");
      return std::nullopt;
    }
    if (std::abs(q.norm() - 1) > 1e-6) rd.Warn(p, "Euler parameters are not unit length; normalised");
    return q.normalized();
  }
  const json& m = o.at("matrix");
  const std::string p = ptr + "/matrix";
  Mat3 R;
  if (!m.is_array() || m.size() != 3) {
    rd.Error(p, "'matrix' must be 3 rows of 3 numbers");
    return std::nullopt;
  }
  for (int i = 0; i < 3; ++i) {
    if (!m[i].is_array() || m[i].size() != 3) {
      rd.Error(p + "/" + std::to_string(i), "each matrix row must be an array of 3 numbers");
      return std::nullopt;
    }
    for (int j = 0; j < 3; ++j) {
      const auto c = rd.ScalarValue(m[i][j], p + "/" + std::to_string(i) + "/" + std::to_string(j), "matrix entry");
      if (!c) return std::nullopt;
      R(i, j) = *c;
    }
  }
  // Re-orthonormalise small CAD round-off silently, larger defects with a warning,
  // and reject matrices that are not rotations at all.
  const double defect = (R.transpose() * R - Mat3::Identity()).norm();
  if (!(defect <= 1e-2) || !(R.determinant() > 0)) {
    rd.Error(p,
             "matrix is not a rotation (orthonormality defect " + std::to_string(defect) +
                 (R.determinant() > 0 ? "" : ", determinant <= 0") + ")",
             "give a proper orthonormal matrix (columns = body axes in global components)");
    return std::nullopt;
  }
  if (defect > 1e-9)
    rd.Warn(p, "matrix is not exactly orthonormal (defect " + std::to_string(defect) + "); re-orthonormalised");
  Eigen::JacobiSVD<Mat3> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return QuatFromMatrix(svd.matrixU() * svd.matrixV().transpose());
}

std::optional<TimeFunction> ReadFunction(Reader& rd, const json& f, const std::string& ptr, double scale) {
  if (f.is_string()) {
    try {
      auto e = std::make_shared<Expression>(Expression::Parse(f.get<std::string>(), &rd.symbols()));
      return TimeFunction(e, scale);
    } catch (const ExpressionError& err) {
      const std::string fix = rd.UnknownNameFix(err);
      rd.Error(
          ptr, std::string("bad expression at column ") + std::to_string(err.column) + ": " + err.what(),
          !fix.empty() && !rd.symbols().empty() ? fix :
          "expressions use t, numbers, + - * / ^, parentheses, pi and sin cos tan asin acos atan atan2 exp log sqrt");
      return std::nullopt;
    }
  }
  if (f.is_number()) {
    rd.Error(ptr, "'function' must be a string expression or a table",
             "write the constant as a string, e.g. \"" + f.dump() + "\"");
    return std::nullopt;
  }
  if (!f.is_object()) {
    rd.Error(ptr, "'function' must be a string expression or {\"table\": [[t, v], ...]}, not " + TypeName(f));
    return std::nullopt;
  }
  if (!rd.CheckObject(f, ptr, {"table", "interpolation"}, {"table"}, "a table function")) return std::nullopt;
  Interpolation how = Interpolation::Quintic;
  if (auto s = rd.String(f, "interpolation", ptr)) {
    if (*s == "linear") how = Interpolation::Linear;
    else if (*s == "cubic") how = Interpolation::Cubic;
    else if (*s != "quintic") {
      rd.Error(ptr + "/interpolation", "unknown interpolation '" + Shorten(*s) + "'",
               "use \"quintic\" (default, smooth to the snap), \"cubic\" or \"linear\"");
      return std::nullopt;
    }
  }
  if (!f.contains("table")) return std::nullopt;
  const json& tab = f.at("table");
  if (!tab.is_array() || tab.size() < 2) {
    rd.Error(ptr + "/table", "'table' must be an array of at least 2 rows [t, value]");
    return std::nullopt;
  }
  std::vector<double> ts, vs;
  for (size_t k = 0; k < tab.size(); ++k) {
    const json& row = tab[k];
    const std::string rp = ptr + "/table/" + std::to_string(k);
    if (!row.is_array() || row.size() != 2 || !row[0].is_number() || !row[1].is_number()) {
      rd.Error(rp, "table row must be [t, value] with two numbers");
      return std::nullopt;
    }
    ts.push_back(row[0].get<double>());
    vs.push_back(row[1].get<double>());
    if (!std::isfinite(ts.back()) || !std::isfinite(vs.back())) {
      rd.Error(rp, "table row has a non-finite number");
      return std::nullopt;
    }
    if (k > 0 && !(ts[k] > ts[k - 1])) {
      rd.Error(rp + "/0", "table times must increase strictly", "sort the rows by time and remove duplicates");
      return std::nullopt;
    }
  }
  try {
    auto spline = std::make_shared<TableSpline>(ts, vs, how);
    int k = 0;
    const double over = spline->MaxOvershoot(&k), range = spline->ValueRange();
    if (range > 0 && over > 0.05 * range) {
      std::ostringstream o;
      o << "the smooth interpolation overshoots the data by " << over << " (" << std::lround(100 * over / range)
        << " % of the table's range) between t = " << spline->knot(k) << " and " << spline->knot(k + 1) << " s";
      rd.Warn(ptr + "/table/" + std::to_string(k), o.str(),
              "add rows where the data turns sharply, or use \"interpolation\": \"linear\" (velocity then jumps at the rows)");
    }
    return TimeFunction(spline, scale);
  } catch (const std::exception& e) {
    rd.Error(ptr + "/table", e.what());
    return std::nullopt;
  }
}

std::vector<std::string> JointTypeNames() {
  std::vector<std::string> names;
  for (const auto& t : JointTypes()) names.push_back(t.name);
  return names;
}

// Reads a parsed document section by section into the model (the spec layer):
// each section reports every problem it finds with its JSON pointer and a fix,
// and a failed element is known by name (index -2) so that references to it
// do not produce a second, misleading error.
class SpecReader {
 public:
  explicit SpecReader(LoadResult* result) : rd_(result) {}
  Reader& reader() { return rd_; }
  Model& model() { return model_; }

  bool ReadHeader(const json& doc) {
    if (!rd_.CheckObject(
            doc, "",
            {"mechkin", "name", "description", "units", "parameters", "bodies", "joints", "drivers", "analysis",
             "outputs", "expect", "gravity", "loads"},
            {"mechkin", "bodies", "joints"}, "the mechanism file"))
      return false;
    if (auto v = rd_.Integer(doc, "mechkin", ""); v && *v != 1)
      rd_.Error("/mechkin", "unsupported format version " + std::to_string(*v), "this mechkin reads version 1");
    if (auto s = rd_.String(doc, "name", "")) model_.name = *s;
    if (auto s = rd_.String(doc, "description", "")) model_.description = *s;
    return true;
  }

  // Parameters first: any number below may be an expression over them.
  // A parameter defined from others is resolved once those are (cycles named).
  void ReadParameters(const json& doc, const ParameterOverrides& overrides) {
    if (doc.contains("parameters") && doc.at("parameters").is_object()) {
      parameters_doc_ = &doc.at("parameters");
      std::vector<std::pair<std::string, json>> pending;  // name, value json (number or expression)
      for (const auto& item : doc.at("parameters").items())
        if (auto value = ParameterDeclaration(item.key(), item.value())) pending.emplace_back(item.key(), *value);
      ResolveParameters(pending, overrides);
    } else if (doc.contains("parameters")) {
      rd_.Error("/parameters", "'parameters' must be an object {\"name\": value, ...}, not " +
                                   TypeName(doc.at("parameters")));
    }
    for (const auto& kv : overrides)
      if (!model_.FindParameter(kv.first)) {
        std::vector<std::string> names;
        for (const auto& p : model_.parameters) names.push_back(p.name);
        const std::string guess = DidYouMean(kv.first, names);
        rd_.Error("/parameters", "no parameter '" + Shorten(kv.first) + "' to set",
                  guess.empty() ? (names.empty() ? "the file declares no parameters" : "parameters: " + Join(names))
                                : "did you mean '" + guess + "'?");
      }
  }

  // One declaration: checks the name and the object form; returns the value's json.
  std::optional<json> ParameterDeclaration(const std::string& name, const json& v) {
    const std::string ptr = "/parameters/" + EscapeToken(name);
    const bool identifier = !name.empty() && name.size() <= 64 &&
                            (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                            std::all_of(name.begin(), name.end(), [](char c) {
                              return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                            });
    if (!identifier || Expression::IsReservedName(name)) {
      rd_.Error(ptr, "invalid parameter name '" + Shorten(name) + "'",
                "use 1-64 letters, digits or '_', starting with a letter or '_', other than t, pi and the "
                "function names");
      return std::nullopt;
    }
    Parameter param;
    param.name = name;
    if (!v.is_object()) {
      model_.parameters.push_back(param);
      return v;
    }
    if (!rd_.CheckObject(v, ptr, {"value", "tolerance", "min", "max", "description"}, {"value"}, "a parameter"))
      return std::nullopt;
    param.tolerance = PlainNumber(v, "tolerance", ptr);
    param.min = PlainNumber(v, "min", ptr);
    param.max = PlainNumber(v, "max", ptr);
    if (param.tolerance && *param.tolerance < 0)
      rd_.Error(ptr + "/tolerance", "tolerance must not be negative", "give the ± band as a positive number");
    if (param.min && param.max && !(*param.min < *param.max))
      rd_.Error(ptr + "/max", "'max' must be greater than 'min'", "swap them or widen the range");
    model_.parameters.push_back(param);
    if (!v.contains("value")) return std::nullopt;
    return v.at("value");
  }

  std::optional<double> PlainNumber(const json& obj, const std::string& key, const std::string& ptr) {
    if (!obj.contains(key)) return std::nullopt;
    if (!obj.at(key).is_number()) {
      rd_.Error(ptr + "/" + key, "'" + key + "' must be a number, not " + TypeName(obj.at(key)));
      return std::nullopt;
    }
    return rd_.Number(obj, key, ptr);
  }

  Parameter* FindParameter(const std::string& name) {
    for (auto& p : model_.parameters)
      if (p.name == name) return &p;
    return nullptr;
  }

  // Resolves values in dependency order: each pass evaluates those whose
  // parameters are known; what is left when a pass makes no progress is a cycle.
  void ResolveParameters(std::vector<std::pair<std::string, json>> pending, const ParameterOverrides& overrides) {
    ExpressionSymbols& symbols = rd_.symbols();
    while (!pending.empty()) {
      std::vector<std::pair<std::string, json>> waiting;
      for (const auto& [name, value] : pending) ResolveOne(name, value, overrides, pending, &waiting);
      if (waiting.size() == pending.size()) {
        std::vector<std::string> names;
        for (const auto& w : waiting) names.push_back(w.first);
        rd_.Error("/parameters/" + EscapeToken(waiting.front().first),
                  "parameters defined in terms of each other: " + Join(names),
                  "give at least one of them a number");
        return;
      }
      pending = std::move(waiting);
    }
    for (Parameter& p : model_.parameters)
      if (symbols.count(p.name)) p.value = symbols.at(p.name);
  }

  // Evaluates one parameter, or defers it (into `waiting`) when it names one not yet known.
  bool ResolveOne(const std::string& name, const json& value, const ParameterOverrides& overrides,
                  const std::vector<std::pair<std::string, json>>& pending,
                  std::vector<std::pair<std::string, json>>* waiting) {
    Parameter* param = FindParameter(name);
    const json& declared = parameters_doc_->at(name);
    const std::string ptr = "/parameters/" + EscapeToken(name) + (declared.is_object() ? "/value" : "");
    if (value.is_string() && param) param->expression = value.get<std::string>();
    if (const auto o = overrides.find(name); o != overrides.end()) {
      rd_.symbols()[name] = o->second;
      if (param) param->overridden = true;
      return true;
    }
    // Deferred while it names another parameter not resolved yet (a scan, not a parse:
    // resolving is then one parse per parameter, and no exception in the normal path).
    if (value.is_string())
      for (const std::string& used : Expression::Names(value.get<std::string>())) {
        const bool later = used != name && !rd_.symbols().count(used) &&
                           std::any_of(pending.begin(), pending.end(), [&](const auto& p) { return p.first == used; });
        if (later) {
          waiting->emplace_back(name, value);
          return false;
        }
      }
    if (const auto d = rd_.ScalarValue(value, ptr, "parameter '" + name + "'")) rd_.symbols()[name] = *d;
    return true;
  }

  // Units first: every other number depends on them.
  void ReadUnits(const json& doc) {
    if (doc.contains("units")) {
      const json& u = doc.at("units");
      if (rd_.CheckObject(u, "/units", {"length", "angle", "mass"}, {}, "'units'")) {
        if (auto s = rd_.String(u, "mass", "/units")) {
          if (auto f = MassUnitToSi(*s)) {
            model_.units.mass_name = *s;
            model_.units.mass_to_si = *f;
          } else {
            const std::string g = DidYouMean(*s, MassUnitNames());
            rd_.Error("/units/mass", "unknown mass unit '" + Shorten(*s) + "'",
                      (g.empty() ? "" : "did you mean '" + g + "'? ") + "use one of " + Join(MassUnitNames()));
          }
        }
        if (auto s = rd_.String(u, "length", "/units")) {
          if (auto f = LengthUnitToSi(*s)) {
            model_.units.length_name = *s;
            model_.units.length_to_si = *f;
          } else {
            const std::string g = DidYouMean(*s, LengthUnitNames());
            rd_.Error("/units/length", "unknown length unit '" + Shorten(*s) + "'",
                      (g.empty() ? "" : "did you mean '" + g + "'? ") + "use one of " + Join(LengthUnitNames()));
          }
        }
        if (auto s = rd_.String(u, "angle", "/units")) {
          if (auto f = AngleUnitToSi(*s)) {
            model_.units.angle_name = *s;
            model_.units.angle_to_si = *f;
          } else {
            const std::string g = DidYouMean(*s, AngleUnitNames());
            rd_.Error("/units/angle", "unknown angle unit '" + Shorten(*s) + "'",
                      (g.empty() ? "" : "did you mean '" + g + "'? ") + "use one of " + Join(AngleUnitNames()));
          }
        }
      }
    }
    length_ = model_.units.length_to_si;
    angle_ = model_.units.angle_to_si;
  }

  /// Every element of the array `key` through `read(element, pointer)`.
  template <typename ReadElement>
  void ReadArray(const json& doc, const std::string& key, const std::string& what, ReadElement read) {
    if (!doc.contains(key)) return;
    const json& items = doc.at(key);
    if (!items.is_array()) {
      rd_.Error("/" + key, "'" + key + "' must be an array of " + what + " objects, not " + TypeName(items));
      return;
    }
    for (size_t k = 0; k < items.size(); ++k) read(items[k], "/" + key + "/" + std::to_string(k));
  }

  void ReadBody(const json& b, const std::string& ptr) {
    if (!rd_.CheckObject(b, ptr, {"name", "description", "position", "orientation", "inertia", "shape"}, {"name", "position"},
                         "a body"))
      return;
    Body body;
    auto name = rd_.Name(b, ptr, "body");
    auto pos = LengthVector(b, "position", ptr);
    body.euler = Vec4(1, 0, 0, 0);
    bool ok = name && pos;
    if (b.contains("orientation")) {
      auto q = ReadOrientation(rd_, b.at("orientation"), ptr + "/orientation", angle_);
      if (q)
        body.euler = *q;
      else
        ok = false;
    }
    if (name && *name == "ground") {
      rd_.Error(ptr + "/name", "'ground' is reserved for the fixed frame and cannot be a moving body",
                "rename the body, or attach parts to ground directly");
      ok = false;
    } else if (name && body_index_.count(*name)) {
      rd_.Error(ptr + "/name", "duplicate body name '" + *name + "'", "give every body a unique name");
      ok = false;
    }
    if (!ok) {
      if (name && *name != "ground") body_index_.emplace(*name, -2);  // known name, invalid body
      return;
    }
    body.name = *name;
    body.position = *pos;
    if (b.contains("shape")) body.shape = ReadShape(b.at("shape"), ptr + "/shape");
    if (b.contains("inertia")) {
      body.inertia = ReadInertia(b, ptr, *pos, body.euler);
      if (!body.inertia) {
        body_index_.emplace(*name, -2);
        return;
      }
    }
    body_index_[body.name] = static_cast<BodyIndex>(model_.bodies.size());
    model_.bodies.push_back(body);
  }

  void ReadJoint(const json& jj, const std::string& ptr) {
    if (!jj.is_object()) {
      rd_.Error(ptr, "a joint must be a JSON object, not " + TypeName(jj));
      return;
    }
    auto type_s = rd_.String(jj, "type", ptr);
    const JointTypeInfo* info = nullptr;
    if (type_s) {
      for (const auto& t : JointTypes())
        if (*type_s == t.name) info = &t;
      if (!info) {
        const std::string g = DidYouMean(*type_s, JointTypeNames());
        rd_.Error(ptr + "/type", "unknown joint type '" + Shorten(*type_s) + "'",
                  (g.empty() ? "" : "did you mean '" + g + "'? ") + "types: " + Join(JointTypeNames()));
      }
    }
    std::vector<std::string> allowed = {"name", "description", "type", "body1", "body2"};
    std::vector<std::string> required = {"name", "type", "body1", "body2"};
    if (info) {
      allowed.insert(allowed.end(), info->geometry.begin(), info->geometry.end());
      allowed.insert(allowed.end(), info->optional.begin(), info->optional.end());
      required.insert(required.end(), info->geometry.begin(), info->geometry.end());
    } else {
      for (const auto& t : JointTypes()) {
        allowed.insert(allowed.end(), t.geometry.begin(), t.geometry.end());
        allowed.insert(allowed.end(), t.optional.begin(), t.optional.end());
      }
    }
    rd_.CheckObject(jj, ptr, allowed, required, info ? std::string("a ") + info->name + " joint" : "a joint");
    auto name = rd_.Name(jj, ptr, "joint");
    auto b1 = BodyRef(jj, "body1", ptr);
    auto b2 = BodyRef(jj, "body2", ptr);
    bool ok = name && b1 && b2 && info;
    if (name) {
      if (joint_index_.count(*name)) {
        rd_.Error(ptr + "/name", "duplicate joint name '" + *name + "'", "give every joint a unique name");
        ok = false;
      }
      joint_index_.emplace(*name, -2);
    }
    if (b1 && b2 && *b1 == *b2) {
      rd_.Error(ptr + "/body2", "joint connects body '" + model_.BodyName(*b1) + "' to itself",
                "a joint needs two different bodies (either may be ground)");
      ok = false;
    }
    if (!info) return;
    ReadJointGeometry(jj, ptr, *info, ok ? &*name : nullptr, b1 ? *b1 : kGround, b2 ? *b2 : kGround);
  }

  void ReadDriver(const json& d, const std::string& ptr) {
    if (!d.is_object()) {
      rd_.Error(ptr, "a driver must be a JSON object, not " + TypeName(d));
      return;
    }
    auto type_s = rd_.String(d, "type", ptr);
    std::vector<std::string> allowed = {"name", "description", "type", "function"};
    std::vector<std::string> required = {"name", "type", "function"};
    const bool by_body = (d.contains("body") || d.contains("axis")) && !(type_s && *type_s == "coordinate");
    if (type_s && *type_s == "rotation" && by_body) {
      allowed.insert(allowed.end(), {"body", "axis"});
      required.insert(required.end(), {"body", "axis"});
    } else if (type_s && (*type_s == "rotation" || *type_s == "translation")) {
      allowed.push_back("joint");
      required.push_back("joint");
    } else if (type_s && *type_s == "distance") {
      allowed.insert(allowed.end(), {"body1", "point1", "body2", "point2"});
      required.insert(required.end(), {"body1", "point1", "body2", "point2"});
    } else if (type_s && *type_s == "coordinate") {
      allowed.insert(allowed.end(), {"body", "point", "axis", "axis_body"});
      required.insert(required.end(), {"body", "point", "axis"});
    } else if (type_s && *type_s == "angle") {
      allowed.insert(allowed.end(), {"body1", "body2", "about", "vector"});
      required.insert(required.end(), {"body1", "body2", "about"});
    } else {
      if (type_s) {
        const std::string g = DidYouMean(*type_s, {"rotation", "translation", "distance", "coordinate", "angle"});
        rd_.Error(ptr + "/type", "unknown driver type '" + Shorten(*type_s) + "'",
                  (g.empty() ? "" : "did you mean '" + g + "'? ") + "types: rotation, translation, distance, coordinate, angle");
      }
      allowed.insert(allowed.end(), {"joint", "body", "axis", "body1", "point1", "body2", "point2", "point", "axis_body",
                                     "about", "vector"});
    }
    rd_.CheckObject(d, ptr, allowed, required, type_s ? "a " + *type_s + " driver" : "a driver");
    auto name = rd_.Name(d, ptr, "driver");
    bool ok = name.has_value() && type_s.has_value();
    if (name) {
      if (driver_names_.count(*name)) {
        rd_.Error(ptr + "/name", "duplicate driver name '" + *name + "'", "give every driver a unique name");
        ok = false;
      }
      driver_names_.insert(*name);
    }
    Driver drv;
    double scale = length_;
    if (type_s && *type_s == "rotation" && by_body) {
      ok = DriverOnBody(d, ptr, &drv) && ok;
      scale = angle_;
    } else if (type_s && (*type_s == "rotation" || *type_s == "translation")) {
      ok = DriverOnJoint(d, ptr, *type_s, &drv) && ok;
      scale = *type_s == "rotation" ? angle_ : length_;
    } else if (type_s && *type_s == "distance") {
      ok = DriverBetweenPoints(d, ptr, &drv) && ok;
    } else if (type_s && *type_s == "coordinate") {
      ok = DriverOnCoordinate(d, ptr, &drv) && ok;
    } else if (type_s && *type_s == "angle") {
      ok = DriverOnAngle(d, ptr, &drv) && ok;
      scale = angle_;
    } else {
      ok = false;
    }
    if (d.contains("function")) {
      auto f = ReadFunction(rd_, d.at("function"), ptr + "/function", scale);
      if (f)
        drv.function = *f;
      else
        ok = false;
    } else
      ok = false;
    if (!ok) return;
    drv.name = *name;
    model_.drivers.push_back(drv);
    driver_pointers_.push_back(ptr);
  }

  // "branch": {"joints": {"D": -40}}: revolute angles / prismatic slides from the design pose.
  void ReadBranch(const json& b, Analysis* an) {
    const std::string ptr = "/analysis/branch";
    if (!rd_.CheckObject(b, ptr, {"joints"}, {"joints"}, "'branch'")) return;
    const json& joints = b.at("joints");
    if (!joints.is_object()) {
      rd_.Error(ptr + "/joints", "'joints' must be an object {\"joint name\": coordinate}, not " + TypeName(joints));
      return;
    }
    for (const auto& item : joints.items()) {
      const std::string p = ptr + "/joints/" + EscapeToken(item.key());
      const auto it = joint_index_.find(item.key());
      if (it == joint_index_.end() || it->second < 0) {
        std::vector<std::string> names;
        for (const auto& kv : joint_index_) names.push_back(kv.first);
        const std::string g = DidYouMean(item.key(), names);
        rd_.Error(p, "unknown joint '" + Shorten(item.key()) + "'", g.empty() ? "valid joints: " + Join(names) : "did you mean '" + g + "'?");
        continue;
      }
      const JointType t = model_.joints[it->second].type;
      if (t != JointType::Revolute && t != JointType::Prismatic) {
        rd_.Error(p, "branch hints are revolute angles or prismatic slides; '" + item.key() + "' is " + JointTypeName(t),
                  "hint a revolute or prismatic joint of the branch");
        continue;
      }
      if (auto v = rd_.ScalarValue(item.value(), p, "the hint"))
        an->branch_joints.emplace_back(it->second, *v * (t == JointType::Revolute ? angle_ : length_));
    }
  }

  void ReadAnalysis(const json& doc) {
    if (doc.contains("analysis")) {
      const json& a = doc.at("analysis");
      if (rd_.CheckObject(a, "/analysis", {"start", "end", "steps", "branch"}, {"start", "end", "steps"}, "'analysis'")) {
        auto s = rd_.Number(a, "start", "/analysis");
        auto e = rd_.Number(a, "end", "/analysis");
        auto n = rd_.Integer(a, "steps", "/analysis");
        if (s && e && !(*e > *s)) rd_.Error("/analysis/end", "'end' must be greater than 'start'", "set end > start");
        if (n && *n < 1)
          rd_.Error("/analysis/steps", "'steps' must be at least 1", "give the number of intervals (rows = steps + 1)");
        if (n && *n > 10000000) rd_.Error("/analysis/steps", "'steps' is larger than 10,000,000", "use fewer steps");
        if (s && e && n && *e > *s && *n >= 1 && *n <= 10000000) model_.analysis = Analysis{*s, *e, *n, {}};
        if (a.contains("branch") && model_.analysis) ReadBranch(a.at("branch"), &*model_.analysis);
      }
    }
  }

  void ReadOutput(const json& o, const std::string& ptr) {
    if (!o.is_object()) {
      rd_.Error(ptr, "an output must be a JSON object, not " + TypeName(o));
      return;
    }
    auto type_s = rd_.String(o, "type", ptr);
    Output out;
    std::vector<std::string> allowed = {"name", "description", "type"};
    std::vector<std::string> required = {"name", "type"};
    if (type_s && *type_s == "point") {
      out.kind = OutputKind::Point;
      allowed.insert(allowed.end(), {"body", "point", "frame"});
      required.insert(required.end(), {"body", "point"});
    } else if (type_s && *type_s == "velocity_ratio") {
      out.kind = OutputKind::VelocityRatio;
      allowed.insert(allowed.end(), {"output", "input"});
      required.insert(required.end(), {"output", "input"});
    } else if (type_s && *type_s == "orientation") {
      out.kind = OutputKind::Orientation;
      allowed.insert(allowed.end(), {"body", "relative_to", "sequence"});
      required.insert(required.end(), {"body", "sequence"});
    } else if (type_s && *type_s == "joint") {
      out.kind = OutputKind::JointCoordinate;
      allowed.insert(allowed.end(), {"joint", "sequence"});
      required.push_back("joint");
    } else if (type_s && *type_s == "distance") {
      out.kind = OutputKind::Distance;
      allowed.insert(allowed.end(), {"body1", "point1", "body2", "point2"});
      required.insert(required.end(), {"body1", "point1", "body2", "point2"});
    } else if (type_s && *type_s == "angle") {
      out.kind = OutputKind::Angle;
      allowed.insert(allowed.end(), {"body1", "vector1", "body2", "vector2", "about"});
      required.insert(required.end(), {"body1", "vector1", "body2", "vector2"});
    } else {
      if (type_s) {
        const std::vector<std::string> types = {"point", "joint", "distance", "angle", "velocity_ratio", "orientation"};
        const std::string g = DidYouMean(*type_s, types);
        rd_.Error(ptr + "/type", "unknown output type '" + Shorten(*type_s) + "'",
                  (g.empty() ? "" : "did you mean '" + g + "'? ") + "types: " + Join(types));
      }
      allowed.insert(allowed.end(), {"body", "point", "joint", "body1", "point1", "body2", "point2", "vector1",
                                     "vector2", "about", "frame", "output", "input", "relative_to", "sequence"});
    }
    rd_.CheckObject(o, ptr, allowed, required, "an output");
    auto name = rd_.Name(o, ptr, "output");
    bool ok = name && type_s;
    if (name) {
      if (output_names_.count(*name)) {
        rd_.Error(ptr + "/name", "duplicate output name '" + *name + "'", "give every output a unique name");
        ok = false;
      } else if (body_index_.count(*name)) {
        rd_.Error(ptr + "/name", "output name '" + *name + "' is also a body name",
                  "table columns would clash; rename it");
        ok = false;
      } else if (*name == "t" || *name == "newton_iterations" || *name == "residual" || *name == "condition" ||
                 name->rfind("error_bound", 0) == 0) {
        rd_.Error(ptr + "/name", "output name '" + *name + "' is the name of a built-in table column",
                  "rename the output (t, newton_iterations, residual, condition and error_bound* are reserved)");
        ok = false;
      }
      output_names_.insert(*name);
    }
    if (!ok) return;
    if (out.kind == OutputKind::Point) {
      auto b = BodyRef(o, "body", ptr);
      auto p = LengthVector(o, "point", ptr);
      if (!b || !p) return;
      out.body1 = *b;
      out.point1 = LocalPoint(*b, *p);
      if (o.contains("frame")) {
        auto f = BodyRef(o, "frame", ptr);
        if (!f) return;
        out.frame = *f;
      }
    } else if (out.kind == OutputKind::VelocityRatio) {
      if (!ReadVelocityRatio(o, ptr, &out)) return;
    } else if (out.kind == OutputKind::Orientation) {
      if (!ReadOrientationOutput(o, ptr, &out)) return;
    } else if (out.kind == OutputKind::JointCoordinate) {
      auto jn = rd_.String(o, "joint", ptr);
      if (!jn) return;
      const auto it = joint_index_.find(*jn);
      if (it == joint_index_.end()) {
        std::vector<std::string> names;
        for (const auto& kv : joint_index_) names.push_back(kv.first);
        rd_.Error(ptr + "/joint", "unknown joint '" + Shorten(*jn) + "'", "valid joints: " + Join(names));
        return;
      }
      if (it->second < 0) return;
      const Joint& j = model_.joints[it->second];
      if (j.type == JointType::Distance) {
        rd_.Error(ptr + "/joint", "'" + j.name + "' is a distance link: its length does not change",
                  "use a distance output between its two points, or an angle output");
        return;
      }
      if (o.contains("sequence") && j.type != JointType::Spherical) {
        rd_.Error(ptr + "/sequence", "'sequence' applies to spherical joints; '" + j.name + "' is " + JointTypeName(j.type),
                  "remove it");
        return;
      }
      out.sequence = "ZYX";
      if (o.contains("sequence") && !ReadSequence(o, ptr, &out)) return;
      out.joint = it->second;
      out.body1 = j.body1;
      out.body2 = j.body2;
    } else if (out.kind == OutputKind::Angle) {
      if (!ReadAngleOutput(o, ptr, &out)) return;
    } else {
      auto b1 = BodyRef(o, "body1", ptr);
      auto b2 = BodyRef(o, "body2", ptr);
      auto p1 = LengthVector(o, "point1", ptr);
      auto p2 = LengthVector(o, "point2", ptr);
      if (!b1 || !b2 || !p1 || !p2) return;
      out.body1 = *b1;
      out.body2 = *b2;
      out.point1 = LocalPoint(*b1, *p1);
      out.point2 = LocalPoint(*b2, *p2);
    }
    out.name = *name;
    model_.outputs.push_back(out);
  }

  // {"type": "velocity_ratio", "output", "input"}: d(output)/d(input); `output` an
  // earlier one-coordinate output (revolute or prismatic joint, distance, angle),
  // `input` such an output or a driver.
  bool ReadVelocityRatio(const json& o, const std::string& ptr, Output* out) {
    auto of = rd_.String(o, "output", ptr);
    auto in = rd_.String(o, "input", ptr);
    if (!of || !in) return false;
    std::vector<std::string> scalar;
    int of_index = -1, in_output = -1, in_driver = -1;
    for (size_t k = 0; k < model_.outputs.size(); ++k) {
      if (!IsScalarOutput(model_.outputs[k])) continue;
      scalar.push_back(model_.outputs[k].name);
      if (model_.outputs[k].name == *of) of_index = static_cast<int>(k);
      if (model_.outputs[k].name == *in) in_output = static_cast<int>(k);
    }
    for (size_t k = 0; k < model_.drivers.size(); ++k)
      if (model_.drivers[k].name == *in) in_driver = static_cast<int>(k);
    const std::string fix = "name an earlier output with one coordinate (revolute or prismatic joint, distance, "
                            "angle)" + (scalar.empty() ? std::string() : ": " + Join(scalar));
    if (of_index < 0) rd_.Error(ptr + "/output", "'" + Shorten(*of) + "' is not such an output", fix);
    if (in_output < 0 && in_driver < 0)
      rd_.Error(ptr + "/input", "'" + Shorten(*in) + "' is neither such an output nor a driver", fix + ", or a driver");
    if (of_index < 0 || (in_output < 0 && in_driver < 0)) return false;
    out->ratio_of = of_index;
    out->ratio_input_output = in_output;
    out->ratio_input_driver = in_output < 0 ? in_driver : -1;
    return true;
  }

  bool IsScalarOutput(const Output& o) const {
    if (o.kind == OutputKind::Distance || o.kind == OutputKind::Angle) return true;
    if (o.kind != OutputKind::JointCoordinate) return false;
    const JointType t = model_.joints[o.joint].type;
    return t == JointType::Revolute || t == JointType::Prismatic;
  }

  // {"type": "orientation", "body", "relative_to"?, "sequence"}.
  bool ReadOrientationOutput(const json& o, const std::string& ptr, Output* out) {
    auto b = BodyRef(o, "body", ptr);
    std::optional<BodyIndex> rel = kGround;
    if (o.contains("relative_to")) rel = BodyRef(o, "relative_to", ptr);
    if (!b || !rel || !ReadSequence(o, ptr, out)) return false;
    out->body1 = *rel;
    out->body2 = *b;
    return true;
  }

  bool ReadSequence(const json& o, const std::string& ptr, Output* out) {
    auto seq = rd_.String(o, "sequence", ptr);
    if (!seq) return false;
    static const std::vector<std::string> kSequences = {
        "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ",
        "axis-angle", "euler-parameters"};
    if (std::find(kSequences.begin(), kSequences.end(), *seq) == kSequences.end()) {
      const std::string g = DidYouMean(*seq, kSequences);
      rd_.Error(ptr + "/sequence", "unknown sequence '" + Shorten(*seq) + "'",
                (g.empty() ? "" : "did you mean '" + g + "'? ") + "sequences: " + Join(kSequences) +
                    " (rotation sequences are intrinsic: ZYX = yaw about z, then pitch about the new y, then roll)");
      return false;
    }
    out->sequence = *seq;
    return true;
  }

  // {"type": "angle", "body1", "vector1", "body2", "vector2", "about"?}: directions in
  // global design coordinates, stored as unit vectors fixed in their bodies.
  bool ReadAngleOutput(const json& o, const std::string& ptr, Output* out) {
    auto b1 = BodyRef(o, "body1", ptr);
    auto b2 = BodyRef(o, "body2", ptr);
    std::vector<Vec3> global;  // the directions as written, for the parallel check
    auto direction = [&](const char* key, std::optional<BodyIndex> body) -> std::optional<Vec3> {
      auto v = rd_.Vector(o, key, ptr, true);
      if (!v) return std::nullopt;
      if (!(v->norm() > 0)) {
        rd_.Error(ptr + "/" + key, std::string("'") + key + "' is the zero vector", "give a direction, e.g. [1, 0, 0]");
        return std::nullopt;
      }
      global.push_back(v->normalized());
      if (!body) return std::nullopt;
      return Vec3((Pose(*body).second.transpose() * v->normalized()).normalized());
    };
    auto v1 = direction("vector1", b1);
    auto v2 = direction("vector2", b2);
    if (!b1 || !b2 || !v1 || !v2) return false;
    out->body1 = *b1;
    out->body2 = *b2;
    out->vector1 = *v1;
    out->vector2 = *v2;
    if (o.contains("about")) {
      auto a = direction("about", b1);
      if (!a) return false;
      for (size_t k = 0; k + 1 < global.size(); ++k)
        if (global.back().cross(global[k]).norm() < 1e-6) {  // at the design pose
          rd_.Error(ptr + "/about", "'about' is parallel to one of the two vectors: the signed angle about it is undefined",
                    "choose an axis across both vectors (e.g. their common normal)");
          return false;
        }
      out->about = *a;
      out->signed_about = true;
    }
    return true;
  }

  void ReadExpect(const json& doc) {
    if (doc.contains("expect")) {
      const json& e = doc.at("expect");
      if (rd_.CheckObject(e, "/expect", {"grubler", "mobility", "redundant", "idle", "driven"}, {}, "'expect'")) {
        model_.expect.grubler = rd_.Integer(e, "grubler", "/expect");
        model_.expect.mobility = rd_.Integer(e, "mobility", "/expect");
        model_.expect.redundant = rd_.Integer(e, "redundant", "/expect");
        model_.expect.idle = rd_.Integer(e, "idle", "/expect");
        if (auto s = rd_.String(e, "driven", "/expect")) {
          if (*s == "full" || *s == "under" || *s == "over")
            model_.expect.driven = *s;
          else
            rd_.Error("/expect/driven", "unknown driving status '" + Shorten(*s) + "'",
                      "use \"full\", \"under\" or \"over\"");
        }
      }
    }
  }

  // "inertia": {"mass", "center" (global design coordinates), and "moments"
  // (3×3 about the centre, global design axes) or "principal" + "axes"}.
  // Stored in body coordinates: s'_c = Aᵀ(c − r), J' = Aᵀ J A.
  std::optional<Inertia> ReadInertia(const json& b, const std::string& body_ptr, const Vec3& r, const Vec4& euler) {
    const std::string ptr = body_ptr + "/inertia";
    const json& in = b.at("inertia");
    if (!rd_.CheckObject(in, ptr, {"mass", "center", "moments", "principal", "axes"}, {"mass", "center"}, "'inertia'"))
      return std::nullopt;
    Inertia out;
    auto mass = rd_.Number(in, "mass", ptr);
    auto center = LengthVector(in, "center", ptr);
    if (mass && !(*mass > 0)) rd_.Error(ptr + "/mass", "mass must be positive", "give the body's mass in units/mass");
    if (!mass || !(*mass > 0) || !center) return std::nullopt;
    const Mat3 A = CalcA(euler);
    out.mass = *mass * model_.units.mass_to_si;
    out.center = A.transpose() * (*center - r);
    const double scale = model_.units.mass_to_si * length_ * length_;
    std::optional<Mat3> J;
    if (in.contains("moments") == (in.contains("principal") || in.contains("axes"))) {
      rd_.Error(ptr, "give either 'moments' or 'principal' with 'axes'",
                "moments: [[Ixx,Ixy,Ixz],[Ixy,Iyy,Iyz],[Ixz,Iyz,Izz]] about the centre, in global design axes");
      return std::nullopt;
    }
    J = in.contains("moments") ? ReadMatrix(in, "moments", ptr) : ReadPrincipal(in, ptr);
    if (!J) return std::nullopt;
    *J *= scale;
    if (!CheckInertiaTensor(*J, ptr)) return std::nullopt;
    out.moments = A.transpose() * *J * A;
    return out;
  }

  std::optional<Mat3> ReadMatrix(const json& o, const std::string& key, const std::string& ptr) {
    const json& m = o.at(key);
    if (!m.is_array() || m.size() != 3) {
      rd_.Error(ptr + "/" + key, "'" + key + "' must be 3 rows of 3 numbers");
      return std::nullopt;
    }
    Mat3 out;
    for (int i = 0; i < 3; ++i) {
      auto row = rd_.VectorValue(m[i], ptr + "/" + key + "/" + std::to_string(i), "row", false);
      if (!row) return std::nullopt;
      out.row(i) = row->transpose();
    }
    return out;
  }

  std::optional<Mat3> ReadPrincipal(const json& in, const std::string& ptr) {
    auto p = rd_.Vector(in, "principal", ptr, false);
    if (!in.contains("axes")) rd_.Error(ptr + "/axes", "'principal' needs 'axes'", "give the 3 principal axes (rows)");
    if (!p || !in.contains("axes")) return std::nullopt;
    auto axes = ReadMatrix(in, "axes", ptr);
    if (!axes) return std::nullopt;
    Mat3 U;
    for (int k = 0; k < 3; ++k) U.col(k) = axes->row(k).transpose().normalized();
    if ((U.transpose() * U - Mat3::Identity()).norm() > 1e-6) {
      rd_.Error(ptr + "/axes", "principal axes are not perpendicular", "give three perpendicular axes");
      return std::nullopt;
    }
    return U * p->asDiagonal() * U.transpose();
  }

  bool CheckInertiaTensor(const Mat3& J, const std::string& ptr) {
    const double size = J.cwiseAbs().maxCoeff();
    if ((J - J.transpose()).cwiseAbs().maxCoeff() > 1e-9 * size) {
      rd_.Error(ptr + "/moments", "the inertia tensor is not symmetric", "Ixy must equal Iyx, and so on");
      return false;
    }
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(J);
    const Vec3 I = eig.eigenvalues();
    if (I.minCoeff() < -1e-12 * size || I[0] + I[1] < I[2] * (1 - 1e-9)) {
      rd_.Error(ptr, "the inertia tensor is not physical (principal moments " + FormatTime(I[0]) + ", " +
                         FormatTime(I[1]) + ", " + FormatTime(I[2]) + " must be ≥ 0 and obey I1 + I2 ≥ I3)",
                "check the moments and their units (mass × length², about the centre of mass)");
      return false;
    }
    return true;
  }

  // "shape": {"type": "box", "size": [a, b, c]} | {"type": "cylinder", "radius", "length", "axis"}
  // | {"type": "sphere", "radius"}, with an optional "center"; all in body coordinates (file units).
  // For drawing only; a bad shape is reported but does not change the analysis.
  std::optional<Shape> ReadShape(const json& o, const std::string& ptr) {
    auto type = rd_.String(o, "type", ptr);
    if (!rd_.CheckObject(o, ptr, {"type", "size", "radius", "length", "axis", "center"}, {"type"}, "'shape'") || !type)
      return std::nullopt;
    Shape sh;
    if (auto c = rd_.Vector(o, "center", ptr, false)) sh.center = *c * length_;
    auto positive = [&](const char* key) -> double {
      auto v = rd_.Number(o, key, ptr);
      if (!v || !(*v > 0)) {
        rd_.Error(ptr + "/" + key, std::string("'") + key + "' must be a positive number", "give the size in units/length");
        return 0;
      }
      return *v * length_;
    };
    if (*type == "box") {
      sh.kind = Shape::Kind::Box;
      auto size = rd_.Vector(o, "size", ptr, true);
      if (!size) rd_.Error(ptr + "/size", "a box needs 'size': [a, b, c] along the body axes");
      else sh.size = size->cwiseAbs() * length_;
    } else if (*type == "cylinder") {
      sh.kind = Shape::Kind::Cylinder;
      sh.radius = positive("radius");
      sh.length = positive("length");
      if (auto a = rd_.Vector(o, "axis", ptr, true)) {
        if (a->norm() > 0) sh.axis = a->normalized();
        else rd_.Error(ptr + "/axis", "the cylinder 'axis' is the zero vector", "give a direction, e.g. [0, 0, 1]");
      }
    } else if (*type == "sphere") {
      sh.kind = Shape::Kind::Sphere;
      sh.radius = positive("radius");
    } else {
      rd_.Error(ptr + "/type", "unknown shape '" + Shorten(*type) + "'", "use box, cylinder or sphere");
      return std::nullopt;
    }
    return sh;
  }

  // "gravity": [gx, gy, gz] in length/s².
  void ReadGravity(const json& doc) {
    if (!doc.contains("gravity")) return;
    if (auto g = rd_.Vector(doc, "gravity", "", false)) model_.gravity = *g * length_;
  }

  // A force or torque component: a number, or an expression of t (same grammar as drivers).
  std::optional<TimeFunction> Component(const json& v, const std::string& ptr, double scale) {
    if (v.is_number()) return ReadFunction(rd_, json(v.dump()), ptr, scale);
    return ReadFunction(rd_, v, ptr, scale);
  }

  void ReadLoad(const json& o, const std::string& ptr) {
    auto type = rd_.String(o, "type", ptr);
    std::vector<std::string> allowed = {"name", "description", "type"}, required = {"name", "type"};
    const bool spring = type && *type == "spring";
    if (spring) {
      allowed.insert(allowed.end(), {"body1", "point1", "body2", "point2", "stiffness", "free_length", "damping", "preload"});
      required.insert(required.end(), {"body1", "point1", "body2", "point2", "stiffness"});
    } else if (type && (*type == "force" || *type == "torque")) {
      allowed.insert(allowed.end(), {"body", "components", "frame"});
      required.insert(required.end(), {"body", "components"});
      if (*type == "force") {
        allowed.push_back("point");
        required.push_back("point");
      }
    } else if (type) {
      rd_.Error(ptr + "/type", "unknown load type '" + Shorten(*type) + "'", "types: force, torque, spring");
      return;
    }
    if (!rd_.CheckObject(o, ptr, allowed, required, "a load") || !type) return;
    auto name = rd_.Name(o, ptr, "load");
    Load load;
    const bool ok = spring ? ReadSpring(o, ptr, &load) : ReadForceOrTorque(o, ptr, *type == "force", &load);
    if (!ok || !name) return;
    load.name = *name;
    model_.loads.push_back(load);
  }

  bool ReadForceOrTorque(const json& o, const std::string& ptr, bool force, Load* load) {
    load->kind = force ? LoadKind::Force : LoadKind::Torque;
    auto b = BodyRef(o, "body", ptr);
    bool ok = b.has_value();
    if (b && *b == kGround) {
      rd_.Error(ptr + "/body", "a load on ground does nothing", "name a moving body");
      ok = false;
    }
    if (force) {
      auto p = LengthVector(o, "point", ptr);
      if (p && ok) load->point1 = LocalPoint(*b, *p);
      ok = ok && p;
    }
    if (auto f = rd_.String(o, "frame", ptr)) {
      if (*f != "global" && *f != "body") {
        rd_.Error(ptr + "/frame", "unknown frame '" + Shorten(*f) + "'", "use \"global\" or \"body\"");
        ok = false;
      }
      load->in_body_axes = *f == "body";
    }
    const json& c = o.at("components");
    if (!c.is_array() || c.size() != 3) {
      rd_.Error(ptr + "/components", "'components' must be 3 numbers or expressions of t");
      return false;
    }
    const double scale = force ? model_.units.force_to_si() : model_.units.torque_to_si();
    for (int k = 0; k < 3; ++k) {
      auto f = Component(c[k], ptr + "/components/" + std::to_string(k), scale);
      if (f) load->components[k] = *f;
      else ok = false;
    }
    if (b) load->body1 = *b;
    return ok;
  }

  bool ReadSpring(const json& o, const std::string& ptr, Load* load) {
    load->kind = LoadKind::Spring;
    auto b1 = BodyRef(o, "body1", ptr), b2 = BodyRef(o, "body2", ptr);
    auto p1 = LengthVector(o, "point1", ptr), p2 = LengthVector(o, "point2", ptr);
    auto k = rd_.Number(o, "stiffness", ptr);
    if (!b1 || !b2 || !p1 || !p2 || !k) return false;
    if (*b1 == *b2) {
      rd_.Error(ptr + "/body2", "a spring between a body and itself does nothing", "name two different bodies");
      return false;
    }
    const double stiffness_to_si = model_.units.mass_to_si;  // force/length = mass/s²
    load->body1 = *b1;
    load->body2 = *b2;
    load->point1 = LocalPoint(*b1, *p1);
    load->point2 = LocalPoint(*b2, *p2);
    load->stiffness = *k * stiffness_to_si;
    load->free_length = (*p2 - *p1).norm();
    if (auto L0 = rd_.Number(o, "free_length", ptr)) load->free_length = *L0 * length_;
    if (auto c = rd_.Number(o, "damping", ptr)) load->damping = *c * stiffness_to_si;
    if (auto f = rd_.Number(o, "preload", ptr)) load->preload = *f * model_.units.force_to_si();
    if (!(load->free_length >= 0) || load->stiffness < 0 || load->damping < 0) {
      rd_.Error(ptr, "stiffness, damping and free length must not be negative", "check the signs");
      return false;
    }
    return true;
  }

  // A point 1000× farther from the middle of the mechanism than its typical
  // point (a typo such as 1e7 for 1e-3) silently inflates the characteristic
  // length and so every tolerance: warn, naming the point. Valid files only, so
  // model indices are the file's.
  void WarnFarPoints() {
    struct Place { Vec3 p; std::string ptr; };
    std::vector<Place> pts;
    for (size_t b = 0; b < model_.bodies.size(); ++b)
      pts.push_back({model_.bodies[b].position, "/bodies/" + std::to_string(b) + "/position"});
    for (size_t j = 0; j < model_.joints.size(); ++j) {
      const Joint& jt = model_.joints[j];
      auto [r, A] = Pose(jt.body1);
      pts.push_back({r + A * jt.frame1.origin, "/joints/" + std::to_string(j) + (jt.type == JointType::Distance ? "/point1" : "/origin")});
    }
    if (pts.size() < 4) return;
    Vec3 middle;
    for (int a = 0; a < 3; ++a) {
      std::vector<double> c;
      for (const auto& q : pts) c.push_back(q.p[a]);
      std::nth_element(c.begin(), c.begin() + c.size() / 2, c.end());
      middle[a] = c[c.size() / 2];
    }
    std::vector<double> d;
    for (const auto& q : pts) d.push_back((q.p - middle).norm());
    std::vector<double> sorted = d;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double typical = sorted[sorted.size() / 2];
    if (!(typical > 0)) return;
    for (size_t k = 0; k < pts.size(); ++k)
      if (d[k] > 1000 * typical)
        rd_.Warn(pts[k].ptr, "this point is " + FormatTime(d[k] / typical) + " times farther from the middle of the mechanism than its typical point",
                 "check the number and the unit: a far point sets the characteristic length and so every tolerance");
  }

  // A unit slip: `2*pi*t` in a file whose angles are degrees turns 6.28°, not a turn.
  void WarnRadiansInDegrees(const Driver& drv, const std::string& ptr, double swing) {
    const bool angle = drv.kind == DriverKind::JointRotation || drv.kind == DriverKind::BodyRotation;
    const std::string text = drv.function.Describe();
    if (!angle || model_.units.angle_name != "deg" || drv.function.is_table() || !(swing < 10)) return;
    if (text.find("pi") == std::string::npos) return;
    rd_.Warn(ptr, "driver '" + drv.name + "' uses pi but swings only " + FormatTime(swing) +
                      " deg over the analysis: the file's angles are degrees",
             "for a turn write 360*t (not 2*pi*t), or set \"units\": {\"angle\": \"rad\"}");
  }

  // A joint point far from every other joint point of both its bodies (1352 typed for
  // 135.2): over 5 times the median of the other joints' link lengths.
  void WarnStrayJointPoints() {
    std::vector<JointEnds> ends(model_.joints.size());
    for (size_t j = 0; j < model_.joints.size(); ++j) {
      const Joint& jt = model_.joints[j];
      for (int side = 0; side < 2; ++side) {
        const BodyIndex b = side ? jt.body2 : jt.body1;
        auto [r, A] = Pose(b);
        ends[j].body[side] = b;
        ends[j].point[side] = r + A * (side ? jt.frame2.origin : jt.frame1.origin);
      }
    }
    for (const StrayJointPoint& s : FindStrayJointPoints(ends))
      rd_.Warn("/joints/" + std::to_string(s.joint), "joint '" + model_.joints[s.joint].name + "' lies " +
                                                         FormatTime(s.nearest / s.typical) +
                                                         " times the other links' typical length from every other "
                                                         "joint of both its bodies",
               "check its coordinates (a slipped digit or unit)");
  }

  // A distance link 1000 times longer or shorter than the mechanism: a slipped unit or digit.
  void WarnOddLengths() {
    const double L = model_.characteristic_length;
    for (size_t j = 0; j < model_.joints.size(); ++j) {
      const Joint& jt = model_.joints[j];
      if (jt.type != JointType::Distance || !(L > 0)) continue;
      if (jt.length > 1000 * L || jt.length < L / 1000)
        rd_.Warn("/joints/" + std::to_string(j), "distance link '" + jt.name + "' is " + FormatTime(jt.length / length_) +
                                                     " " + model_.units.length_name + " long, " +
                                                     (jt.length > L ? "over 1000 times" : "under 1/1000 of") +
                                                     " the mechanism's size (" + FormatTime(L / length_) + ")",
                 "check the number and its unit");
    }
  }

  // Every driver function over the analysis span, on the table's own grid (at most
  // 2001 points, both ends included): where it or one of its four derivatives is
  // undefined or not finite, `run` could not go on, so the file is refused here.
  // A driver that turns more than 90° (or moves more than the mechanism's size)
  // between two rows gets a warning: the steps cannot follow it.
  void CheckDriverSpans() {
    if (!model_.analysis) return;
    const Analysis& an = *model_.analysis;
    const int points = std::min(an.steps, 2000);
    for (size_t d = 0; d < model_.drivers.size(); ++d) {
      const Driver& drv = model_.drivers[d];
      const std::string ptr = driver_pointers_[d] + "/function";
      const bool angle = drv.kind == DriverKind::JointRotation || drv.kind == DriverKind::BodyRotation;
      double worst_rate = 0, worst_t = an.start;
      double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
      for (int k = 0; k <= points; ++k) {
        const double t = k == points ? an.end : an.start + (an.end - an.start) * k / points;
        std::string why;
        try {
          const Jet j = drv.function.Eval(t);
          for (int o = 0; o <= kMaxOrder && why.empty(); ++o)
            if (!std::isfinite(j.c[o])) why = o == 0 ? "its value is not finite" : "its derivative of order " + std::to_string(o) + " is not finite";
          if (why.empty() && std::abs(j.c[1]) > worst_rate) { worst_rate = std::abs(j.c[1]); worst_t = t; }
          if (why.empty()) lowest = std::min(lowest, j.c[0]), highest = std::max(highest, j.c[0]);
        } catch (const std::exception& e) {
          why = e.what();
        }
        if (!why.empty()) {
          rd_.Error(ptr, "driver '" + drv.name + "' cannot be evaluated at t = " + FormatTime(t) + " s of the analysis span: " + why,
                    "change the function, or start or end the analysis where it is defined (and differentiable)");
          break;
        }
      }
      WarnRadiansInDegrees(drv, ptr, (highest - lowest) / angle_);
      const double per_step = worst_rate * (an.end - an.start) / an.steps;
      const double limit = angle ? M_PI / 2 : model_.characteristic_length;
      if (per_step > limit)
        rd_.Warn(ptr, "driver '" + drv.name + "' moves " + FormatTime(per_step / (angle ? angle_ : length_)) + " " +
                          (angle ? model_.units.angle_name : model_.units.length_name) + " between two rows near t = " +
                          FormatTime(worst_t) + " s",
                 "use more steps (analysis/steps) so that each step follows the motion");
    }
  }

 private:
  static std::string FormatTime(double t) {
    std::ostringstream o;
    o.precision(10);
    o << t;
    return o.str();
  }
  // A point in the file's length unit, in metres. Coordinates beyond 1e12 m
  // (a typo, or values whose squares overflow) are refused.
  std::optional<Vec3> LengthVector(const json& o, const std::string& key, const std::string& ptr) {
    auto v = rd_.Vector(o, key, ptr, false);
    if (!v) return v;
    *v *= length_;
    for (int k = 0; k < 3; ++k)
      if (std::abs((*v)[k]) > kMaxCoordinate) {
        rd_.Error(ptr + "/" + key + "/" + std::to_string(k),
                  "coordinate " + FormatTime((*v)[k] / length_) + " " + model_.units.length_name + " is beyond 1e12 m",
                  "check the number and the length unit (units/length)");
        return std::nullopt;
      }
    return v;
  }
  static constexpr double kMaxCoordinate = 1e12;  // m
  std::optional<BodyIndex> BodyRef(const json& o, const std::string& key, const std::string& ptr) {
    auto b = rd_.BodyRef(o, key, ptr, body_index_);
    if (b && *b == -2) return std::nullopt;
    return b;
  }
  std::pair<Vec3, Mat3> Pose(BodyIndex b) const {
    if (b == kGround) return {Vec3::Zero(), Mat3::Identity()};
    return {model_.bodies[b].position, CalcA(model_.bodies[b].euler)};
  }
  Vec3 LocalPoint(BodyIndex b, const Vec3& global) const {
    auto [r, A] = Pose(b);
    return Vec3(A.transpose() * (global - r));
  }
  JointFrame LocalFrame(BodyIndex b, const JointFrame& global) const {
    auto [r, A] = Pose(b);
    return ToLocal(global, r, A);
  }
  // A driver between body1 and body2 on one global frame, held in each body's axes.
  void SetDriverFrames(Driver* drv, BodyIndex body1, BodyIndex body2, const JointFrame& global) const {
    drv->body1 = body1;
    drv->body2 = body2;
    drv->frame1 = LocalFrame(body1, global);
    drv->frame2 = LocalFrame(body2, global);
  }

  // The geometry keys of a joint of known type, validated; adds the joint when
  // `name` is given (the joint's name, bodies and type were valid).
  void ReadJointGeometry(const json& jj, const std::string& ptr, const JointTypeInfo& info_ref, const std::string* name,
                         BodyIndex body1, BodyIndex body2) {
    const JointTypeInfo* info = &info_ref;
    bool ok = name != nullptr;
    Joint joint;
    joint.type = info->type;
    std::optional<Vec3> origin, axis, axis1, axis2, normal, p1, p2;
    if (jj.contains("origin")) {
      origin = LengthVector(jj, "origin", ptr);
      ok = ok && origin;
    }
    if (jj.contains("axis")) {
      axis = rd_.Vector(jj, "axis", ptr, true);
      ok = ok && axis;
    }
    if (jj.contains("axis1")) {
      axis1 = rd_.Vector(jj, "axis1", ptr, true);
      ok = ok && axis1;
    }
    if (jj.contains("axis2")) {
      axis2 = rd_.Vector(jj, "axis2", ptr, true);
      ok = ok && axis2;
    }
    if (jj.contains("normal")) {
      normal = rd_.Vector(jj, "normal", ptr, true);
      ok = ok && normal;
    }
    if (jj.contains("point1")) {
      p1 = LengthVector(jj, "point1", ptr);
      ok = ok && p1;
    }
    if (jj.contains("point2")) {
      p2 = LengthVector(jj, "point2", ptr);
      ok = ok && p2;
    }
    for (const auto& key : info->geometry)
      if (!jj.contains(key)) ok = false;
    if (info->type == JointType::Screw) {
      auto pitch = rd_.Number(jj, "pitch", ptr);
      if (pitch && *pitch == 0) {
        rd_.Error(ptr + "/pitch", "screw pitch is zero", "use a revolute joint, or give the lead per revolution");
        ok = false;
      } else if (pitch && std::abs(*pitch * length_) > kMaxCoordinate) {
        rd_.Error(ptr + "/pitch", "screw pitch is beyond 1e12 m per revolution", "check the number and the length unit");
        ok = false;
      } else if (pitch) {
        joint.pitch = *pitch * length_;
      } else {
        ok = false;
      }
    }
    if (axis1 && axis2) {
      const double c = axis1->normalized().dot(axis2->normalized());
      if (std::abs(c) > 1e-6) {
        rd_.Error(ptr + "/axis2",
                  "universal joint axes are not perpendicular (angle " +
                      std::to_string(std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI) + " deg)",
                  "make axis2 perpendicular to axis1 (the cross axes of a Hooke joint are at 90 deg)");
        ok = false;
      }
    }
    if (info->type == JointType::Distance && p1 && p2) {
      double len = (*p2 - *p1).norm();
      if (jj.contains("length")) {
        auto l = rd_.Number(jj, "length", ptr);
        if (!l)
          ok = false;
        else if (!(*l > 0)) {
          rd_.Error(ptr + "/length", "distance length must be positive", "give the link length");
          ok = false;
        } else
          len = *l * length_;
        if (len > kMaxCoordinate) {
          rd_.Error(ptr + "/length", "distance length is beyond 1e12 m", "check the number and the length unit");
          ok = false;
        }
      }
      if (ok && !(len > 0)) {
        rd_.Error(ptr + "/point2", "distance joint points coincide at the design pose and no length is given",
                  "a distance link of zero length is singular; use a spherical joint");
        ok = false;
      }
      joint.length = len;
    }
    if (!ok) return;
    joint.body1 = body1;
    joint.body2 = body2;
    AddJoint(*name, origin, axis, axis1, axis2, normal, p1, p2, &joint);
  }

  void AddJoint(const std::string& name, const std::optional<Vec3>& origin, const std::optional<Vec3>& axis,
                const std::optional<Vec3>& axis1, const std::optional<Vec3>& axis2, const std::optional<Vec3>& normal,
                const std::optional<Vec3>& p1, const std::optional<Vec3>& p2, Joint* joint_ptr) {
    Joint& joint = *joint_ptr;
    joint.name = name;
    JointFrame global;
    switch (joint.type) {
      case JointType::Revolute:
      case JointType::Prismatic:
      case JointType::Screw:
      case JointType::Cylindrical:
        global = MakeFrame(*origin, *axis);
        break;
      case JointType::Planar:
        global = MakeFrame(*origin, *normal);
        break;
      case JointType::Universal:
        global = MakeFrame(*origin, *axis1, *axis2);
        break;
      case JointType::Spherical:
        global.origin = *origin;
        break;
      case JointType::Distance:
        break;
    }
    if (joint.type == JointType::Distance) {
      joint.frame1.origin = LocalPoint(joint.body1, *p1);
      joint.frame2.origin = LocalPoint(joint.body2, *p2);
    } else {
      joint.frame1 = LocalFrame(joint.body1, global);
      joint.frame2 = LocalFrame(joint.body2, global);
      if (joint.type == JointType::Universal) {
        // body2 carries axis2 as its h (constraints.md §5, U row).
        joint.frame2 = LocalFrame(joint.body2, MakeFrame(*origin, *axis2, *axis1));
      }
    }
    joint_index_[joint.name] = static_cast<int>(model_.joints.size());
    model_.joints.push_back(joint);
  }

  bool DriverOnBody(const json& d, const std::string& ptr, Driver* drv_ptr) {
    Driver& drv = *drv_ptr;
    bool ok = true;
    drv.kind = DriverKind::BodyRotation;
    auto b = BodyRef(d, "body", ptr);
    auto axis = rd_.Vector(d, "axis", ptr, true);
    if (b && *b == kGround) {
      rd_.Error(ptr + "/body", "ground cannot be driven", "name a moving body");
      ok = false;
    } else if (b && axis) {
      // GRRD with ground as body i (constraints.md §3.6 seed note).
      const JointFrame global = MakeFrame(Vec3::Zero(), *axis);
      drv.body1 = kGround;
      drv.body2 = *b;
      drv.frame1 = global;
      auto [r, A] = Pose(*b);
      drv.frame2 = ToLocal(global, r, A);
    } else
      ok = false;
    return ok;
  }

  bool DriverOnJoint(const json& d, const std::string& ptr, const std::string& type, Driver* drv_ptr) {
    Driver& drv = *drv_ptr;
    const std::string* type_s = &type;
    bool ok = true;
    const bool rot = *type_s == "rotation";
    drv.kind = rot ? DriverKind::JointRotation : DriverKind::JointTranslation;
    auto jn = rd_.String(d, "joint", ptr);
    if (jn) {
      const auto it = joint_index_.find(*jn);
      if (it == joint_index_.end()) {
        std::vector<std::string> names;
        for (const auto& kv : joint_index_) names.push_back(kv.first);
        const std::string g = DidYouMean(*jn, names);
        rd_.Error(ptr + "/joint", "unknown joint '" + Shorten(*jn) + "'",
                  (g.empty() ? "" : "did you mean '" + g + "'? ") + "valid joints: " + Join(names));
        ok = false;
      } else if (it->second < 0) {
        ok = false;  // that joint already has an error
      } else {
        const Joint& j = model_.joints[it->second];
        const bool can =
            rot ? (j.type == JointType::Revolute || j.type == JointType::Cylindrical || j.type == JointType::Screw)
                : (j.type == JointType::Prismatic || j.type == JointType::Cylindrical || j.type == JointType::Screw);
        if (!can) {
          rd_.Error(
              ptr + "/joint",
              std::string("a ") + *type_s + " driver cannot drive " + JointTypeName(j.type) + " joint '" + j.name + "'",
              rot ? "rotation drivers act on revolute, cylindrical or screw joints"
                  : "translation drivers act on prismatic, cylindrical or screw joints");
          ok = false;
        } else {
          drv.joint = it->second;
          drv.body1 = j.body1;
          drv.body2 = j.body2;
          drv.frame1 = j.frame1;
          drv.frame2 = j.frame2;
        }
      }
    } else
      ok = false;
    return ok;
  }

  // {"type": "coordinate", "body", "point", "axis", "axis_body"?}: the body point's
  // coordinate along an axis fixed in ground (or in axis_body), 0 at the design pose
  // (the seed's dot-2 distance driver: Φ = a_iᵀ(P_j − P_i) − f(t), P_i the design
  // position of the point, fixed in the axis body).
  bool DriverOnCoordinate(const json& d, const std::string& ptr, Driver* drv) {
    drv->kind = DriverKind::JointTranslation;
    auto b = BodyRef(d, "body", ptr);
    auto p = LengthVector(d, "point", ptr);
    auto axis = rd_.Vector(d, "axis", ptr, true);
    std::optional<BodyIndex> ab = kGround;
    if (d.contains("axis_body")) ab = BodyRef(d, "axis_body", ptr);
    if (!b || !p || !axis || !ab) return false;
    if (*b == *ab) {
      rd_.Error(ptr + "/axis_body", "the axis is fixed in the driven body itself: its coordinate cannot change",
                "fix the axis in ground (omit axis_body) or in another body");
      return false;
    }
    const JointFrame global = MakeFrame(*p, *axis);
    SetDriverFrames(drv, *ab, *b, global);
    return true;
  }

  // {"type": "angle", "body1", "body2", "about", "vector"?}: the turn of body2's
  // `vector` (default: a direction across `about`) about `about` (fixed in body1),
  // relative to body1, 0 at the design pose — the general rotation driver (§3.9) on
  // two bodies that no revolute keeps aligned.
  bool DriverOnAngle(const json& d, const std::string& ptr, Driver* drv) {
    drv->kind = DriverKind::BodyRotation;
    drv->general_angle = true;
    auto b1 = BodyRef(d, "body1", ptr);
    auto b2 = BodyRef(d, "body2", ptr);
    auto about = rd_.Vector(d, "about", ptr, true);
    std::optional<Vec3> vector;
    if (d.contains("vector")) {
      vector = rd_.Vector(d, "vector", ptr, true);
      if (!vector) return false;
      if (about && vector->normalized().cross(about->normalized()).norm() < 1e-6) {
        rd_.Error(ptr + "/vector", "'vector' is parallel to 'about': its turn about it is undefined",
                  "give a direction across the axis");
        return false;
      }
    }
    if (!b1 || !b2 || !about) return false;
    if (*b1 == *b2) {
      rd_.Error(ptr + "/body2", "an angle driver between body '" + model_.BodyName(*b1) + "' and itself",
                "name two different bodies");
      return false;
    }
    const JointFrame global = vector ? MakeFrame(Vec3::Zero(), *about, *vector) : MakeFrame(Vec3::Zero(), *about);
    SetDriverFrames(drv, *b1, *b2, global);
    return true;
  }

  bool DriverBetweenPoints(const json& d, const std::string& ptr, Driver* drv_ptr) {
    Driver& drv = *drv_ptr;
    bool ok = true;
    drv.kind = DriverKind::Distance;
    auto b1 = BodyRef(d, "body1", ptr);
    auto b2 = BodyRef(d, "body2", ptr);
    auto p1 = LengthVector(d, "point1", ptr);
    auto p2 = LengthVector(d, "point2", ptr);
    if (b1 && b2 && *b1 == *b2) {
      rd_.Error(ptr + "/body2", "distance driver between body '" + model_.BodyName(*b1) + "' and itself",
                "name two different bodies");
      ok = false;
    } else if (b1 && b2 && p1 && p2) {
      drv.body1 = *b1;
      drv.body2 = *b2;
      drv.point1 = LocalPoint(*b1, *p1);
      drv.point2 = LocalPoint(*b2, *p2);
    } else
      ok = false;
    return ok;
  }

  Reader rd_;
  Model model_;
  const json* parameters_doc_ = nullptr;  // the "parameters" object while it is read
  std::map<std::string, BodyIndex> body_index_;
  std::map<std::string, int> joint_index_;
  std::set<std::string> driver_names_, output_names_;
  std::vector<std::string> driver_pointers_;  // per model driver, its place in the file
  double length_ = 1, angle_ = 1;
};

// Parses the text as JSON; on failure reports where (line and column) and why.
// Follows the parse to name duplicate keys by their JSON pointer (JSON allows
// them; the last one silently wins, which is rarely what the author meant).
class DuplicateKeyTracker {
 public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: frames_.push_back(Frame{true, {}, {}, 0}); break;
      case json::parse_event_t::array_start: frames_.push_back(Frame{false, {}, {}, 0}); break;
      case json::parse_event_t::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second) duplicates_.push_back(Pointer());
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        NextElement();
        break;
      case json::parse_event_t::value: NextElement(); break;
    }
    return true;
  }
  const std::vector<std::string>& duplicates() const { return duplicates_; }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string key;
    size_t index = 0;
  };
  void NextElement() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
  }
  std::string Pointer() const {
    std::string p;
    for (const Frame& f : frames_) p += "/" + (f.object ? EscapeToken(f.key) : std::to_string(f.index));
    return p;
  }
  std::vector<Frame> frames_;
  std::vector<std::string> duplicates_;
};

bool ParseJson(const std::string& text, Reader& rd, json* doc_out) {
  json& doc = *doc_out;
  try {
    DuplicateKeyTracker tracker;
    doc = json::parse(text, std::ref(tracker));
    for (const auto& ptr : tracker.duplicates())
      rd.Warn(ptr, "the key appears more than once in its object; the last value is used",
              "remove the other occurrences");
  } catch (const json::parse_error& e) {
    // Convert the byte offset into line and column.
    size_t line = 1, col = 1;
    const size_t end = std::min<size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    for (size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    std::string what = e.what();
    const auto pos = what.find("syntax error");
    if (pos != std::string::npos) what = what.substr(pos);
    rd.Error("", "JSON syntax error at line " + std::to_string(line) + ", column " + std::to_string(col) + ": " + what,
             text.empty() ? "the file is empty; start from a file in mechanisms/" : "fix the JSON syntax");
    return false;
  } catch (const json::out_of_range& e) {
    // nlohmann reports overflowing numbers (1e999) without a position: find the token.
    std::string what = e.what(), where;
    const auto q1 = what.find('\''), q2 = what.rfind('\'');
    if (q1 != std::string::npos && q2 > q1) {
      const std::string token = what.substr(q1 + 1, q2 - q1 - 1);
      const size_t at = text.find(token);
      if (at != std::string::npos) {
        size_t line = 1, col = 1;
        for (size_t i = 0; i < at; ++i) {
          if (text[i] == '\n') {
            ++line;
            col = 1;
          } else {
            ++col;
          }
        }
        where = " at line " + std::to_string(line) + ", column " + std::to_string(col);
      }
      what = "number '" + Shorten(token) + "' is too large for a double" + where;
    }
    rd.Error("", what, "use a finite value (|x| < 1.8e308)");
    return false;
  } catch (const std::exception& e) {
    rd.Error("", std::string("cannot parse the file as JSON: ") + e.what());
    return false;
  }

  return true;
}

}  // namespace

LoadResult LoadMechanismText(const std::string& text, const std::string& source_name,
                             const ParameterOverrides& overrides) {
  LoadResult result;
  SpecReader spec(&result);
  json doc;
  if (!ParseJson(text, spec.reader(), &doc) || !spec.ReadHeader(doc)) return result;
  spec.model().source = source_name;
  spec.model().document = std::make_shared<const std::string>(text);
  spec.ReadParameters(doc, overrides);
  spec.ReadUnits(doc);
  spec.ReadArray(doc, "bodies", "body", [&](const json& e, const std::string& p) { spec.ReadBody(e, p); });
  spec.ReadArray(doc, "joints", "joint", [&](const json& e, const std::string& p) { spec.ReadJoint(e, p); });
  spec.ReadArray(doc, "drivers", "driver", [&](const json& e, const std::string& p) { spec.ReadDriver(e, p); });
  spec.ReadAnalysis(doc);
  spec.ReadArray(doc, "outputs", "output", [&](const json& e, const std::string& p) { spec.ReadOutput(e, p); });
  spec.ReadExpect(doc);
  spec.ReadGravity(doc);
  spec.ReadArray(doc, "loads", "load", [&](const json& e, const std::string& p) { spec.ReadLoad(e, p); });
  if (!result.errors.empty()) return result;
  Model& model = spec.model();
  model.characteristic_length = CharacteristicLength(model);
  spec.WarnFarPoints();
  spec.WarnOddLengths();
  spec.WarnStrayJointPoints();
  spec.CheckDriverSpans();
  if (!result.errors.empty()) return result;
  result.model = std::move(model);
  return result;
}

namespace {

// Reads all of `fd` up to the size limit. A stream that stays silent longer
// than `timeout_ms` (a FIFO with no writer, a terminal) is given up on.
bool ReadStream(int fd, std::string* text, std::string* why, int timeout_ms) {
  char buf[1 << 16];
  for (;;) {
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, timeout_ms);
    if (ready == 0) { *why = "nothing arrived for " + std::to_string(timeout_ms / 1000) + " s"; return false; }
    if (ready < 0 && errno == EINTR) continue;
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) { *why = std::strerror(errno); return false; }
    if (n == 0) return true;
    if (text->size() + static_cast<size_t>(n) > kMaxFileBytes) { *why = "larger than 256 MiB"; return false; }
    text->append(buf, static_cast<size_t>(n));
  }
}

}  // namespace

LoadResult WithParameters(const Model& model, const ParameterOverrides& overrides) {
  if (!model.document) {
    LoadResult result;
    result.errors.push_back({"", "this model was not compiled from a file", "load it with LoadMechanismFile"});
    return result;
  }
  ParameterOverrides merged;
  for (const auto& p : model.parameters)
    if (p.overridden) merged[p.name] = p.value;
  for (const auto& kv : overrides) merged[kv.first] = kv.second;
  return LoadMechanismText(*model.document, model.source, merged);
}

LoadResult LoadMechanismFile(const std::string& path, const ParameterOverrides& overrides) {
  LoadResult result;
  auto fail = [&](const std::string& msg, const std::string& fix) {
    result.errors.push_back({"", msg, fix});
    return result;
  };
  const bool standard_input = path == "-";
  struct stat st {};
  if (!standard_input && ::stat(path.c_str(), &st) != 0)
    return fail("cannot open '" + path + "': " + std::strerror(errno), "check the path and permissions");
  if (!standard_input && S_ISDIR(st.st_mode))
    return fail("'" + path + "' is a directory", "give a mechanism JSON file inside it");
  if (!standard_input && (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) || S_ISSOCK(st.st_mode)))
    return fail("'" + path + "' is a device, not a file", "give a mechanism JSON file");
  if (!standard_input && S_ISREG(st.st_mode) && static_cast<std::size_t>(st.st_size) > kMaxFileBytes)
    return fail("file is larger than 256 MiB", "a mechanism file is a few kilobytes; check the path");
  // Pipes, FIFOs and the standard input are read as streams, with a time-out.
  const int fd = standard_input ? 0 : ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return fail("cannot open '" + path + "': " + std::strerror(errno), "check the path and permissions");
  if (!standard_input) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  std::string text, why;
  const bool ok = ReadStream(fd, &text, &why, 10000);
  if (!standard_input) ::close(fd);
  if (!ok) return fail("cannot read '" + path + "': " + why, "give a complete mechanism JSON file");
  return LoadMechanismText(text, standard_input ? "<stdin>" : path, overrides);
}

}  // namespace mechkin
