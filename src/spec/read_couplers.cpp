// "couplers": gears, belts, racks and pinions, screw couplings and general
// couplings between joint coordinates (docs/format.md "Couplers").
#include <algorithm>

#include "spec/json_reader.hpp"

namespace mechkin::spec_reader {

namespace {

const std::vector<std::string>& CouplerTypes() {
  static const std::vector<std::string> kTypes = {"gear", "belt", "rack_pinion", "screw_coupling", "coupling"};
  return kTypes;
}

// The keys a coupler of `type` takes besides name, description, type.
void CouplerKeys(const std::string& type, std::vector<std::string>* allowed, std::vector<std::string>* required) {
  auto add = [&](std::initializer_list<const char*> keys) {
    allowed->insert(allowed->end(), keys.begin(), keys.end());
    required->insert(required->end(), keys.begin(), keys.end());
  };
  if (type == "gear") add({"joint1", "joint2", "ratio"}), allowed->insert(allowed->end(), {"pitch_radius", "pressure_angle"});
  else if (type == "belt") add({"joint1", "joint2", "ratio"});
  else if (type == "rack_pinion") add({"joint1", "joint2", "pitch_radius"});
  else if (type == "screw_coupling") add({"joint1", "joint2", "pitch"});
  else if (type == "coupling") add({"joints", "coefficients"}), allowed->insert(allowed->end(), {"constant", "coordinates"});
  else
    allowed->insert(allowed->end(), {"joint1", "joint2", "ratio", "pitch_radius", "pressure_angle", "pitch", "joints",
                                     "coefficients", "constant", "coordinates"});
}

// c[key] as an array of strings (joint names, coordinate kinds).
std::vector<std::string> StringList(JsonReader& rd, const json& c, const std::string& key, const std::string& ptr,
                                    const std::string& what, bool* ok) {
  std::vector<std::string> out;
  if (!c.contains(key)) return out;
  const json& v = c.at(key);
  if (!v.is_array()) {
    rd.Error(ptr + "/" + key, "'" + key + "' must be an array of " + what + ", not " + TypeName(v),
             "write e.g. \"" + key + "\": [\"J1\", \"J2\"]");
    *ok = false;
    return out;
  }
  for (size_t k = 0; k < v.size(); ++k) {
    if (!v[k].is_string()) {
      rd.Error(ptr + "/" + key + "/" + std::to_string(k), "must be a string (" + what + "), not " + TypeName(v[k]));
      *ok = false;
      continue;
    }
    out.push_back(v[k].get<std::string>());
  }
  return out;
}

void ReadCouplingLists(JsonReader& rd, const json& c, const std::string& ptr, CouplerSpec* cp) {
  cp->joints = StringList(rd, c, "joints", ptr, "joint names", &cp->ok);
  cp->coordinates = StringList(rd, c, "coordinates", ptr, "\"rotation\" or \"translation\"", &cp->ok);
  if (c.contains("coefficients")) {
    const json& v = c.at("coefficients");
    if (!v.is_array()) {
      rd.Error(ptr + "/coefficients", "'coefficients' must be an array of numbers, not " + TypeName(v),
               "one coefficient per joint, e.g. [1, 1, -2]");
      cp->ok = false;
    } else {
      for (size_t k = 0; k < v.size(); ++k)
        cp->coefficients.push_back(rd.ScalarValue(v[k], ptr + "/coefficients/" + std::to_string(k), "coefficient"));
    }
  }
  cp->constant = rd.Number(c, "constant", ptr);
}

}  // namespace

void ReadCoupler(JsonReader& rd, const json& c, const std::string& ptr, MechanismSpec* spec) {
  if (!c.is_object()) {
    rd.Error(ptr, "a coupler must be a JSON object, not " + TypeName(c));
    return;
  }
  CouplerSpec cp;
  cp.pointer = ptr;
  cp.type = rd.String(c, "type", ptr);
  const bool known = cp.type && std::count(CouplerTypes().begin(), CouplerTypes().end(), *cp.type) > 0;
  if (cp.type && !known) {
    const std::string g = DidYouMean(*cp.type, CouplerTypes());
    rd.Error(ptr + "/type", "unknown coupler type '" + Shorten(*cp.type) + "'",
             (g.empty() ? "" : "did you mean '" + g + "'? ") + "types: " + Join(CouplerTypes()));
    cp.ok = false;
  }
  std::vector<std::string> allowed = {"name", "description", "type"}, required = {"name", "type"};
  CouplerKeys(known ? *cp.type : "", &allowed, &required);
  if (!rd.CheckObject(c, ptr, allowed, required, known ? "a " + *cp.type + " coupler" : "a coupler")) cp.ok = false;
  cp.name = rd.Name(c, ptr, "coupler");
  cp.joint1 = rd.String(c, "joint1", ptr);
  cp.joint2 = rd.String(c, "joint2", ptr);
  cp.ratio = rd.Number(c, "ratio", ptr);
  cp.pitch_radius = rd.Number(c, "pitch_radius", ptr);
  cp.pitch = rd.Number(c, "pitch", ptr);
  cp.pressure_angle = rd.Number(c, "pressure_angle", ptr);
  ReadCouplingLists(rd, c, ptr, &cp);
  spec->couplers.push_back(std::move(cp));
}

}  // namespace mechkin::spec_reader
