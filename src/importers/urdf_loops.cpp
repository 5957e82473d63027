// URDF's loop conventions beyond the second parent (docs/import.md "URDF loops"):
//  * <loop_joint name type><link1 link xyz rpy/><link2 link xyz rpy/><axis xyz/></loop_joint>
//    (Drake's extension): a frame on each link, the axis in those frames; the frames
//    need not coincide in the written pose (mechkin assembles the loop);
//  * <gazebo><joint name type><parent/><child/><pose/><axis><xyz/></axis></joint></gazebo>:
//    an SDFormat joint, its pose relative to the child link, kept as written;
//  * links named closing_<name>_1 and closing_<name>_2 (CAD exporters): their origins
//    coincide — a spherical joint, since the type is not stated.
// Top-level elements that are neither read nor harmless are named in a warning.
#include <cstring>
#include <set>

#include "importers/readers.hpp"

namespace mechkin::importers {

using tinyxml2::XMLElement;

namespace {

struct LoopType {
  const char* name;
  Kind kind;
};
const LoopType kLoopTypes[] = {{"revolute", Kind::Revolute},   {"continuous", Kind::Revolute},
                               {"prismatic", Kind::Prismatic}, {"fixed", Kind::Fixed},
                               {"ball", Kind::Spherical},      {"spherical", Kind::Spherical},
                               {"universal", Kind::Universal}, {"cylindrical", Kind::Cylindrical}};

bool FindLoopType(const XMLElement* e, Kind* kind, Graph* g) {
  const char* t = RequiredAttribute(e, "type", g);
  if (!t) return false;
  for (const LoopType& l : kLoopTypes)
    if (std::strcmp(t, l.name) == 0) return *kind = l.kind, true;
  g->Error(e, std::string("unsupported loop joint type '") + t + "'",
           "types: revolute, continuous, prismatic, fixed, ball, universal, cylindrical");
  return false;
}

// <link1 link xyz rpy/>: the link and the frame on it.
bool LoopEnd(const XMLElement* e, const char* tag, std::string* link, Pose* frame, Graph* g) {
  const XMLElement* end = e->FirstChildElement(tag);
  if (!end) {
    g->Error(e, std::string("a <loop_joint> needs <") + tag + " link=\"...\" xyz rpy/>", "add it");
    return false;
  }
  const char* l = RequiredAttribute(end, "link", g);
  if (!l || !ReadOrigin(end, frame, g)) return false;
  if (!g->FindLink(l)) {
    g->Error(end, std::string("link '") + l + "' is not defined", "fix the link name");
    return false;
  }
  *link = l;
  return true;
}

void ReadLoopJoint(const XMLElement* e, Graph* g) {
  Joint j;
  const char* name = RequiredAttribute(e, "name", g);
  if (!name || !FindLoopType(e, &j.kind, g)) return;
  j.name = name;
  j.place = g->PlaceOf(e);
  if (!LoopEnd(e, "link1", &j.parent, &j.in_parent, g) || !LoopEnd(e, "link2", &j.child, &j.in_child, g)) return;
  double axis[3] = {1, 0, 0};
  const XMLElement* ax = e->FirstChildElement("axis");
  if (!ReadOptionalNumbers(ax, "xyz", 3, axis, g)) return;
  const auto unit = UnitAxis(Vec3(axis[0], axis[1], axis[2]), ax ? ax : e, "the loop joint axis", g);
  if (!unit) return;
  j.axis = *unit;
  j.axis2 = AnyPerpendicular(j.axis);
  g->Warn(e, "loop joint (the <loop_joint> extension): frames <link1> in '" + j.parent + "' and <link2> in '" +
                 j.child + "', axis in them; the loop is closed by assembly");
  g->AddJoint(std::move(j), e);
}

// A child element's numbers (SDFormat style: <pose>0 0 0 0 0 0</pose>).
bool TextNumbers(const XMLElement* e, int count, double* out, Graph* g) {
  std::vector<double> v;
  if (!e->GetText() || !ParseNumberList(e->GetText(), &v) || static_cast<int>(v.size()) != count) {
    g->Error(e, "<" + std::string(e->Name()) + "> must hold " + std::to_string(count) + " numbers");
    return false;
  }
  for (int k = 0; k < count; ++k) out[k] = v[k];
  return true;
}

bool GazeboAxis(const XMLElement* e, const char* tag, Vec3* axis, Graph* g) {
  const XMLElement* ax = e->FirstChildElement(tag);
  const XMLElement* xyz = ax ? ax->FirstChildElement("xyz") : nullptr;
  if (!xyz) return true;
  double v[3];
  if (!TextNumbers(xyz, 3, v, g)) return false;
  const auto unit = UnitAxis(Vec3(v[0], v[1], v[2]), xyz, "the axis", g);
  if (unit) *axis = *unit;
  return unit.has_value();
}

void ReadGazeboJoint(const XMLElement* e, Graph* g) {
  Joint j;
  const char* name = RequiredAttribute(e, "name", g);
  if (!name || !FindLoopType(e, &j.kind, g)) return;
  j.name = name;
  j.place = g->PlaceOf(e);
  const XMLElement* parent = e->FirstChildElement("parent");
  const XMLElement* child = e->FirstChildElement("child");
  if (!parent || !child || !parent->GetText() || !child->GetText()) {
    g->Error(e, "an SDFormat <joint> needs <parent> and <child> link names", "add both");
    return;
  }
  j.parent = parent->GetText(), j.child = child->GetText();
  for (const std::string& l : {j.parent, j.child})
    if (!g->FindLink(l)) return g->Error(e, "link '" + l + "' is not defined", "fix the link name");
  double pose[6] = {0, 0, 0, 0, 0, 0};
  if (const XMLElement* p = e->FirstChildElement("pose"); p && !TextNumbers(p, 6, pose, g)) return;
  j.in_child = {RollPitchYaw(pose[3], pose[4], pose[5]), Vec3(pose[0], pose[1], pose[2])};
  j.in_parent = g->FindLink(j.parent)->world.Inverse() * g->FindLink(j.child)->world * j.in_child;
  j.axis = Vec3::UnitX();
  if (!GazeboAxis(e, "axis", &j.axis, g)) return;
  j.axis2 = AnyPerpendicular(j.axis);
  if (j.kind == Kind::Universal && !GazeboAxis(e, "axis2", &j.axis2, g)) return;
  g->Warn(e, "loop joint from a <gazebo> block (an SDFormat joint): its <pose> in the child link '" + j.child +
                 "', fixed in '" + j.parent + "' where it lies in the written pose");
  g->AddJoint(std::move(j), e);
}

// closing_<name>_1 and closing_<name>_2: a point closure between the two links' origins.
void ReadClosingPairs(Graph* g) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const Link& l : g->links) {
    const std::string& n = l.name;
    if (n.rfind("closing_", 0) != 0 || n.size() < 11 || n.compare(n.size() - 2, 2, "_1") != 0) continue;
    const std::string other = n.substr(0, n.size() - 1) + "2";
    if (g->FindLink(other)) pairs.push_back({n, other});
  }
  for (const auto& [a, b] : pairs) {
    Joint j;
    j.name = a.substr(0, a.size() - 2);
    j.kind = Kind::Spherical;
    j.parent = a, j.child = b;
    j.place = g->FindLink(a)->place;
    j.in_child = g->FindLink(b)->world.Inverse() * g->FindLink(a)->world;
    g->Warn(j.place, "links '" + a + "' and '" + b + "' (the closing_<name>_1/_2 convention of CAD exporters) are "
                     "joined by a spherical joint '" + j.name + "' at their origins: the convention states no type",
            "for a revolute closure write a <loop_joint type=\"revolute\"> instead");
    g->AddJoint(std::move(j), nullptr);
  }
}

}  // namespace

void ReadUrdfLoops(const XMLElement* robot, Graph* g) {
  static const std::set<std::string> kHarmless = {"link", "joint", "material", "transmission", "gazebo"};
  for (const XMLElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "loop_joint") ReadLoopJoint(e, g);
    else if (tag == "gazebo")
      for (const XMLElement* j = e->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint"))
        ReadGazeboJoint(j, g);
    else if (!kHarmless.count(tag))
      g->Warn(e, "element <" + tag + "> is not read (not kinematic, or not URDF)");
  }
  ReadClosingPairs(g);
}

}  // namespace mechkin::importers
