#include "spec/json_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace mechkin {

Vector3Spec Vector3Spec::Of(double x, double y, double z, std::string key, std::string pointer) {
  Vector3Spec v;
  v.c = {Scalar::Of(x, pointer + "/0"), Scalar::Of(y, pointer + "/1"), Scalar::Of(z, pointer + "/2")};
  v.key = std::move(key);
  v.pointer = std::move(pointer);
  return v;
}

namespace spec_reader {

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

bool JsonReader::CheckObject(const json& obj, const std::string& ptr, const std::vector<std::string>& allowed,
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

std::optional<Scalar> JsonReader::Number(const json& obj, const std::string& key, const std::string& ptr) {
  if (!obj.contains(key)) return std::nullopt;
  return ScalarValue(obj.at(key), ptr + "/" + key, "'" + key + "'");
}

// Type problems become Invalid scalars, reported when compiled (in the file's order).
Scalar JsonReader::ScalarValue(const json& v, const std::string& p, const std::string& what) {
  if (v.is_string()) return Scalar::Expr(v.get<std::string>(), p);
  Scalar s;
  s.pointer = p;
  if (!v.is_number()) {
    s.kind = Scalar::Kind::Invalid;
    s.text = what + " must be a number or an expression string, not " + TypeName(v);
    return s;
  }
  s.number = v.get<double>();
  if (!std::isfinite(s.number)) {
    s.kind = Scalar::Kind::Invalid;
    s.text = what + " is not a finite number";
    s.fix = "use a finite value";
  }
  return s;
}

std::optional<Scalar> JsonReader::Integer(const json& obj, const std::string& key, const std::string& ptr) {
  if (!obj.contains(key)) return std::nullopt;
  const json& v = obj.at(key);
  const std::string p = ptr + "/" + key;
  if (v.is_number_float() || v.is_string()) return ScalarValue(v, p, "'" + key + "'");
  Scalar s;
  s.pointer = p;
  s.kind = Scalar::Kind::Invalid;
  if (v.is_number_integer() || v.is_number_unsigned()) {
    const bool out_of_range = v.is_number_unsigned()
                                  ? v.get<unsigned long long>() > 1000000000ull
                                  : (v.get<long long>() > 1000000000ll || v.get<long long>() < -1000000000ll);
    if (!out_of_range) return Scalar::Of(static_cast<double>(v.get<long long>()), p);
    s.text = "'" + key + "' is out of range";
    s.fix = "use an integer of magnitude below 1e9";
    return s;
  }
  s.text = "'" + key + "' must be an integer, not " + TypeName(v);
  return s;
}

std::optional<std::string> JsonReader::String(const json& obj, const std::string& key, const std::string& ptr) {
  if (!obj.contains(key)) return std::nullopt;
  const json& v = obj.at(key);
  if (!v.is_string()) {
    Error(ptr + "/" + key, "'" + key + "' must be a string, not " + TypeName(v));
    return std::nullopt;
  }
  return v.get<std::string>();
}

std::optional<std::string> JsonReader::Name(const json& obj, const std::string& ptr, const std::string& what) {
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

std::optional<Vector3Spec> JsonReader::Vector(const json& obj, const std::string& key, const std::string& ptr) {
  if (!obj.contains(key)) return std::nullopt;
  return VectorValue(obj.at(key), ptr + "/" + key, key);
}

Vector3Spec JsonReader::VectorValue(const json& v, const std::string& p, const std::string& key) {
  Vector3Spec out;
  out.key = key;
  out.pointer = p;
  if (!v.is_array() || v.size() != 3) {
    out.error = "'" + key + "' must be an array of 3 numbers [x, y, z], not " +
                (v.is_array() ? "an array of " + std::to_string(v.size()) : TypeName(v));
    return out;
  }
  for (int k = 0; k < 3; ++k) out.c[k] = ScalarValue(v[k], p + "/" + std::to_string(k), "component");
  return out;
}

std::optional<std::array<Vector3Spec, 3>> JsonReader::Matrix(const json& obj, const std::string& key,
                                                             const std::string& ptr, std::string* error) {
  if (!obj.contains(key)) return std::nullopt;
  const json& m = obj.at(key);
  if (!m.is_array() || m.size() != 3) {
    *error = "'" + key + "' must be 3 rows of 3 numbers";
    return std::nullopt;
  }
  std::array<Vector3Spec, 3> rows;
  for (int i = 0; i < 3; ++i) rows[i] = VectorValue(m[i], ptr + "/" + key + "/" + std::to_string(i), "row");
  return rows;
}

}  // namespace spec_reader
}  // namespace mechkin
