// Markers (issue "Describe mechanisms as designers do"): named frames fixed in a
// body, in its own coordinates — "markers": {"pin": {"point", "axis"?, "x_axis"?}};
// ground's in the top-level "ground": {"markers": {...}}.
#include <algorithm>
#include <cctype>

#include "spec/json_reader.hpp"

namespace mechkin::spec_reader {

namespace {

bool IsMarkerName(const std::string& s) {
  return !s.empty() && s.size() <= 64 && (std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_') &&
         std::all_of(s.begin(), s.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; });
}

}  // namespace

std::vector<MarkerSpec> ReadMarkers(JsonReader& rd, const json& markers, const std::string& ptr) {
  std::vector<MarkerSpec> out;
  if (!markers.is_object()) {
    rd.Error(ptr, "'markers' must be an object {\"name\": {\"point\": [x, y, z], \"axis\": [x, y, z]}, ...}, not " +
                      TypeName(markers));
    return out;
  }
  for (const auto& item : markers.items()) {
    const std::string p = ptr + "/" + EscapeToken(item.key());
    if (!IsMarkerName(item.key())) {
      rd.Error(p, "invalid marker name '" + Shorten(item.key()) + "'",
               "use 1-64 letters, digits, '_' or '-', starting with a letter or '_'");
      continue;
    }
    if (!rd.CheckObject(item.value(), p, {"point", "axis", "x_axis", "description"}, {"point"}, "a marker")) continue;
    MarkerSpec m;
    m.name = item.key();
    m.pointer = p;
    m.point = rd.Vector(item.value(), "point", p);
    m.axis = rd.Vector(item.value(), "axis", p);
    m.x_axis = rd.Vector(item.value(), "x_axis", p);
    out.push_back(std::move(m));
  }
  return out;
}

void ReadGround(JsonReader& rd, const json& doc, MechanismSpec* spec) {
  rd.diagnostics().SetPlace(Section::Ground);
  if (!doc.contains("ground")) return;
  const json& g = doc.at("ground");
  if (!rd.CheckObject(g, "/ground", {"markers", "shapes", "description"}, {}, "'ground'")) return;
  if (g.contains("shapes")) spec->ground_shapes = ReadShapeList(rd, g.at("shapes"), "/ground/shapes");
  if (g.contains("markers")) spec->ground_markers = ReadMarkers(rd, g.at("markers"), "/ground/markers");
}

}  // namespace mechkin::spec_reader
