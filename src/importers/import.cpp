// The layer's entry points: detecting a foreign file and importing it.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

#include "importers/readers.hpp"

namespace mechkin::importers {

std::string FormatName(ForeignFormat format) {
  switch (format) {
    case ForeignFormat::Urdf: return "URDF";
    case ForeignFormat::Mjcf: return "MJCF";
    case ForeignFormat::Sdf: return "SDFormat";
    case ForeignFormat::FreeCad: return "FreeCAD";
    case ForeignFormat::None: break;
  }
  return "";
}

namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string Extension(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return Lower(path.substr(dot + 1));
}

}  // namespace

ForeignFormat DetectForeignFormat(const std::string& path, const std::string& head) {
  const std::string ext = Extension(path);
  if (ext == "fcstd" || head.compare(0, 4, "PK\x03\x04") == 0) return ForeignFormat::FreeCad;
  const size_t first = head.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
  const bool xml = first != std::string::npos && head[first] == '<';
  if (!xml && ext != "urdf" && ext != "sdf" && ext != "mjcf" && ext != "world" && ext != "xml")
    return ForeignFormat::None;
  const std::string root = RootName(head);
  if (root == "robot") return ForeignFormat::Urdf;
  if (root == "mujoco") return ForeignFormat::Mjcf;
  if (root == "sdf") return ForeignFormat::Sdf;
  if (ext == "urdf") return ForeignFormat::Urdf;
  if (ext == "sdf" || ext == "world") return ForeignFormat::Sdf;
  if (ext == "mjcf" || ext == "xml" || xml) return ForeignFormat::Mjcf;
  return ForeignFormat::None;
}

ImportResult ImportText(const std::string& text, ForeignFormat format, const std::string& display_name,
                        const ImportOptions& options) {
  ImportResult result;
  result.format = format;
  Graph graph(display_name, &result);
  if (format == ForeignFormat::None) {
    graph.Error(Place{}, "not a URDF, MJCF, SDFormat or FreeCAD Assembly file",
                "give a .urdf, MJCF .xml, .sdf or .FCStd file");
    return result;
  }
  tinyxml2::XMLDocument doc;
  if (!ParseXml(text, &doc, &graph)) return result;
  const tinyxml2::XMLElement* root = doc.RootElement();
  const std::string want = format == ForeignFormat::Urdf   ? "robot"
                           : format == ForeignFormat::Mjcf ? "mujoco"
                           : format == ForeignFormat::Sdf  ? "sdf"
                                                           : "Document";
  if (want != root->Name()) {
    graph.Error(root, "the root element of a " + FormatName(format) + " file is <" + want + ">",
                "give a " + FormatName(format) + " file");
    return result;
  }
  if (format == ForeignFormat::Urdf) ReadUrdf(root, &graph);
  if (format == ForeignFormat::Mjcf) ReadMjcf(root, &graph);
  if (format == ForeignFormat::Sdf) ReadSdf(root, &graph);
  if (format == ForeignFormat::FreeCad) ReadFreeCad(root, &graph);
  if (graph.failed()) return result;
  if (graph.description.empty())
    graph.description = "Imported from " + display_name + " (" + FormatName(format) +
                        ") by mechkin import; units m, rad, kg; markers at the joint frames (docs/import.md).";
  BuildSpec(graph, options, &result);
  return result;
}

ImportResult ImportFile(const std::string& path, const ImportOptions& options) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (!in) {
    ImportResult r;
    r.errors.push_back({path, 0, "", "cannot read the file", "check the path and permissions"});
    return r;
  }
  const std::string text = buffer.str();
  const ForeignFormat format = DetectForeignFormat(path, text.substr(0, 4096));
  if (format != ForeignFormat::FreeCad) return ImportText(text, format, path, options);
  std::string document, why;
  if (!ReadFcstd(path, &document, &why)) {
    ImportResult r;
    r.format = format;
    r.errors.push_back({path, 0, "", why, "give a FreeCAD 1.x .FCStd file"});
    return r;
  }
  return ImportText(document, format, path + ":Document.xml", options);
}

}  // namespace mechkin::importers
