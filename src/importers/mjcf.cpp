// MJCF (MuJoCo XML; docs/import.md "MJCF"): <compiler angle eulerseq autolimits>,
// <default> classes for joints (nested classes, childclass, an element's own class),
// the body tree with pos/quat/axisangle/euler/xyaxes/zaxis, hinge/slide/ball joints
// in their body's frame (several joints in one body: a chain through massless
// bodies), <inertial>, sites, and <equality> (mjcf_equality.cpp). A body without a
// joint is welded to its parent. The written pose is qpos0: a joint's coordinate is
// q − ref.
#include <cctype>
#include <cstring>
#include <set>

#include "importers/mjcf.hpp"

namespace mechkin::importers::mjcf {

using tinyxml2::XMLElement;

namespace {

const XMLElement* Holder(const Reader& r, const XMLElement* joint, const std::string& cls, const char* key) {
  if (joint->Attribute(key)) return joint;
  std::set<std::string> seen;
  for (std::string c = cls; !c.empty() && seen.insert(c).second;) {
    auto it = r.classes.find(c);
    if (it == r.classes.end()) break;
    if (it->second.second && it->second.second->Attribute(key)) return it->second.second;
    c = it->second.first;
  }
  return nullptr;
}

void ReadCompiler(const XMLElement* e, Reader* r) {
  if (const char* a = e->Attribute("angle")) {
    if (std::strcmp(a, "degree") && std::strcmp(a, "radian"))
      r->g->Error(e, std::string("angle=\"") + a + "\": expected degree or radian");
    r->degrees = std::strcmp(a, "radian") != 0;
  }
  if (const char* s = e->Attribute("eulerseq")) {
    const std::string seq = s;
    bool ok = seq.size() == 3;
    for (char c : seq) ok = ok && std::strchr("xyzXYZ", c);
    if (!ok) r->g->Error(e, "eulerseq=\"" + seq + "\": expected three of x y z X Y Z", "e.g. eulerseq=\"xyz\"");
    r->eulerseq = seq;
  }
  if (const char* a = e->Attribute("autolimits")) r->autolimits = std::strcmp(a, "false") != 0;
  if (const char* c = e->Attribute("coordinate"); c && std::strcmp(c, "local"))
    r->g->Error(e, std::string("coordinate=\"") + c + "\" is not supported (removed from MuJoCo)",
                "write positions in local coordinates");
}

void ReadDefaults(const XMLElement* e, const std::string& parent, Reader* r) {
  const char* c = e->Attribute("class");
  const std::string cls = c ? c : parent.empty() ? "main" : "";
  if (cls.empty()) {
    r->g->Error(e, "a nested <default> needs a class name", "add class=\"...\"");
    return;
  }
  if (r->classes.count(cls)) r->g->Error(e, "a second <default> class '" + cls + "'", "give it another name");
  r->classes[cls] = {parent, e->FirstChildElement("joint")};
  for (const XMLElement* d = e->FirstChildElement("default"); d; d = d->NextSiblingElement("default"))
    ReadDefaults(d, cls, r);
}

Vec3 UnitOf(char c) { return std::tolower(c) == 'x' ? Vec3::UnitX() : std::tolower(c) == 'y' ? Vec3::UnitY() : Vec3::UnitZ(); }

// One of quat (w x y z), axisangle, euler (eulerseq), xyaxes, zaxis; identity when none.
bool ReadOrientation(const XMLElement* e, const Reader& r, Mat3* R) {
  Graph* g = r.g;
  int given = 0;
  for (const char* k : {"quat", "axisangle", "euler", "xyaxes", "zaxis"}) given += e->Attribute(k) != nullptr;
  if (given > 1) return g->Error(e, "more than one orientation (quat, axisangle, euler, xyaxes, zaxis)", "keep one"), false;
  *R = Mat3::Identity();
  double v[6];
  if (e->Attribute("quat")) {
    if (!ReadNumbers(e, "quat", 4, v, g)) return false;
    const Eigen::Quaterniond q(v[0], v[1], v[2], v[3]);
    if (q.norm() < 1e-12) return g->Error(e, "quat is zero", "give w x y z of a rotation"), false;
    *R = q.normalized().toRotationMatrix();
  } else if (e->Attribute("axisangle")) {
    if (!ReadNumbers(e, "axisangle", 4, v, g)) return false;
    const auto axis = UnitAxis(Vec3(v[0], v[1], v[2]), e, "the axisangle axis", g);
    if (!axis) return false;
    *R = AxisAngle(*axis, r.Angle(v[3]));
  } else if (e->Attribute("euler")) {
    if (!ReadNumbers(e, "euler", 3, v, g)) return false;
    for (int k = 0; k < 3; ++k) {
      const Mat3 Rk = AxisAngle(UnitOf(r.eulerseq[k]), r.Angle(v[k]));
      *R = std::islower(static_cast<unsigned char>(r.eulerseq[k])) ? Mat3(*R * Rk) : Mat3(Rk * *R);
    }
  } else if (e->Attribute("xyaxes")) {
    if (!ReadNumbers(e, "xyaxes", 6, v, g)) return false;
    const Vec3 x(v[0], v[1], v[2]), y0(v[3], v[4], v[5]);
    const Vec3 y = y0 - (y0.dot(x) / std::max(x.squaredNorm(), 1e-300)) * x;
    if (x.norm() < 1e-12 || y.norm() < 1e-12) return g->Error(e, "xyaxes are zero or parallel", "give two directions"), false;
    R->col(0) = x.normalized(), R->col(1) = y.normalized(), R->col(2) = x.normalized().cross(y.normalized());
  } else if (e->Attribute("zaxis")) {
    if (!ReadNumbers(e, "zaxis", 3, v, g)) return false;
    const auto z = UnitAxis(Vec3(v[0], v[1], v[2]), e, "zaxis", g);
    if (!z) return false;
    *R = ZTo(*z);
  }
  return true;
}

bool ReadFrame(const XMLElement* e, const Reader& r, Pose* pose) {
  double p[3] = {0, 0, 0};
  if (!ReadOptionalNumbers(e, "pos", 3, p, r.g) || !ReadOrientation(e, r, &pose->R)) return false;
  pose->p = Vec3(p[0], p[1], p[2]);
  return true;
}

bool ReadMjcfInertial(const XMLElement* e, const Reader& r, LinkInertia* in) {
  if (!ReadFrame(e, r, &in->frame) || !ReadNumbers(e, "mass", 1, &in->mass, r.g)) return false;
  double v[6];
  if (e->Attribute("fullinertia")) {
    if (!ReadNumbers(e, "fullinertia", 6, v, r.g)) return false;  // ixx iyy izz ixy ixz iyz
    in->moments << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
    return true;
  }
  if (!ReadNumbers(e, "diaginertia", 3, v, r.g)) return false;
  in->moments = Vec3(v[0], v[1], v[2]).asDiagonal();
  return true;
}

struct JointType {
  const char* name;
  Kind kind;
};
const JointType kJointTypes[] = {{"hinge", Kind::Revolute}, {"slide", Kind::Prismatic}, {"ball", Kind::Spherical}};

// A joint's range as limits from the written pose (q − ref), per `limited` and autolimits.
bool ReadRange(const XMLElement* je, const std::string& cls, const Reader& r, Joint* j, double ref) {
  const XMLElement* lim = Holder(r, je, cls, "limited");
  const XMLElement* ran = Holder(r, je, cls, "range");
  const std::string limited = lim ? lim->Attribute("limited") : "auto";
  const bool on = limited == "true" || (limited != "false" && ran && r.autolimits);
  if (!on) return true;
  if (j->kind == Kind::Spherical) {
    r.g->Warn(je, "the range of a ball joint (a cone) is not mapped: mechkin limits are for one coordinate");
    return true;
  }
  double v[2];
  if (!ran) return r.g->Error(je, "limited=\"true\" without a range", "add range=\"lo hi\""), false;
  if (!ReadNumbers(ran, "range", 2, v, r.g)) return false;
  const double k = j->kind == Kind::Revolute && r.degrees ? M_PI / 180 : 1;
  if (!(v[0] < v[1])) return r.g->Error(ran, "range lower bound is not below the upper", "give lo < hi"), false;
  j->limits = std::array<double, 2>{v[0] * k - ref, v[1] * k - ref};
  return true;
}

// A <joint> in body `link`: its frame in that body (pos, axis), its ref and limits.
bool ReadJointElement(const XMLElement* je, const std::string& cls_in, const std::string& link, Reader* r, Joint* j) {
  const char* own_class = je->Attribute("class");
  const std::string cls = own_class ? own_class : cls_in;
  if (!r->classes.count(cls) && cls != "main")
    return r->g->Error(je, "unknown default class '" + cls + "'", "define <default class=\"" + cls + "\">"), false;
  const XMLElement* th = Holder(*r, je, cls, "type");
  const std::string type = th ? th->Attribute("type") : "hinge";
  if (type == "free")
    return r->g->Error(je, "a free joint (6 freedoms) is not supported: it is no kinematic constraint",
                       "remove the free body, or weld it (delete the joint)"), false;
  const JointType* t = nullptr;
  for (const JointType& k : kJointTypes)
    if (type == k.name) t = &k;
  if (!t) return r->g->Error(th, "unknown joint type '" + type + "'", "MJCF types: hinge, slide, ball, free"), false;
  j->kind = t->kind;
  double pos[3] = {0, 0, 0}, axis[3] = {0, 0, 1}, ref = 0;
  if (!ReadOptionalNumbers(Holder(*r, je, cls, "pos"), "pos", 3, pos, r->g) ||
      !ReadOptionalNumbers(Holder(*r, je, cls, "axis"), "axis", 3, axis, r->g) ||
      !ReadOptionalNumbers(Holder(*r, je, cls, "ref"), "ref", 1, &ref, r->g))
    return false;
  const auto unit = UnitAxis(Vec3(axis[0], axis[1], axis[2]), je, "the joint axis", r->g);
  if (!unit) return false;
  j->axis = *unit;
  j->in_child = {Mat3::Identity(), Vec3(pos[0], pos[1], pos[2])};
  if (j->kind == Kind::Revolute) ref = r->Angle(ref);
  if (j->kind == Kind::Spherical) ref = 0;
  const char* name = je->Attribute("name");
  j->name = name ? name : link + "_joint" + std::to_string(++r->unnamed);
  j->place = r->g->PlaceOf(je);
  r->joints[j->name] = {link, ref};
  return ReadRange(je, cls, *r, j, ref);
}

}  // namespace

const char* Reader::JointAttribute(const XMLElement* joint, const std::string& cls, const char* key) const {
  const XMLElement* h = Holder(*this, joint, cls, key);
  return h ? h->Attribute(key) : nullptr;
}

void ReadBody(const XMLElement* e, const std::string& parent, const std::string& cls_in, Reader* r);

namespace {

// The body's joints, in order: parent → (massless links) → the body; none: welded.
void ReadBodyJoints(const XMLElement* e, const std::string& parent, const std::string& name, const std::string& cls,
                    Reader* r) {
  Graph* g = r->g;
  std::vector<const XMLElement*> joints;
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (!std::strcmp(c->Name(), "joint")) joints.push_back(c);
    if (!std::strcmp(c->Name(), "freejoint"))
      g->Error(c, "a free joint (6 freedoms) is not supported: it is no kinematic constraint",
               "remove the free body, or weld it (delete the joint)");
  }
  const Pose world = g->FindLink(name)->world;
  if (joints.empty()) {
    Joint weld;
    weld.kind = Kind::Fixed, weld.name = name + "__weld", weld.parent = parent, weld.child = name;
    weld.in_parent = g->FindLink(parent)->world.Inverse() * world;
    g->AddJoint(weld, e);
    return;
  }
  std::string from = parent;
  for (size_t k = 0; k < joints.size(); ++k) {
    Joint j;
    if (!ReadJointElement(joints[k], cls, name, r, &j)) continue;
    j.parent = from;
    j.child = k + 1 == joints.size() ? name : name + "__" + j.name;
    if (j.child != name) {
      g->AddLink(Link{j.child, world, std::nullopt, j.place, false}, joints[k]);
      g->Warn(joints[k], "several joints in body '" + name + "': joint '" + j.name + "' moves a massless body '" +
                             j.child + "' in the chain to it");
    }
    r->joints[j.name].link = j.child;
    j.in_parent = g->FindLink(from)->world.Inverse() * world * j.in_child;
    from = j.child;
    g->AddJoint(std::move(j), joints[k]);
  }
}

void ReadSites(const XMLElement* e, const std::string& link, Reader* r) {
  for (const XMLElement* s = e->FirstChildElement("site"); s; s = s->NextSiblingElement("site")) {
    double p[3] = {0, 0, 0};
    if (s->Attribute("name") && ReadOptionalNumbers(s, "pos", 3, p, r->g))
      r->sites[s->Attribute("name")] = {link, Vec3(p[0], p[1], p[2])};
  }
}

}  // namespace

void ReadBody(const XMLElement* e, const std::string& parent, const std::string& cls_in, Reader* r) {
  Graph* g = r->g;
  const char* childclass = e->Attribute("childclass");
  const std::string cls = childclass ? childclass : cls_in;
  const char* n = e->Attribute("name");
  Link l;
  l.name = n ? n : "body" + std::to_string(e->GetLineNum());
  l.place = g->PlaceOf(e);
  Pose local;
  if (!ReadFrame(e, *r, &local)) return;
  l.world = g->FindLink(parent)->world * local;
  if (const XMLElement* in = e->FirstChildElement("inertial")) {
    LinkInertia inertia;
    if (ReadMjcfInertial(in, *r, &inertia)) l.inertia = inertia;
  }
  if (!g->AddLink(l, e)) return;
  ReadBodyJoints(e, parent, l.name, cls, r);
  ReadSites(e, l.name, r);
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "body") ReadBody(c, l.name, cls, r);
    if (tag == "frame" || tag == "include" || tag == "replicate" || tag == "attach")
      g->Error(c, "<" + tag + "> is not supported", "expand it into plain bodies");
  }
}

}  // namespace mechkin::importers::mjcf

namespace mechkin::importers {

void ReadMjcf(const tinyxml2::XMLElement* root, Graph* g) {
  mjcf::Reader r;
  r.g = g;
  g->name = root->Attribute("model") ? root->Attribute("model") : "";
  static const std::set<std::string> kNotKinematic = {"option", "size", "visual", "statistic", "asset", "contact",
                                                      "tendon", "actuator", "sensor", "keyframe", "custom", "extension"};
  for (const tinyxml2::XMLElement* e = root->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "compiler") mjcf::ReadCompiler(e, &r);
    else if (tag == "default") mjcf::ReadDefaults(e, "", &r);
    else if (tag == "include") g->Error(e, "<include> is not supported", "paste the included file's elements here");
    else if (tag == "tendon" || tag == "actuator" || tag == "keyframe")
      g->Warn(e, "<" + tag + "> is not read: not a kinematic constraint (drive joints with --drive)");
    else if (!kNotKinematic.count(tag) && tag != "worldbody" && tag != "equality")
      g->Warn(e, "element <" + tag + "> is not read");
  }
  Link world{"world", Pose{}, std::nullopt, Place{}, true};
  g->AddLink(world, nullptr);
  for (const tinyxml2::XMLElement* w = root->FirstChildElement("worldbody"); w; w = w->NextSiblingElement("worldbody")) {
    mjcf::ReadSites(w, "world", &r);
    for (const tinyxml2::XMLElement* c = w->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      if (tag == "body") mjcf::ReadBody(c, "world", "main", &r);
      if (tag == "joint" || tag == "freejoint") g->Error(c, "a joint directly in <worldbody>", "put it in a <body>");
      if (tag == "frame") g->Error(c, "<frame> is not supported", "expand it into plain bodies");
    }
  }
  if (g->failed()) return;
  for (const tinyxml2::XMLElement* e = root->FirstChildElement("equality"); e; e = e->NextSiblingElement("equality"))
    mjcf::ReadEquality(e, &r);
}

}  // namespace mechkin::importers
