// URDF (docs/import.md "URDF"): links, joints, limits, mimic joints, inertials, and
// the loop conventions real files use — a joint whose child already has a parent
// (a second parent), <loop_joint>, a <gazebo> SDFormat <joint>, and CAD exporters'
// closing_<name>_1 / closing_<name>_2 link pairs. The joint list is read as a graph:
// every joint is kept.
#include <cstring>
#include <deque>
#include <set>

#include "importers/readers.hpp"

namespace mechkin::importers {

using tinyxml2::XMLElement;

namespace {

struct UrdfType {
  const char* name;
  Kind kind;
  bool limited;  // takes <limit lower upper>
};
// floating is not a constraint: its child is left a free body (below).
const UrdfType kUrdfTypes[] = {{"revolute", Kind::Revolute, true}, {"continuous", Kind::Revolute, false},
                               {"prismatic", Kind::Prismatic, true}, {"fixed", Kind::Fixed, false},
                               {"planar", Kind::Planar, false}};

const UrdfType* FindUrdfType(const char* t) {
  for (const UrdfType& u : kUrdfTypes)
    if (t && std::strcmp(t, u.name) == 0) return &u;
  return nullptr;
}

bool ReadInertial(const XMLElement* e, LinkInertia* out, Graph* g) {
  if (!ReadOrigin(e->FirstChildElement("origin"), &out->frame, g)) return false;
  const XMLElement* mass = e->FirstChildElement("mass");
  const XMLElement* inertia = e->FirstChildElement("inertia");
  if (!mass || !inertia) {
    g->Error(e, "an <inertial> needs <mass value> and <inertia ixx ixy ixz iyy iyz izz>", "add both, or remove it");
    return false;
  }
  if (!ReadNumbers(mass, "value", 1, &out->mass, g)) return false;
  double v[6];
  const char* keys[] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  for (int k = 0; k < 6; ++k)
    if (!ReadNumbers(inertia, keys[k], 1, &v[k], g)) return false;
  out->moments << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
  return true;
}

void ReadLinks(const XMLElement* robot, Graph* g) {
  for (const XMLElement* e = robot->FirstChildElement("link"); e; e = e->NextSiblingElement("link")) {
    const char* name = RequiredAttribute(e, "name", g);
    if (!name) continue;
    Link l;
    l.name = name;
    l.place = g->PlaceOf(e);
    if (const XMLElement* in = e->FirstChildElement("inertial")) {
      LinkInertia inertia;
      if (ReadInertial(in, &inertia, g)) l.inertia = inertia;
    }
    g->AddLink(std::move(l), e);
  }
}

// <limit lower upper>: the range when both are given and differ; 0/0 (absent) is no lock.
void ReadLimit(const XMLElement* e, const UrdfType& type, Joint* j, Graph* g) {
  const XMLElement* lim = e->FirstChildElement("limit");
  if (!lim || !type.limited) return;
  if (!lim->Attribute("lower") && !lim->Attribute("upper")) {
    g->Warn(lim, "a <limit> without lower and upper: the joint is left without limits (0/0 is not a lock)");
    return;
  }
  double lo = 0, hi = 0;
  if (!ReadOptionalNumbers(lim, "lower", 1, &lo, g) || !ReadOptionalNumbers(lim, "upper", 1, &hi, g)) return;
  if (lo > hi) {
    g->Error(lim, "lower limit " + std::to_string(lo) + " is above upper limit " + std::to_string(hi),
             "swap lower and upper");
  } else if (lo == hi) {
    g->Warn(lim, "lower = upper: the joint is left without limits (mechkin limits need lower < upper)");
  } else {
    j->limits = std::array<double, 2>{lo, hi};
  }
}

void ReadMimic(const XMLElement* e, const std::string& joint, Graph* g) {
  const XMLElement* m = e->FirstChildElement("mimic");
  if (!m) return;
  const char* other = RequiredAttribute(m, "joint", g);
  double mult = 1, offset = 0;
  if (!other || !ReadOptionalNumbers(m, "multiplier", 1, &mult, g) || !ReadOptionalNumbers(m, "offset", 1, &offset, g))
    return;
  // q_joint = multiplier q_other + offset  →  q_joint − multiplier q_other = offset.
  g->couplings.push_back({"mimic_" + joint, {joint, other}, {1.0, -mult}, offset, g->PlaceOf(m)});
}

// The joint's own elements (its frame in the parent; the tree decides the child's frame).
bool ReadJoint(const XMLElement* e, Joint* j, Graph* g) {
  const char* name = RequiredAttribute(e, "name", g);
  const char* type = RequiredAttribute(e, "type", g);
  const XMLElement* parent = e->FirstChildElement("parent");
  const XMLElement* child = e->FirstChildElement("child");
  if (!name || !type) return false;
  j->name = name;
  j->place = g->PlaceOf(e);
  if (!parent || !child) {
    g->Error(e, "a joint needs <parent link> and <child link>", "add both");
    return false;
  }
  const char* pl = RequiredAttribute(parent, "link", g);
  const char* cl = RequiredAttribute(child, "link", g);
  if (!pl || !cl) return false;
  j->parent = pl, j->child = cl;
  for (const char* l : {pl, cl})
    if (!g->FindLink(l)) {
      g->Error(e, std::string("link '") + l + "' is not defined", "add a <link name=\"" + std::string(l) + "\"> or fix the name");
      return false;
    }
  if (j->parent == j->child) {
    g->Error(e, "the joint's parent and child are the same link '" + j->parent + "'", "join two different links");
    return false;
  }
  if (!ReadOrigin(e->FirstChildElement("origin"), &j->in_parent, g)) return false;
  double axis[3] = {1, 0, 0};
  const XMLElement* ax = e->FirstChildElement("axis");
  if (!ReadOptionalNumbers(ax, "xyz", 3, axis, g)) return false;
  const auto unit = UnitAxis(Vec3(axis[0], axis[1], axis[2]), ax ? ax : e, "the joint axis", g);
  if (!unit) return false;
  j->axis = *unit;
  return true;
}

struct Tree {
  std::map<std::string, size_t> parent_joint;  // link → its tree joint (index into graph joints)
  std::vector<bool> loop;                      // per joint: a second parent
};

// Joints in file order; the first joint naming a link as child is its tree joint.
void ReadJoints(const XMLElement* robot, Graph* g, Tree* tree) {
  for (const XMLElement* e = robot->FirstChildElement("joint"); e; e = e->NextSiblingElement("joint")) {
    Joint j;
    if (!ReadJoint(e, &j, g)) continue;
    const char* type = e->Attribute("type");
    const UrdfType* t = FindUrdfType(type);
    if (type && std::strcmp(type, "floating") == 0) {
      g->Warn(e, "a floating joint is no constraint: link '" + j.child + "' is left a free body (6 freedoms)");
      continue;
    }
    if (!t) {
      g->Error(e, std::string("unknown joint type '") + type + "'",
               "URDF types: revolute, continuous, prismatic, fixed, floating, planar");
      continue;
    }
    j.kind = t->kind;
    ReadLimit(e, *t, &j, g);
    ReadMimic(e, j.name, g);
    const bool second = tree->parent_joint.count(j.child) > 0;
    if (!second) tree->parent_joint[j.child] = g->joints.size();
    if (g->AddJoint(std::move(j), e)) tree->loop.push_back(second);
  }
}

// The written pose: every tree joint at q = 0 from the root, which is ground.
void PlaceLinks(Graph* g, const Tree& tree, const XMLElement* robot) {
  std::deque<std::string> queue;
  std::set<std::string> placed;
  for (Link& l : g->links)
    if (!tree.parent_joint.count(l.name)) {
      if (queue.empty()) l.ground = true;
      else
        g->Warn(l.place, "a second root link: '" + l.name + "' is not connected to the first root by tree joints",
                "it is placed where written and moves freely unless loop joints hold it");
      queue.push_back(l.name);
      placed.insert(l.name);
    }
  while (!queue.empty()) {
    const std::string at = queue.front();
    queue.pop_front();
    for (size_t k = 0; k < g->joints.size(); ++k) {
      const Joint& j = g->joints[k];
      if (tree.loop[k] || j.parent != at || placed.count(j.child)) continue;
      g->FindLink(j.child)->world = g->FindLink(at)->world * j.in_parent;
      placed.insert(j.child);
      queue.push_back(j.child);
    }
  }
  for (const Link& l : g->links)
    if (!placed.count(l.name))
      g->Error(l.place, "link '" + l.name + "' is on a cycle of parent joints with no root link",
               "make one link the root: no joint may name it as child");
  if (queue.empty() && g->links.empty()) g->Error(robot, "the robot has no <link>", "add links and joints");
}

void CloseSecondParents(Graph* g, const Tree& tree) {
  for (size_t k = 0; k < g->joints.size(); ++k) {
    Joint& j = g->joints[k];
    if (!tree.loop[k]) continue;
    const Link& parent = *g->FindLink(j.parent);
    const Link& child = *g->FindLink(j.child);
    j.in_child = child.world.Inverse() * parent.world * j.in_parent;
    const std::string first = g->joints[tree.parent_joint.at(j.child)].name;
    g->Warn(j.place, "link '" + j.child + "' already has the parent joint '" + first +
                         "': this joint is kept as a loop-closing joint (the second-parent convention), its frame "
                         "<origin> in '" + j.parent + "' fixed in '" + j.child + "' where it lies in the written pose");
  }
}

}  // namespace

bool ReadOrigin(const XMLElement* e, Pose* pose, Graph* g) {
  *pose = Pose{};
  if (!e) return true;
  double xyz[3] = {0, 0, 0}, rpy[3] = {0, 0, 0};
  if (!ReadOptionalNumbers(e, "xyz", 3, xyz, g) || !ReadOptionalNumbers(e, "rpy", 3, rpy, g)) return false;
  pose->p = Vec3(xyz[0], xyz[1], xyz[2]);
  pose->R = RollPitchYaw(rpy[0], rpy[1], rpy[2]);
  return true;
}

void ReadUrdfLoops(const XMLElement* robot, Graph* g);

void ReadUrdf(const XMLElement* robot, Graph* g) {
  g->name = robot->Attribute("name") ? robot->Attribute("name") : "";
  ReadLinks(robot, g);
  Tree tree;
  ReadJoints(robot, g, &tree);
  if (g->failed()) return;
  PlaceLinks(g, tree, robot);
  if (g->failed()) return;
  CloseSecondParents(g, tree);
  ReadUrdfLoops(robot, g);
}

}  // namespace mechkin::importers
