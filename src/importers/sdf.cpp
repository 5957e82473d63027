// SDFormat (docs/import.md "SDFormat"): one <model> (in <sdf> or a <world>), its links,
// <frame>s and joints, every pose resolved through `relative_to` (a link's default
// __model__, a frame's its attached_to, a joint's its child), `degrees="true"` and
// quat_xyzw poses, <axis><xyz expressed_in>, limits, screw pitch, inertials. Links are
// placed by their own poses, so a joint that closes a kinematic loop is read like any
// other: its frame fixed in both links where it lies as written.
#include <cmath>
#include <cstring>
#include <set>

#include "importers/readers.hpp"

namespace mechkin::importers {

using tinyxml2::XMLElement;

namespace {

struct SdfType {
  const char* name;
  Kind kind;
};
const SdfType kSdfTypes[] = {{"revolute", Kind::Revolute},   {"continuous", Kind::Revolute},
                             {"prismatic", Kind::Prismatic}, {"ball", Kind::Spherical},
                             {"universal", Kind::Universal}, {"screw", Kind::Screw},
                             {"fixed", Kind::Fixed}};

struct Frame {
  const XMLElement* element = nullptr;  // link, frame or joint
  std::string relative_to;              // the frame its pose is in
  Pose pose;                            // in relative_to
  std::string attached_to;              // frames: what they are fixed to
};

class SdfReader {
 public:
  SdfReader(const XMLElement* model, Graph* g) : model_(model), g_(g) {}
  void Read();

 private:
  bool ReadPose(const XMLElement* owner, const std::string& default_relative, Frame* f);
  bool World(const std::string& name, Pose* out, int depth = 0);
  std::string LinkOf(const std::string& frame, int depth = 0) const;
  void ReadJoint(const XMLElement* e);
  bool ReadAxis(const XMLElement* e, const char* tag, const Pose& joint_world, Vec3* axis, Joint* j);
  void ReadInertial(const XMLElement* e, Link* l);
  void ReadLinksAndJoints();

  const XMLElement* model_;
  Graph* g_;
  std::map<std::string, Frame> frames_;  // links, frames, joints; "__model__" and "world" implicit
  Pose model_world_;
  std::string canonical_;  // the link __model__ is attached to
};

// A child element's numbers (<pose>0 0 0 0 0 0</pose>); false with an error.
bool Numbers(const XMLElement* e, size_t count, std::vector<double>* out, Graph* g) {
  if (!ParseNumberList(e->GetText() ? e->GetText() : "", out) || out->size() != count) {
    g->Error(e, "<" + std::string(e->Name()) + "> must hold " + std::to_string(count) + " numbers");
    return false;
  }
  return true;
}

bool ChildNumber(const XMLElement* e, const char* tag, double* out, Graph* g) {
  const XMLElement* c = e ? e->FirstChildElement(tag) : nullptr;
  if (!c) return false;
  std::vector<double> v;
  if (!Numbers(c, 1, &v, g)) return false;
  *out = v[0];
  return true;
}

bool SdfPose(const XMLElement* p, Pose* pose, Graph* g) {
  const char* format = p->Attribute("rotation_format");
  const bool quat = format && !std::strcmp(format, "quat_xyzw");
  if (format && !quat && std::strcmp(format, "euler_rpy"))
    return g->Error(p, std::string("rotation_format=\"") + format + "\": expected euler_rpy or quat_xyzw"), false;
  std::vector<double> v;
  if (!p->GetText()) return *pose = Pose{}, true;  // <pose/>: the identity
  if (!Numbers(p, quat ? 7 : 6, &v, g)) return false;
  pose->p = Vec3(v[0], v[1], v[2]);
  if (quat) {
    const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    if (q.norm() < 1e-12) return g->Error(p, "the quaternion is zero", "give x y z w of a rotation"), false;
    pose->R = q.normalized().toRotationMatrix();
    return true;
  }
  const char* deg = p->Attribute("degrees");
  const double k = deg && !std::strcmp(deg, "true") ? M_PI / 180 : 1;
  pose->R = RollPitchYaw(v[3] * k, v[4] * k, v[5] * k);
  return true;
}

bool SdfReader::ReadPose(const XMLElement* owner, const std::string& default_relative, Frame* f) {
  f->element = owner;
  f->relative_to = default_relative;
  const XMLElement* p = owner->FirstChildElement("pose");
  if (!p) return true;
  if (const char* r = p->Attribute("relative_to"); r && *r) f->relative_to = r;
  return SdfPose(p, &f->pose, g_);
}

// The frame's pose in the world, through its relative_to chain.
bool SdfReader::World(const std::string& name, Pose* out, int depth) {
  if (name == "world") return *out = Pose{}, true;
  if (name == "__model__") return *out = model_world_, true;
  auto it = frames_.find(name);
  if (it == frames_.end()) return false;
  if (depth > 100) {
    g_->Error(it->second.element, "the relative_to chain of '" + name + "' is a cycle", "break the cycle");
    return false;
  }
  Pose base;
  if (!World(it->second.relative_to, &base, depth + 1)) {
    if (depth == 0 && !g_->failed())
      g_->Error(it->second.element, "pose relative_to '" + it->second.relative_to + "': no such frame",
                "name a link, frame or joint of the model");
    return false;
  }
  *out = base * it->second.pose;
  return true;
}

// The link a frame is fixed to (a link itself; a frame through attached_to; "world").
std::string SdfReader::LinkOf(const std::string& name, int depth) const {
  if (name == "world" || depth > 100) return name == "world" ? name : "";
  if (name == "__model__") return canonical_;
  auto it = frames_.find(name);
  if (it == frames_.end()) return "";
  if (!std::strcmp(it->second.element->Name(), "link")) return name;
  if (!std::strcmp(it->second.element->Name(), "joint")) return LinkOf(it->second.attached_to, depth + 1);
  return LinkOf(it->second.attached_to.empty() ? "__model__" : it->second.attached_to, depth + 1);
}

void SdfReader::ReadInertial(const XMLElement* e, Link* l) {
  const XMLElement* in = e->FirstChildElement("inertial");
  if (!in) return;
  LinkInertia inertia;
  if (const XMLElement* p = in->FirstChildElement("pose"); p && !SdfPose(p, &inertia.frame, g_)) return;
  double m = 1, v[6] = {1, 0, 0, 1, 0, 1};  // SDFormat's defaults
  ChildNumber(in, "mass", &m, g_);
  const char* keys[] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  for (int k = 0; k < 6; ++k) ChildNumber(in->FirstChildElement("inertia"), keys[k], &v[k], g_);
  inertia.mass = m;
  inertia.moments << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
  l->inertia = inertia;
}

// <axis><xyz expressed_in>: in the joint frame unless it names another frame (or the
// 1.6 use_parent_model_frame); <limit><lower><upper> when both are finite and ordered.
bool SdfReader::ReadAxis(const XMLElement* e, const char* tag, const Pose& joint_world, Vec3* axis, Joint* j) {
  const XMLElement* ax = e->FirstChildElement(tag);
  const XMLElement* xyz = ax ? ax->FirstChildElement("xyz") : nullptr;
  if (!xyz) return true;
  std::vector<double> v;
  if (!Numbers(xyz, 3, &v, g_)) return false;
  const auto unit = UnitAxis(Vec3(v[0], v[1], v[2]), xyz, "the axis", g_);
  if (!unit) return false;
  Pose in{};
  const char* expressed = xyz->Attribute("expressed_in");
  const XMLElement* upm = ax->FirstChildElement("use_parent_model_frame");
  if (upm && upm->GetText() && (!std::strcmp(upm->GetText(), "true") || !std::strcmp(upm->GetText(), "1")))
    expressed = "__model__";
  if (expressed && *expressed && !World(expressed, &in)) {
    g_->Error(xyz, std::string("expressed_in=\"") + expressed + "\": no such frame", "name a frame of the model");
    return false;
  }
  *axis = expressed && *expressed ? Vec3(joint_world.R.transpose() * in.R * *unit) : *unit;
  double lo = -1e16, hi = 1e16;
  const XMLElement* lim = ax->FirstChildElement("limit");
  const bool has_lower = ChildNumber(lim, "lower", &lo, g_);  // both read: each reports its own error
  const bool has_upper = ChildNumber(lim, "upper", &hi, g_);
  const bool both = has_lower && has_upper;
  if (both && std::abs(lo) < 1e15 && std::abs(hi) < 1e15 && j->kind != Kind::Universal && !std::strcmp(tag, "axis")) {
    if (lo < hi) j->limits = std::array<double, 2>{lo, hi};
    else if (lo > hi) return g_->Error(lim, "lower limit above upper limit", "swap them"), false;
  }
  return true;
}

void SdfReader::ReadJoint(const XMLElement* e) {
  Joint j;
  const char* name = RequiredAttribute(e, "name", g_);
  const char* type = RequiredAttribute(e, "type", g_);
  if (!name || !type) return;
  j.name = name, j.place = g_->PlaceOf(e);
  const SdfType* t = nullptr;
  for (const SdfType& k : kSdfTypes)
    if (!std::strcmp(type, k.name)) t = &k;
  if (!t)
    return g_->Error(e, std::string("unsupported joint type '") + type + "'",
                     std::strcmp(type, "revolute2") == 0 ? "write it as two revolute joints through a massless link"
                     : std::strcmp(type, "gearbox") == 0 ? "a gearbox couples two joints: not read yet"
                                                         : "types: revolute, continuous, prismatic, ball, universal, screw, fixed");
  j.kind = t->kind;
  const XMLElement* parent = e->FirstChildElement("parent");
  const XMLElement* child = e->FirstChildElement("child");
  if (!parent || !child || !parent->GetText() || !child->GetText())
    return g_->Error(e, "a joint needs <parent> and <child>", "name two links (or frames, or world)");
  const std::string pf = parent->GetText(), cf = child->GetText();
  j.parent = LinkOf(pf), j.child = LinkOf(cf);
  if (j.parent.empty() || j.child.empty())
    return g_->Error(j.parent.empty() ? parent : child, "'" + (j.parent.empty() ? pf : cf) + "' is no link or frame of the model",
                     "fix the name");
  if (j.child == "world") return g_->Error(child, "the child of a joint cannot be the world", "swap parent and child");
  if (j.parent == j.child) return g_->Error(e, "parent and child are on the same link '" + j.parent + "'", "join two links");
  if (pf != j.parent || cf != j.child)
    g_->Warn(e, "the joint names frames ('" + pf + "', '" + cf + "'): read as joining the links they are attached "
                "to ('" + j.parent + "', '" + j.child + "'), its frame where it lies as written");
  Pose world, parent_world, child_world;
  if (!World(name, &world) || !World(j.parent, &parent_world) || !World(j.child, &child_world)) return;
  j.in_parent = parent_world.Inverse() * world, j.in_child = child_world.Inverse() * world;
  j.axis = Vec3::UnitZ();
  if (!ReadAxis(e, "axis", world, &j.axis, &j)) return;
  j.axis2 = AnyPerpendicular(j.axis);
  if (j.kind == Kind::Universal && !ReadAxis(e, "axis2", world, &j.axis2, &j)) return;
  if (j.kind == Kind::Universal && std::abs(j.axis.dot(j.axis2)) > 1e-6)
    return g_->Error(e, "a universal joint's axis and axis2 are not perpendicular", "give perpendicular axes");
  if (j.kind == Kind::Screw) {
    double p = 0;
    if (ChildNumber(e, "screw_thread_pitch", &p, g_)) j.pitch = p;  // m per turn, right-handed
    else if (ChildNumber(e, "thread_pitch", &p, g_) && p != 0) j.pitch = -2 * M_PI / p;  // rad/m, left-handed
    else return g_->Error(e, "a screw joint needs <screw_thread_pitch> (or <thread_pitch>)", "add its pitch");
  }
  g_->AddJoint(std::move(j), e);
}

void SdfReader::Read() {
  g_->name = model_->Attribute("name") ? model_->Attribute("name") : "";
  if (const XMLElement* p = model_->FirstChildElement("pose"); p && !SdfPose(p, &model_world_, g_)) return;
  const XMLElement* first = model_->FirstChildElement("link");
  const char* canonical = model_->Attribute("canonical_link");
  canonical_ = canonical ? canonical : first && first->Attribute("name") ? first->Attribute("name") : "";
  for (const char* tag : {"link", "frame", "joint"})
    for (const XMLElement* e = model_->FirstChildElement(tag); e; e = e->NextSiblingElement(tag)) {
      const char* name = RequiredAttribute(e, "name", g_);
      if (!name) continue;
      if (frames_.count(name) || !std::strcmp(name, "world") || !std::strcmp(name, "__model__")) {
        g_->Error(e, std::string("the name '") + name + "' is taken", "give every link, frame and joint its own name");
        continue;
      }
      Frame f;
      const char* attached = e->Attribute("attached_to");
      const XMLElement* child = e->FirstChildElement("child");
      f.attached_to = !std::strcmp(tag, "joint") ? (child && child->GetText() ? child->GetText() : "")
                                                 : attached ? attached : "";
      const std::string def = !std::strcmp(tag, "link") ? "__model__"
                              : !std::strcmp(tag, "joint") ? f.attached_to
                                                           : (f.attached_to.empty() ? "__model__" : f.attached_to);
      if (ReadPose(e, def, &f)) frames_[name] = f;
    }
  if (g_->failed()) return;
  ReadLinksAndJoints();
}

void SdfReader::ReadLinksAndJoints() {
  g_->AddLink(Link{"world", Pose{}, std::nullopt, Place{}, true}, nullptr);
  for (const XMLElement* e = model_->FirstChildElement("link"); e; e = e->NextSiblingElement("link")) {
    Link l;
    l.name = e->Attribute("name");
    l.place = g_->PlaceOf(e);
    if (!World(l.name, &l.world)) return;
    ReadInertial(e, &l);
    g_->AddLink(std::move(l), e);
  }
  const XMLElement* st = model_->FirstChildElement("static");
  if (st && st->GetText() && !std::strcmp(st->GetText(), "true"))
    for (size_t k = 1; k < g_->links.size(); ++k) {
      Joint weld;
      weld.name = g_->links[k].name + "__static", weld.kind = Kind::Fixed;
      weld.parent = "world", weld.child = g_->links[k].name, weld.place = g_->PlaceOf(st);
      g_->AddJoint(std::move(weld), st);
    }
  for (const XMLElement* e = model_->FirstChildElement("joint"); e; e = e->NextSiblingElement("joint")) ReadJoint(e);
  for (const XMLElement* e = model_->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "model" || tag == "include")
      g_->Error(e, "<" + tag + "> inside a model (a nested model) is not supported", "flatten it into this model");
    else if (tag != "link" && tag != "joint" && tag != "frame" && tag != "pose" && tag != "static")
      g_->Warn(e, "element <" + tag + "> is not read");
  }
}

}  // namespace

void ReadSdf(const XMLElement* sdf, Graph* g) {
  std::vector<const XMLElement*> models;
  for (const XMLElement* m = sdf->FirstChildElement("model"); m; m = m->NextSiblingElement("model")) models.push_back(m);
  for (const XMLElement* w = sdf->FirstChildElement("world"); w; w = w->NextSiblingElement("world"))
    for (const XMLElement* m = w->FirstChildElement("model"); m; m = m->NextSiblingElement("model")) {
      const XMLElement* st = m->FirstChildElement("static");
      if (st && st->GetText() && !std::strcmp(st->GetText(), "true")) {
        g->Warn(m, "a static model in the world is not read (ground geometry)");
        continue;
      }
      models.push_back(m);
    }
  if (models.size() != 1) {
    g->Error(sdf, models.empty() ? "no <model> to read" : "more than one moving <model>: mechkin reads one",
             "keep the mechanism's model in the file");
    return;
  }
  SdfReader(models[0], g).Read();
}

}  // namespace mechkin::importers
