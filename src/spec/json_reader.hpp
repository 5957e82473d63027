// Internal to src/spec: the JSON walking helpers of the section readers.
// Structural problems (unknown or missing keys, wrong JSON types, bad names) are
// reported here; values that may be parameter expressions are kept for compile.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "spec/diagnostic.hpp"
#include "spec/spec.hpp"

namespace mechkin::spec_reader {

using nlohmann::json;

/// "a number", "an object", ... for messages.
std::string TypeName(const json& j);

class JsonReader {
 public:
  explicit JsonReader(DiagnosticLog* out) : out_(out) {}
  DiagnosticLog& diagnostics() { return *out_; }
  /// The folder files named by the mechanism file are read from (mesh shapes):
  /// the mechanism file's own, "" (the working directory) for text without a path.
  const std::string& folder() const { return folder_; }
  void set_folder(std::string folder) { folder_ = std::move(folder); }

  void Error(const std::string& ptr, const std::string& msg, const std::string& fix = "") { out_->Error(ptr, msg, fix); }
  void Warn(const std::string& ptr, const std::string& msg, const std::string& fix = "") { out_->Warn(ptr, msg, fix); }

  /// Reports unknown and missing keys of `obj`. Returns false when obj is not an object.
  bool CheckObject(const json& obj, const std::string& ptr, const std::vector<std::string>& allowed,
                   const std::vector<std::string>& required, const std::string& what);

  /// obj[key] as a Scalar (a number or an expression string), nullopt when absent.
  std::optional<Scalar> Number(const json& obj, const std::string& key, const std::string& ptr);
  /// A number or expression string at pointer p; `what` names it in messages.
  Scalar ScalarValue(const json& v, const std::string& p, const std::string& what);
  /// obj[key] as an integer Scalar (a JSON integer, or a number/expression checked at compile).
  std::optional<Scalar> Integer(const json& obj, const std::string& key, const std::string& ptr);
  std::optional<std::string> String(const json& obj, const std::string& key, const std::string& ptr);
  /// obj["name"], usable in table column headers.
  std::optional<std::string> Name(const json& obj, const std::string& ptr, const std::string& what);
  std::optional<Vector3Spec> Vector(const json& obj, const std::string& key, const std::string& ptr);
  Vector3Spec VectorValue(const json& v, const std::string& p, const std::string& key);
  /// obj[key] as 3 rows of 3 numbers; the shape error, if any, goes to *error.
  std::optional<std::array<Vector3Spec, 3>> Matrix(const json& obj, const std::string& key, const std::string& ptr,
                                                   std::string* error);

 private:
  DiagnosticLog* out_;
  std::string folder_;
};

/// Every element of the array doc[key] through `read(element, pointer, index)`.
template <typename ReadElement>
void ReadArray(JsonReader& rd, const json& doc, const std::string& key, const std::string& what, Section section,
               ReadElement read) {
  rd.diagnostics().SetPlace(section);
  if (!doc.contains(key)) return;
  const json& items = doc.at(key);
  if (!items.is_array()) {
    rd.Error("/" + key, "'" + key + "' must be an array of " + what + " objects, not " + TypeName(items));
    return;
  }
  for (size_t k = 0; k < items.size(); ++k) {
    rd.diagnostics().SetPlace(section, static_cast<int>(k));
    read(items[k], "/" + key + "/" + std::to_string(k));
  }
}

// The section readers (one file each).
bool ReadHeader(JsonReader& rd, const json& doc, MechanismSpec* spec);
void ReadParameters(JsonReader& rd, const json& doc, MechanismSpec* spec);
void ReadUnits(JsonReader& rd, const json& doc, MechanismSpec* spec);
void ReadAnalysis(JsonReader& rd, const json& doc, MechanismSpec* spec);
void ReadExpect(JsonReader& rd, const json& doc, MechanismSpec* spec);
void ReadGravity(JsonReader& rd, const json& doc, MechanismSpec* spec);
void ReadView(JsonReader& rd, const json& doc, MechanismSpec* spec);
void ReadBody(JsonReader& rd, const json& b, const std::string& ptr, bool by_markers, MechanismSpec* spec);
/// Some joint of the document names "marker1" or "marker2".
bool JointsUseMarkers(const json& doc);
void ReadJoint(JsonReader& rd, const json& j, const std::string& ptr, MechanismSpec* spec);
void ReadDriver(JsonReader& rd, const json& d, const std::string& ptr, MechanismSpec* spec);
void ReadCoupler(JsonReader& rd, const json& c, const std::string& ptr, MechanismSpec* spec);
void ReadOutput(JsonReader& rd, const json& o, const std::string& ptr, MechanismSpec* spec);
void ReadGround(JsonReader& rd, const json& doc, MechanismSpec* spec);
/// A "shape" object (nullopt: reported) and a "shapes" array of them (read_shapes.cpp).
std::optional<ShapeSpec> ReadShape(JsonReader& rd, const json& o, const std::string& ptr);
std::vector<ShapeSpec> ReadShapeList(JsonReader& rd, const json& shapes, const std::string& ptr);
std::vector<MarkerSpec> ReadMarkers(JsonReader& rd, const json& markers, const std::string& ptr);
void ReadLoad(JsonReader& rd, const json& o, const std::string& ptr, MechanismSpec* spec);
/// A driver function: an expression string or {"table": [[t, v], ...]} (Invalid: reported).
FunctionSpec ReadFunction(JsonReader& rd, const json& f, const std::string& ptr);
/// Parses the text; reports syntax errors (line, column) and duplicate keys.
bool ParseJson(const std::string& text, JsonReader& rd, json* doc);

}  // namespace mechkin::spec_reader
