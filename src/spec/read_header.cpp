// The top-level sections: header, parameters, units, analysis, expect, gravity.
#include <algorithm>
#include <cctype>
#include <cmath>

#include "spec/json_reader.hpp"

namespace mechkin::spec_reader {

namespace {

// Identifiers reserved by the expression grammar (model/expression.cpp keeps the
// authoritative list; compile refuses a parameter named like one of them).
bool IsIdentifier(const std::string& name) {
  return !name.empty() && name.size() <= 64 && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
         std::all_of(name.begin(), name.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

std::optional<double> PlainNumber(JsonReader& rd, const json& obj, const std::string& key, const std::string& ptr) {
  if (!obj.contains(key)) return std::nullopt;
  if (!obj.at(key).is_number()) {
    rd.Error(ptr + "/" + key, "'" + key + "' must be a number, not " + spec_reader::TypeName(obj.at(key)));
    return std::nullopt;
  }
  const double d = obj.at(key).get<double>();
  if (!std::isfinite(d)) {
    rd.Error(ptr + "/" + key, "'" + key + "' is not a finite number", "use a finite value");
    return std::nullopt;
  }
  return d;
}

// One declaration: a number or expression, or {"value", "tolerance", "min", "max", "description"}.
void ReadParameter(JsonReader& rd, const std::string& name, const json& v, MechanismSpec* spec) {
  const std::string ptr = "/parameters/" + EscapeToken(name);
  ParameterSpec param;
  param.name = name;
  if (!IsIdentifier(name)) {
    rd.Error(ptr, "invalid parameter name '" + Shorten(name) + "'",
             "use 1-64 letters, digits or '_', starting with a letter or '_', other than t, pi and the "
             "function names");
    return;
  }
  if (!v.is_object()) {
    param.value = rd.ScalarValue(v, ptr, "parameter '" + name + "'");
    spec->parameters.push_back(param);
    return;
  }
  rd.CheckObject(v, ptr, {"value", "tolerance", "min", "max", "description"}, {"value"}, "a parameter");
  param.tolerance = PlainNumber(rd, v, "tolerance", ptr);
  param.min = PlainNumber(rd, v, "min", ptr);
  param.max = PlainNumber(rd, v, "max", ptr);
  if (param.tolerance && *param.tolerance < 0)
    rd.Error(ptr + "/tolerance", "tolerance must not be negative", "give the ± band as a positive number");
  if (param.min && param.max && !(*param.min < *param.max))
    rd.Error(ptr + "/max", "'max' must be greater than 'min'", "swap them or widen the range");
  if (v.contains("value")) param.value = rd.ScalarValue(v.at("value"), ptr + "/value", "parameter '" + name + "'");
  spec->parameters.push_back(param);
}

void ReadBranch(JsonReader& rd, const json& b, AnalysisSpec* an) {
  const std::string ptr = "/analysis/branch";
  if (!rd.CheckObject(b, ptr, {"joints", "flip"}, {}, "'branch'")) return;
  if (!b.contains("joints") && !b.contains("flip")) {
    rd.Error(ptr + "/joints", "missing key 'joints' in 'branch'", "add it");  // (or "flip")
    return;
  }
  BranchSpec branch;
  if (b.contains("joints")) {
    const json& joints = b.at("joints");
    if (!joints.is_object()) {
      rd.Error(ptr + "/joints", "'joints' must be an object {\"joint name\": coordinate}, not " + TypeName(joints));
      return;
    }
    for (const auto& item : joints.items()) {
      const std::string p = ptr + "/joints/" + EscapeToken(item.key());
      branch.joints.emplace_back(item.key(), rd.ScalarValue(item.value(), p, "the hint"));
    }
  }
  if (b.contains("flip")) {
    const json& flip = b.at("flip");
    if (!flip.is_array()) {
      rd.Error(ptr + "/flip", "'flip' must be an array of joint names, not " + TypeName(flip),
               "e.g. \"flip\": [\"rocker_bearing\"]");
      return;
    }
    for (size_t k = 0; k < flip.size(); ++k) {
      const std::string p = ptr + "/flip/" + std::to_string(k);
      if (!flip[k].is_string()) {
        rd.Error(p, "a joint name must be a string, not " + TypeName(flip[k]), "name a revolute or prismatic joint");
        continue;
      }
      branch.flip.emplace_back(flip[k].get<std::string>(), p);
    }
  }
  an->branch = std::move(branch);
}

}  // namespace

bool ReadHeader(JsonReader& rd, const json& doc, MechanismSpec* spec) {
  rd.diagnostics().SetPlace(Section::Header);
  if (!rd.CheckObject(doc, "",
                      {"$schema", "mechkin", "name", "description", "units", "parameters", "bodies", "joints",
                       "couplers", "drivers", "analysis", "outputs", "expect", "gravity", "loads", "ground", "view"},
                      {"mechkin", "bodies", "joints"}, "the mechanism file"))
    return false;
  rd.String(doc, "$schema", "");  // names the JSON Schema for editors; otherwise ignored
  spec->version = rd.Integer(doc, "mechkin", "");
  if (auto s = rd.String(doc, "name", "")) spec->name = *s;
  if (auto s = rd.String(doc, "description", "")) spec->description = *s;
  return true;
}

// A JSON object's keys come in sorted order (nlohmann::json keeps a std::map).
void ReadParameters(JsonReader& rd, const json& doc, MechanismSpec* spec) {
  rd.diagnostics().SetPlace(Section::Parameters);
  if (!doc.contains("parameters")) return;
  const json& params = doc.at("parameters");
  if (!params.is_object()) {
    rd.Error("/parameters", "'parameters' must be an object {\"name\": value, ...}, not " + TypeName(params));
    return;
  }
  for (const auto& item : params.items()) ReadParameter(rd, item.key(), item.value(), spec);
}

void ReadUnits(JsonReader& rd, const json& doc, MechanismSpec* spec) {
  rd.diagnostics().SetPlace(Section::Units);
  if (!doc.contains("units")) return;
  const json& u = doc.at("units");
  if (!rd.CheckObject(u, "/units", {"length", "angle", "mass", "force", "torque"}, {}, "'units'")) return;
  UnitsSpec units;
  units.mass = rd.String(u, "mass", "/units");
  units.length = rd.String(u, "length", "/units");
  units.angle = rd.String(u, "angle", "/units");
  units.force = rd.String(u, "force", "/units");
  units.torque = rd.String(u, "torque", "/units");
  spec->units = units;
}

void ReadAnalysis(JsonReader& rd, const json& doc, MechanismSpec* spec) {
  rd.diagnostics().SetPlace(Section::Analysis);
  if (!doc.contains("analysis")) return;
  const json& a = doc.at("analysis");
  if (!rd.CheckObject(a, "/analysis", {"start", "end", "steps", "branch"}, {"start", "end", "steps"}, "'analysis'"))
    return;
  AnalysisSpec an;
  an.start = rd.Number(a, "start", "/analysis");
  an.end = rd.Number(a, "end", "/analysis");
  an.steps = rd.Integer(a, "steps", "/analysis");
  if (a.contains("branch")) ReadBranch(rd, a.at("branch"), &an);
  spec->analysis = std::move(an);
}

namespace {

// "min": {"transmission": 40}: per output name, a bound on its column over the run.
void ReadBounds(JsonReader& rd, const json& e, const char* key, std::vector<std::pair<std::string, Scalar>>* out) {
  if (!e.contains(key)) return;
  const std::string ptr = std::string("/expect/") + key;
  const json& b = e.at(key);
  if (!b.is_object()) {
    rd.Error(ptr, std::string("'") + key + "' must be an object of output names and numbers",
             std::string("write \"") + key + "\": {\"transmission\": 40}");
    return;
  }
  for (auto it = b.begin(); it != b.end(); ++it)
    if (auto v = rd.Number(b, it.key(), ptr)) out->emplace_back(it.key(), *v);
}

}  // namespace

void ReadExpect(JsonReader& rd, const json& doc, MechanismSpec* spec) {
  rd.diagnostics().SetPlace(Section::Expect);
  if (!doc.contains("expect")) return;
  const json& e = doc.at("expect");
  if (!rd.CheckObject(e, "/expect", {"grubler", "mobility", "redundant", "idle", "driven", "min_clearance", "min", "max"},
                      {},
                      "'expect'"))
    return;
  ExpectSpec ex;
  ex.grubler = rd.Integer(e, "grubler", "/expect");
  ex.mobility = rd.Integer(e, "mobility", "/expect");
  ex.redundant = rd.Integer(e, "redundant", "/expect");
  ex.idle = rd.Integer(e, "idle", "/expect");
  ex.min_clearance = rd.Number(e, "min_clearance", "/expect");
  ReadBounds(rd, e, "min", &ex.min);
  ReadBounds(rd, e, "max", &ex.max);
  if (auto s = rd.String(e, "driven", "/expect")) {
    if (*s == "full" || *s == "under" || *s == "over")
      ex.driven = *s;
    else
      rd.Error("/expect/driven", "unknown driving status '" + Shorten(*s) + "'", "use \"full\", \"under\" or \"over\"");
  }
  spec->expect = ex;
}

void ReadGravity(JsonReader& rd, const json& doc, MechanismSpec* spec) {
  rd.diagnostics().SetPlace(Section::Gravity);
  if (doc.contains("gravity")) spec->gravity = rd.Vector(doc, "gravity", "");
}

namespace {

// "plots": [["camber", "toe"], ["wheel_centre.z"]]: panels of column names (checked
// against the table's columns by `view`, which knows them).
void ReadPlots(JsonReader& rd, const json& plots, ViewSpec* view) {
  const std::string fix = "write a list of panels, each a list of column names: [[\"camber\", \"toe\"], [\"x\"]]";
  if (!plots.is_array() || plots.empty()) {
    rd.Error("/view/plots", "'plots' must be a non-empty array of panels", fix);
    return;
  }
  for (size_t p = 0; p < plots.size(); ++p) {
    const std::string ptr = "/view/plots/" + std::to_string(p);
    if (!plots[p].is_array() || plots[p].empty()) {
      rd.Error(ptr, "a panel must be a non-empty array of column names, not " + TypeName(plots[p]), fix);
      continue;
    }
    std::vector<std::string> panel;
    for (size_t c = 0; c < plots[p].size(); ++c) {
      if (plots[p][c].is_string())
        panel.push_back(plots[p][c].get<std::string>());
      else
        rd.Error(ptr + "/" + std::to_string(c), "a column name must be a string, not " + TypeName(plots[p][c]), fix);
    }
    view->plots.push_back(std::move(panel));
  }
}

}  // namespace

void ReadView(JsonReader& rd, const json& doc, MechanismSpec* spec) {
  rd.diagnostics().SetPlace(Section::View);
  if (!doc.contains("view")) return;
  const json& v = doc.at("view");
  if (!rd.CheckObject(v, "/view", {"up", "plots", "paused"}, {}, "'view'")) return;
  ViewSpec view;
  if (auto up = rd.String(v, "up", "/view")) {
    if (*up == "x" || *up == "y" || *up == "z")
      view.up = *up;
    else
      rd.Error("/view/up", "unknown up axis '" + Shorten(*up) + "'", "use \"x\", \"y\" or \"z\"");
  }
  if (v.contains("plots")) ReadPlots(rd, v.at("plots"), &view);
  if (v.contains("paused")) {
    if (v.at("paused").is_boolean())
      view.paused = v.at("paused").get<bool>();
    else
      rd.Error("/view/paused", "'paused' must be true or false, not " + TypeName(v.at("paused")));
  }
  spec->view = std::move(view);
}

}  // namespace mechkin::spec_reader
