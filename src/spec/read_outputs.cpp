// "outputs", "loads" and the functions of time of drivers and loads.
#include <algorithm>
#include <cmath>

#include "spec/json_reader.hpp"

namespace mechkin::spec_reader {

namespace {

using StringField = std::pair<const char*, std::optional<std::string>*>;
using VectorField = std::pair<const char*, std::optional<Vector3Spec>*>;

// The keys an output of `type` takes besides name, description, type.
bool OutputKeys(JsonReader& rd, const std::optional<std::string>& type, const std::string& ptr,
                std::vector<std::string>* allowed, std::vector<std::string>* required) {
  auto add = [&](std::initializer_list<const char*> keys, std::initializer_list<const char*> needed) {
    allowed->insert(allowed->end(), keys.begin(), keys.end());
    required->insert(required->end(), needed.begin(), needed.end());
    return true;
  };
  if (type && *type == "point") return add({"body", "point", "frame", "marker"}, {"body"});
  if (type && *type == "velocity_ratio") return add({"output", "input"}, {"output", "input"});
  if (type && *type == "orientation") return add({"body", "relative_to", "sequence"}, {"body", "sequence"});
  if (type && *type == "joint") return add({"joint", "sequence"}, {"joint"});
  if (type && *type == "distance")
    return add({"body1", "point1", "body2", "point2"}, {"body1", "point1", "body2", "point2"});
  if (type && *type == "angle")
    return add({"body1", "vector1", "body2", "vector2", "about"}, {"body1", "vector1", "body2", "vector2"});
  if (type && *type == "clearance") return add({"body1", "body2"}, {"body1", "body2"});
  if (type && *type == "expression") return add({"value"}, {"value"});
  if (type && *type == "reduction") return add({"of", "reduce", "t", "targets"}, {"of", "reduce"});
  if (type) {
    const std::vector<std::string> types = {"point",       "joint",      "distance",  "angle",
                                            "velocity_ratio", "orientation", "clearance", "expression",
                                            "reduction"};
    const std::string g = DidYouMean(*type, types);
    rd.Error(ptr + "/type", "unknown output type '" + Shorten(*type) + "'",
             (g.empty() ? "" : "did you mean '" + g + "'? ") + "types: " + Join(types));
  }
  allowed->insert(allowed->end(), {"body", "point", "joint", "body1", "point1", "body2", "point2", "vector1",
                                   "vector2", "about", "frame", "output", "input", "relative_to", "sequence",
                                   "value", "of", "reduce", "t", "targets"});
  return false;
}

// A JSON number (an error at ptr otherwise).
bool PlainNumber(JsonReader& rd, const json& v, const std::string& ptr, double* out) {
  if (!v.is_number()) {
    rd.Error(ptr, "a target must be a plain number, not " + TypeName(v));
    return false;
  }
  *out = v.get<double>();
  return true;
}

// "targets": {"t": [t_i], "values": [v_i] or [[v_i1, …]]} of an "sse" reduction
// (docs/format.md "Targets"): the counts are checked against "of" at compile.
std::optional<OutputSpec::Targets> ReadTargets(JsonReader& rd, const json& o, const std::string& ptr) {
  if (!rd.CheckObject(o, ptr, {"t", "values"}, {"t", "values"}, "targets")) return std::nullopt;
  const json &t = o.at("t"), &values = o.at("values");
  if (!t.is_array() || t.empty()) {
    rd.Error(ptr + "/t", "'t' must be a non-empty array of times (s), not " + TypeName(t));
    return std::nullopt;
  }
  if (!values.is_array()) {
    rd.Error(ptr + "/values", "'values' must be an array (one entry per time), not " + TypeName(values));
    return std::nullopt;
  }
  OutputSpec::Targets out;
  bool ok = true;
  for (size_t i = 0; i < t.size(); ++i) {
    double v = 0;
    ok = PlainNumber(rd, t[i], ptr + "/t/" + std::to_string(i), &v) && ok;
    out.t.push_back(v);
  }
  for (size_t i = 0; i < values.size(); ++i) {
    const std::string p = ptr + "/values/" + std::to_string(i);
    const json& row = values[i];
    std::vector<double> r;
    if (row.is_array()) {
      for (size_t k = 0; k < row.size(); ++k) {
        double v = 0;
        ok = PlainNumber(rd, row[k], p + "/" + std::to_string(k), &v) && ok;
        r.push_back(v);
      }
    } else {
      double v = 0;
      ok = PlainNumber(rd, row, p, &v) && ok;
      r.push_back(v);
    }
    out.values.push_back(std::move(r));
  }
  if (!ok) return std::nullopt;
  return out;
}

// "of" of a reduction: a column's name, or (for "sse") an array of them.
void ReadOf(JsonReader& rd, const json& o, const std::string& ptr, OutputSpec* out) {
  const json& of = o.at("of");
  if (!of.is_array()) {
    out->of = rd.String(o, "of", ptr);
    return;
  }
  if (of.empty()) rd.Error(ptr + "/of", "'of' must name at least one column");
  for (size_t k = 0; k < of.size(); ++k) {
    if (!of[k].is_string()) {
      rd.Error(ptr + "/of/" + std::to_string(k), "a column name must be a string, not " + TypeName(of[k]));
      continue;
    }
    out->of_columns.push_back(of[k].get<std::string>());
  }
  if (!out->of_columns.empty()) out->of = out->of_columns.front();
}

FunctionSpec InvalidFunction(const std::string& ptr) {
  FunctionSpec f;
  f.kind = FunctionSpec::Kind::Invalid;
  f.pointer = ptr;
  return f;
}

// {"table": [[t, v], ...], "interpolation"?}: rows of plain numbers, times increasing.
FunctionSpec ReadTable(JsonReader& rd, const json& f, const std::string& ptr) {
  FunctionSpec out = InvalidFunction(ptr);
  if (!rd.CheckObject(f, ptr, {"table", "interpolation"}, {"table"}, "a table function")) return out;
  if (auto s = rd.String(f, "interpolation", ptr)) {
    if (*s != "linear" && *s != "cubic" && *s != "quintic") {
      rd.Error(ptr + "/interpolation", "unknown interpolation '" + Shorten(*s) + "'",
               "use \"quintic\" (default, smooth to the snap), \"cubic\" or \"linear\"");
      return out;
    }
    out.interpolation = *s;
  }
  if (!f.contains("table")) return out;
  const json& tab = f.at("table");
  if (!tab.is_array() || tab.size() < 2) {
    rd.Error(ptr + "/table", "'table' must be an array of at least 2 rows [t, value]");
    return out;
  }
  for (size_t k = 0; k < tab.size(); ++k) {
    const json& row = tab[k];
    const std::string rp = ptr + "/table/" + std::to_string(k);
    if (!row.is_array() || row.size() != 2 || !row[0].is_number() || !row[1].is_number()) {
      rd.Error(rp, "table row must be [t, value] with two numbers");
      return out;
    }
    out.times.push_back(row[0].get<double>());
    out.values.push_back(row[1].get<double>());
    if (!std::isfinite(out.times.back()) || !std::isfinite(out.values.back())) {
      rd.Error(rp, "table row has a non-finite number");
      return out;
    }
    if (k > 0 && !(out.times[k] > out.times[k - 1])) {
      rd.Error(rp + "/0", "table times must increase strictly", "sort the rows by time and remove duplicates");
      return out;
    }
  }
  out.kind = FunctionSpec::Kind::Table;
  return out;
}

// A force or torque component: a number (its JSON text becomes the expression), or an
// expression of t or a table as for drivers.
FunctionSpec ReadComponent(JsonReader& rd, const json& v, const std::string& ptr) {
  if (v.is_number()) return ReadFunction(rd, json(v.dump()), ptr);
  return ReadFunction(rd, v, ptr);
}

void ReadLoadGeometry(JsonReader& rd, const json& o, const std::string& ptr, LoadSpec* load) {
  load->body = rd.String(o, "body", ptr);
  load->body1 = rd.String(o, "body1", ptr);
  load->body2 = rd.String(o, "body2", ptr);
  load->point = rd.Vector(o, "point", ptr);
  load->point1 = rd.Vector(o, "point1", ptr);
  load->point2 = rd.Vector(o, "point2", ptr);
  load->frame = rd.String(o, "frame", ptr);
  load->stiffness = rd.Number(o, "stiffness", ptr);
  load->free_length = rd.Number(o, "free_length", ptr);
  load->damping = rd.Number(o, "damping", ptr);
  load->preload = rd.Number(o, "preload", ptr);
  if (load->type == "spring" || !o.contains("components")) return;
  const json& c = o.at("components");
  if (!c.is_array() || c.size() != 3) {
    load->components_error = "'components' must be 3 numbers or expressions of t";
    return;
  }
  std::array<FunctionSpec, 3> components;
  for (int k = 0; k < 3; ++k) components[k] = ReadComponent(rd, c[k], ptr + "/components/" + std::to_string(k));
  load->components = std::move(components);
}

}  // namespace

FunctionSpec ReadFunction(JsonReader& rd, const json& f, const std::string& ptr) {
  if (f.is_string()) {
    FunctionSpec out;
    out.text = f.get<std::string>();
    out.pointer = ptr;
    return out;
  }
  if (f.is_number()) {
    rd.Error(ptr, "'function' must be a string expression or a table",
             "write the constant as a string, e.g. \"" + f.dump() + "\"");
    return InvalidFunction(ptr);
  }
  if (!f.is_object()) {
    rd.Error(ptr, "'function' must be a string expression or {\"table\": [[t, v], ...]}, not " + TypeName(f));
    return InvalidFunction(ptr);
  }
  return ReadTable(rd, f, ptr);
}

void ReadOutput(JsonReader& rd, const json& o, const std::string& ptr, MechanismSpec* spec) {
  if (!o.is_object()) {
    rd.Error(ptr, "an output must be a JSON object, not " + TypeName(o));
    return;
  }
  OutputSpec out;
  out.pointer = ptr;
  out.type = rd.String(o, "type", ptr);
  std::vector<std::string> allowed = {"name", "description", "type"}, required = {"name", "type"};
  const bool known = OutputKeys(rd, out.type, ptr, &allowed, &required);
  if (known && *out.type == "clearance") required.erase(required.begin());  // named body1~body2 by default
  if (known && *out.type == "point") {
    if (o.contains("point") && o.contains("marker"))
      rd.Error(ptr + "/marker", "a point output names either 'point' or 'marker'", "remove one of them");
    else if (!o.contains("marker"))
      required.push_back("point");
  }
  rd.CheckObject(o, ptr, allowed, required, "an output");
  out.name = rd.Name(o, ptr, "output");
  if (!known) out.type.reset();
  auto has = [&](const char* key) { return known && std::find(allowed.begin(), allowed.end(), key) != allowed.end(); };
  const StringField strings[] = {{"body", &out.body}, {"frame", &out.frame}, {"joint", &out.joint},
                            {"body1", &out.body1}, {"body2", &out.body2}, {"output", &out.output},
                            {"input", &out.input}, {"relative_to", &out.relative_to}, {"sequence", &out.sequence},
                            {"marker", &out.marker}, {"value", &out.value}, {"reduce", &out.reduce}};
  for (auto [key, field] : strings)
    if (has(key)) *field = rd.String(o, key, ptr);
  if (has("of") && o.contains("of")) ReadOf(rd, o, ptr, &out);
  if (has("targets") && o.contains("targets")) out.targets = ReadTargets(rd, o.at("targets"), ptr + "/targets");
  const VectorField vectors[] = {{"point", &out.point}, {"point1", &out.point1}, {"point2", &out.point2},
                            {"vector1", &out.vector1}, {"vector2", &out.vector2}, {"about", &out.about}};
  for (auto [key, field] : vectors)
    if (has(key)) *field = rd.Vector(o, key, ptr);
  if (has("t")) out.t = rd.Number(o, "t", ptr);
  spec->outputs.push_back(std::move(out));
}

void ReadLoad(JsonReader& rd, const json& o, const std::string& ptr, MechanismSpec* spec) {
  const auto type = rd.String(o, "type", ptr);
  std::vector<std::string> allowed = {"name", "description", "type"}, required = {"name", "type"};
  if (type && *type == "spring") {
    allowed.insert(allowed.end(), {"body1", "point1", "body2", "point2", "stiffness", "free_length", "damping",
                                   "preload"});
    required.insert(required.end(), {"body1", "point1", "body2", "point2", "stiffness"});
  } else if (type && (*type == "force" || *type == "torque")) {
    allowed.insert(allowed.end(), {"body", "components", "frame"});
    required.insert(required.end(), {"body", "components"});
    if (*type == "force") {
      allowed.push_back("point");
      required.push_back("point");
    }
  } else if (type) {
    rd.Error(ptr + "/type", "unknown load type '" + Shorten(*type) + "'", "types: force, torque, spring");
    return;
  }
  if (!rd.CheckObject(o, ptr, allowed, required, "a load") || !type) return;
  LoadSpec load;
  load.pointer = ptr;
  load.type = *type;
  load.name = rd.Name(o, ptr, "load");
  ReadLoadGeometry(rd, o, ptr, &load);
  spec->loads.push_back(std::move(load));
}

}  // namespace mechkin::spec_reader
