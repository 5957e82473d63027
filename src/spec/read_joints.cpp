// "joints" and "drivers".
#include <algorithm>

#include "joints/registry.hpp"
#include "spec/json_reader.hpp"

namespace mechkin::spec_reader {

namespace {

using StringField = std::pair<const char*, std::optional<std::string>*>;
using VectorField = std::pair<const char*, std::optional<Vector3Spec>*>;

// The joint types are the registry's (src/joints): a type registered by the program
// is read like a built-in one.
const JointDescriptor* FindJointType(JsonReader& rd, const std::optional<std::string>& type, const std::string& ptr) {
  if (!type) return nullptr;
  if (const JointDescriptor* d = mechkin::FindJointType(*type)) return d;
  const std::vector<std::string> names = JointTypeNames();
  const std::string g = DidYouMean(*type, names);
  rd.Error(ptr + "/type", "unknown joint type '" + Shorten(*type) + "'",
           (g.empty() ? "" : "did you mean '" + g + "'? ") + "types: " + Join(names));
  return nullptr;
}

void Append(std::vector<std::string>* to, const std::vector<std::string>& keys) {
  to->insert(to->end(), keys.begin(), keys.end());
}

// A joint on two markers ("marker1" of body1, "marker2" of body2): the markers give
// the origin and axes; a screw keeps its pitch, a distance link its optional length.
void MarkerJointKeys(const JointDescriptor& info, std::vector<std::string>* allowed,
                     std::vector<std::string>* required) {
  allowed->insert(allowed->end(), {"marker1", "marker2"});
  required->insert(required->end(), {"marker1", "marker2"});
  Append(allowed, info.MarkerRequiredKeys());
  Append(required, info.MarkerRequiredKeys());
  Append(allowed, info.MarkerOptionalKeys());
}

// "limits": [lo, hi], two numbers or expressions.
std::optional<std::array<Scalar, 2>> ReadLimits(JsonReader& rd, const json& jj, const std::string& ptr) {
  if (!jj.contains("limits")) return std::nullopt;
  const json& v = jj.at("limits");
  if (!v.is_array() || v.size() != 2) {
    rd.Error(ptr + "/limits", "'limits' must be [lo, hi], two numbers, not " + TypeName(v),
             "e.g. \"limits\": [-30, 45] in the file's angle unit (a slide: its length unit)");
    return std::nullopt;
  }
  return std::array<Scalar, 2>{rd.ScalarValue(v[0], ptr + "/limits/0", "the lower limit"),
                               rd.ScalarValue(v[1], ptr + "/limits/1", "the upper limit")};
}

// The keys a driver of `type` takes besides name, description, type, function.
void DriverKeys(JsonReader& rd, const std::optional<std::string>& type, bool by_body, const std::string& ptr,
                std::vector<std::string>* allowed, std::vector<std::string>* required) {
  auto add = [&](std::initializer_list<const char*> keys) {
    allowed->insert(allowed->end(), keys.begin(), keys.end());
    required->insert(required->end(), keys.begin(), keys.end());
  };
  if (type && *type == "rotation" && by_body) {
    add({"body", "axis"});
  } else if (type && (*type == "rotation" || *type == "translation")) {
    add({"joint"});
  } else if (type && *type == "distance") {
    add({"body1", "point1", "body2", "point2"});
  } else if (type && *type == "coordinate") {
    add({"body", "point", "axis"});
    allowed->push_back("axis_body");
  } else if (type && *type == "angle") {
    add({"body1", "body2", "about"});
    allowed->push_back("vector");
  } else {
    if (type) {
      const std::string g = DidYouMean(*type, {"rotation", "translation", "distance", "coordinate", "angle"});
      rd.Error(ptr + "/type", "unknown driver type '" + Shorten(*type) + "'",
               (g.empty() ? "" : "did you mean '" + g + "'? ") +
                   "types: rotation, translation, distance, coordinate, angle");
    }
    allowed->insert(allowed->end(), {"joint", "body", "axis", "body1", "point1", "body2", "point2", "point",
                                     "axis_body", "about", "vector"});
  }
}

}  // namespace

bool JointsUseMarkers(const json& doc) {
  if (!doc.contains("joints") || !doc.at("joints").is_array()) return false;
  for (const json& j : doc.at("joints"))
    if (j.is_object() && (j.contains("marker1") || j.contains("marker2"))) return true;
  return false;
}

void ReadJoint(JsonReader& rd, const json& jj, const std::string& ptr, MechanismSpec* spec) {
  if (!jj.is_object()) {
    rd.Error(ptr, "a joint must be a JSON object, not " + TypeName(jj));
    return;
  }
  JointSpec joint;
  joint.pointer = ptr;
  const auto type = rd.String(jj, "type", ptr);
  const JointDescriptor* info = FindJointType(rd, type, ptr);
  std::vector<std::string> allowed = {"name", "description", "type", "body1", "body2"};
  std::vector<std::string> required = {"name", "type", "body1", "body2"};
  const bool by_markers = jj.contains("marker1") || jj.contains("marker2");
  if (info && by_markers) {
    MarkerJointKeys(*info, &allowed, &required);
  } else {
    for (const JointDescriptor* t : JointTypes()) {
      if (info && info != t) continue;
      Append(&allowed, t->RequiredKeys());
      Append(&allowed, t->OptionalKeys());
      if (info) Append(&required, t->RequiredKeys());
    }
    if (!info) allowed.insert(allowed.end(), {"marker1", "marker2"});
  }
  rd.CheckObject(jj, ptr, allowed, required, info ? "a " + info->name + " joint" : "a joint");
  joint.name = rd.Name(jj, ptr, "joint");
  joint.body1 = rd.String(jj, "body1", ptr);
  joint.body2 = rd.String(jj, "body2", ptr);
  if (info) joint.type = info->name;
  joint.origin = rd.Vector(jj, "origin", ptr);
  joint.axis = rd.Vector(jj, "axis", ptr);
  joint.axis1 = rd.Vector(jj, "axis1", ptr);
  joint.axis2 = rd.Vector(jj, "axis2", ptr);
  joint.normal = rd.Vector(jj, "normal", ptr);
  joint.point1 = rd.Vector(jj, "point1", ptr);
  joint.point2 = rd.Vector(jj, "point2", ptr);
  joint.pitch = rd.Number(jj, "pitch", ptr);
  joint.length = rd.Number(jj, "length", ptr);
  joint.marker1 = rd.String(jj, "marker1", ptr);
  joint.marker2 = rd.String(jj, "marker2", ptr);
  joint.limits = ReadLimits(rd, jj, ptr);
  if (info && !by_markers) {
    const std::vector<std::string> geometry = info->RequiredKeys();
    joint.geometry_complete =
        std::all_of(geometry.begin(), geometry.end(), [&](const std::string& key) { return jj.contains(key); });
  }
  spec->joints.push_back(std::move(joint));
}

void ReadDriver(JsonReader& rd, const json& d, const std::string& ptr, MechanismSpec* spec) {
  if (!d.is_object()) {
    rd.Error(ptr, "a driver must be a JSON object, not " + TypeName(d));
    return;
  }
  DriverSpec drv;
  drv.pointer = ptr;
  drv.type = rd.String(d, "type", ptr);
  drv.by_body = (d.contains("body") || d.contains("axis")) && !(drv.type && *drv.type == "coordinate");
  std::vector<std::string> allowed = {"name", "description", "type", "function"};
  std::vector<std::string> required = {"name", "type", "function"};
  DriverKeys(rd, drv.type, drv.by_body, ptr, &allowed, &required);
  rd.CheckObject(d, ptr, allowed, required, drv.type ? "a " + *drv.type + " driver" : "a driver");
  drv.name = rd.Name(d, ptr, "driver");
  const bool known = drv.type && (*drv.type == "rotation" || *drv.type == "translation" || *drv.type == "distance" ||
                                  *drv.type == "coordinate" || *drv.type == "angle");
  const StringField strings[] = {{"joint", &drv.joint}, {"body", &drv.body}, {"body1", &drv.body1},
                            {"body2", &drv.body2}, {"axis_body", &drv.axis_body}};
  for (auto [key, field] : strings)
    if (known && std::find(allowed.begin(), allowed.end(), key) != allowed.end()) *field = rd.String(d, key, ptr);
  const VectorField vectors[] = {{"axis", &drv.axis}, {"point", &drv.point}, {"point1", &drv.point1},
                            {"point2", &drv.point2}, {"about", &drv.about}, {"vector", &drv.vector}};
  for (auto [key, field] : vectors)
    if (known && std::find(allowed.begin(), allowed.end(), key) != allowed.end()) *field = rd.Vector(d, key, ptr);
  if (d.contains("function")) drv.function = ReadFunction(rd, d.at("function"), ptr + "/function");
  spec->drivers.push_back(std::move(drv));
}

}  // namespace mechkin::spec_reader
