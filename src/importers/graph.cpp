// The graph's bookkeeping, its messages and the XML helpers of the readers.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "importers/graph.hpp"

namespace mechkin::importers {

std::string ImportMessage::Place() const {
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line);
  if (!element.empty()) s += ": " + element;
  return s;
}

std::string ImportMessage::ToString() const {
  std::string s = Place() + ": " + message;
  if (!fix.empty()) s += " — " + fix;
  return s;
}

std::string ImportResult::OriginOf(const std::string& pointer) const {
  std::string best, at;
  for (const auto& [prefix, place] : origins) {
    const bool match = pointer.compare(0, prefix.size(), prefix) == 0 &&
                       (pointer.size() == prefix.size() || pointer[prefix.size()] == '/');
    if (match && prefix.size() >= best.size()) best = prefix, at = place;
  }
  return at;
}

Place Graph::PlaceOf(const tinyxml2::XMLElement* e) const {
  if (!e) return {};
  return {e->GetLineNum(), Describe(e)};
}

void Graph::Error(const Place& at, const std::string& message, const std::string& fix) {
  result_->errors.push_back({file_, at.line, at.element, message, fix});
}

void Graph::Warn(const Place& at, const std::string& message, const std::string& fix) {
  result_->warnings.push_back({file_, at.line, at.element, message, fix});
}

Link* Graph::FindLink(const std::string& n) {
  auto it = link_index_.find(n);
  return it == link_index_.end() ? nullptr : &links[it->second];
}

const Joint* Graph::FindJoint(const std::string& n) const {
  auto it = joint_index_.find(n);
  return it == joint_index_.end() ? nullptr : &joints[it->second];
}

bool Graph::AddLink(Link link, const tinyxml2::XMLElement* e) {
  if (link_index_.count(link.name)) {
    Error(e, "a second link (body) named '" + link.name + "'", "give every link its own name");
    return false;
  }
  link_index_[link.name] = links.size();
  links.push_back(std::move(link));
  return true;
}

bool Graph::AddJoint(Joint joint, const tinyxml2::XMLElement* e) {
  if (joint_index_.count(joint.name)) {
    Error(e, "a second joint named '" + joint.name + "'", "give every joint its own name");
    return false;
  }
  joint_index_[joint.name] = joints.size();
  joints.push_back(std::move(joint));
  return true;
}

// The name of the first element of an XML text (after the declaration, comments, doctype).
std::string RootName(const std::string& head) {
  size_t k = 0;
  while ((k = head.find('<', k)) != std::string::npos) {
    if (head.compare(k, 4, "<!--") == 0) {
      k = head.find("-->", k);
      if (k == std::string::npos) return "";
      continue;
    }
    if (head.compare(k, 2, "<?") == 0 || head.compare(k, 2, "<!") == 0) {
      ++k;
      continue;
    }
    size_t e = k + 1;
    while (e < head.size() && (std::isalnum(static_cast<unsigned char>(head[e])) || head[e] == '_' || head[e] == ':'))
      ++e;
    return head.substr(k + 1, e - k - 1);
  }
  return "";
}


namespace {

// Stray text after the root element (files in the wild have it; MuJoCo, Gazebo and
// ROS read them): the document up to the root's last closing tag, the rest skipped.
bool ParseWithoutTrailingText(const std::string& text, tinyxml2::XMLDocument* doc, Graph* graph) {
  const std::string close = "</" + RootName(text.substr(0, 4096)) + ">";
  const auto end = text.rfind(close);
  if (close.size() <= 3 || end == std::string::npos) return false;
  const std::string prefix = text.substr(0, end + close.size());
  if (text.find_first_not_of(" \t\r\n", prefix.size()) == std::string::npos) return false;
  tinyxml2::XMLDocument trimmed;
  if (trimmed.Parse(prefix.data(), prefix.size()) != tinyxml2::XML_SUCCESS || !trimmed.RootElement()) return false;
  const int line = 1 + static_cast<int>(std::count(prefix.begin(), prefix.end(), '\n'));
  graph->Warn(Place{line, ""}, "text after the root element's " + close + " is skipped");
  doc->Parse(prefix.data(), prefix.size());
  return true;
}

}  // namespace

bool ParseXml(const std::string& text, tinyxml2::XMLDocument* doc, Graph* graph) {
  if (doc->Parse(text.data(), text.size()) == tinyxml2::XML_SUCCESS && doc->RootElement()) return true;
  if (doc->ErrorID() == tinyxml2::XML_ERROR_PARSING_TEXT && ParseWithoutTrailingText(text, doc, graph)) return true;
  // ErrorStr() reads "Error=NAME ErrorID=.. (0x..) Line number=N: DETAIL": keep NAME and DETAIL.
  std::string why = doc->Error() ? doc->ErrorName() : "no root element";
  const std::string full = doc->Error() && doc->ErrorStr() ? doc->ErrorStr() : "";
  const auto detail = full.find(": ", full.find("Line number="));
  if (detail != std::string::npos) why += ": " + full.substr(detail + 2);
  graph->Error(Place{doc->ErrorLineNum(), ""}, "not well-formed XML: " + why, "fix the XML syntax at this line");
  return false;
}

std::string Describe(const tinyxml2::XMLElement* e) {
  std::string s = "<" + std::string(e->Name());
  for (const char* key : {"name", "type", "link", "joint", "joint1", "body1", "class"}) {
    if (const char* v = e->Attribute(key)) {
      s += " " + std::string(key) + "=\"" + v + "\"";
      break;
    }
  }
  return s + ">";
}

bool ParseNumberList(const char* text, std::vector<double>* out) {
  out->clear();
  const char* s = text;
  for (;;) {
    while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r' || *s == ',') ++s;
    if (!*s) return true;
    char* end = nullptr;
    const double v = std::strtod(s, &end);
    if (end == s || !std::isfinite(v)) return false;
    out->push_back(v);
    s = end;
  }
}

bool ReadNumbers(const tinyxml2::XMLElement* e, const char* attribute, int count, double* out, Graph* graph) {
  const char* text = e->Attribute(attribute);
  if (!text) {
    graph->Error(e, std::string("attribute '") + attribute + "' is missing",
                 "give " + std::to_string(count) + " numbers, e.g. " + attribute + "=\"0 0 1\"");
    return false;
  }
  std::vector<double> v;
  if (!ParseNumberList(text, &v) || static_cast<int>(v.size()) != count) {
    graph->Error(e, std::string("attribute '") + attribute + "=\"" + text + "\"' must be " + std::to_string(count) +
                        " numbers separated by spaces");
    return false;
  }
  for (int k = 0; k < count; ++k) out[k] = v[k];
  return true;
}

bool ReadOptionalNumbers(const tinyxml2::XMLElement* e, const char* attribute, int count, double* out,
                         Graph* graph) {
  if (!e || !e->Attribute(attribute)) return true;
  return ReadNumbers(e, attribute, count, out, graph);
}

const char* RequiredAttribute(const tinyxml2::XMLElement* e, const char* attribute, Graph* graph) {
  const char* v = e->Attribute(attribute);
  if (!v || !*v) graph->Error(e, std::string("attribute '") + attribute + "' is missing", "add it");
  return v && *v ? v : nullptr;
}

Mat3 AxisAngle(const Vec3& unit_axis, double angle) {
  return Eigen::AngleAxisd(angle, unit_axis).toRotationMatrix();
}

Mat3 RollPitchYaw(double roll, double pitch, double yaw) {
  return AxisAngle(Vec3::UnitZ(), yaw) * AxisAngle(Vec3::UnitY(), pitch) * AxisAngle(Vec3::UnitX(), roll);
}

Mat3 ZTo(const Vec3& axis) {
  const Vec3 z = Vec3::UnitZ();
  const Vec3 k = z.cross(axis);
  if (k.norm() < 1e-15) return axis.z() > 0 ? Mat3::Identity() : AxisAngle(Vec3::UnitX(), M_PI);
  return AxisAngle(k.normalized(), std::atan2(k.norm(), z.dot(axis)));
}

std::optional<Vec3> UnitAxis(const Vec3& v, const tinyxml2::XMLElement* e, const std::string& what, Graph* graph) {
  if (v.norm() < 1e-12) {
    graph->Error(e, what + " is the zero vector", "give the axis direction, e.g. \"0 0 1\"");
    return std::nullopt;
  }
  return v.normalized();
}

}  // namespace mechkin::importers
