// FreeCAD 1.x Assembly (docs/import.md "FreeCAD Assembly"): the .FCStd zip's
// Document.xml, read as the Assembly workbench writes it. Objects with a JointType
// (an enumeration: its index into the file's own CustomEnumList of names when given,
// else into FreeCAD's list) are the joints; Reference1/Reference2 are
// [root, ["Part.Body.Face3", "Part.Body.Vertex2"]]: the moving part is the first
// object of the path inside the assembly (document groups skipped), the joint frame
// is Placement1 (Placement2) relative to the last object before the element — the
// offsets Offset1/2 are already in it (JointObject.findPlacement), not applied again.
// A part's placement is its Placement, an App::Link's its LinkPlacement. Objects with
// an ObjectToGround fix their part to the ground; Activated=false and Suppressed joints
// are skipped with a warning. Saved placements need not satisfy the joints: the
// markers are assembled. Joint kinds mechkin has no joint for are named with what
// they need.
#include <zip.h>

#include <cstring>
#include <map>

#include "importers/readers.hpp"

namespace mechkin::importers {

using tinyxml2::XMLElement;

bool ReadFcstd(const std::string& path, std::string* document, std::string* why) {
  int code = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_RDONLY, &code);
  if (!z) {
    zip_error_t e;
    zip_error_init_with_code(&e, code);
    *why = std::string("not a readable zip archive: ") + zip_error_strerror(&e);
    zip_error_fini(&e);
    return false;
  }
  zip_stat_t st;
  zip_file_t* f = zip_stat(z, "Document.xml", 0, &st) == 0 ? zip_fopen(z, "Document.xml", 0) : nullptr;
  if (!f || !(st.valid & ZIP_STAT_SIZE) || st.size > (256u << 20)) {
    *why = "the archive holds no readable Document.xml";
    if (f) zip_fclose(f);
    zip_close(z);
    return false;
  }
  document->resize(st.size);
  const zip_int64_t n = zip_fread(f, document->data(), st.size);
  zip_fclose(f);
  zip_close(z);
  if (n != static_cast<zip_int64_t>(st.size)) return *why = "Document.xml cannot be read whole", false;
  return true;
}

namespace {

// FreeCAD's JointType enumeration, in its order; kind Fixed marks the unsupported ones too.
struct FcJoint {
  const char* name;
  bool supported;
  Kind kind;
  const char* needs;  // for the unsupported ones
};
const FcJoint kFcJoints[] = {
    {"Fixed", true, Kind::Fixed, ""},
    {"Revolute", true, Kind::Revolute, ""},
    {"Cylindrical", true, Kind::Cylindrical, ""},
    {"Slider", true, Kind::Prismatic, ""},
    {"Ball", true, Kind::Spherical, ""},
    {"Distance", false, Kind::Fixed,
     "a distance between two vertices is a distance link; other elements need "
     "point-plane or plane-plane distance constraints, which the format lacks"},
    {"Parallel", false, Kind::Fixed,
     "a constraint keeping two axes parallel (two dot-1 equations), not a joint type yet"},
    {"Perpendicular", false, Kind::Fixed, "a constraint keeping two axes perpendicular (one dot-1 equation)"},
    {"Angle", false, Kind::Fixed, "a constraint fixing the angle between two axes (one dot-1 equation)"},
    {"RackPinion", false, Kind::Fixed, "the revolute and prismatic joints it couples: write a rack_pinion coupler"},
    {"Screw", false, Kind::Fixed, "the joints it couples: write a screw joint or a screw_coupling coupler"},
    {"Gears", false, Kind::Fixed, "the two revolute joints it couples: write a gear coupler"},
    {"Belt", false, Kind::Fixed, "the two revolute joints it couples: write a belt coupler"},
};

class FcReader {
 public:
  explicit FcReader(Graph* g) : g_(g) {}
  void Read(const XMLElement* document);

 private:
  using Props = std::map<std::string, const XMLElement*>;
  const XMLElement* Prop(const std::string& object, const char* name) const {
    auto o = props_.find(object);
    if (o == props_.end()) return nullptr;
    auto p = o->second.find(name);
    return p == o->second.end() ? nullptr : p->second;
  }
  bool PlacementOf(const XMLElement* prop, Pose* pose) const;
  Pose ObjectPlacement(const std::string& object) const;
  bool BoolProp(const std::string& object, const char* name, bool otherwise) const;
  const FcJoint* JointTypeOf(const std::string& object);
  bool IsMovingPart(const std::string& object) const;
  std::string NameOf(const std::string& object) const;
  bool Side(const std::string& joint, int k, std::string* part, Pose* frame);
  std::string AddPart(const std::string& object, const Pose& global);
  void ReadJoint(const std::string& joint);

  Graph* g_;
  std::map<std::string, Props> props_;
  std::map<std::string, const XMLElement*> objects_;
  std::map<std::string, std::string> types_;  // object → its type in <Objects>
  std::vector<std::string> order_;
  std::map<std::string, std::string> part_link_;  // part object → link name
};

bool FcReader::PlacementOf(const XMLElement* prop, Pose* pose) const {
  const XMLElement* p = prop ? prop->FirstChildElement("PropertyPlacement") : nullptr;
  if (!p) return false;
  double v[7];
  const char* keys[] = {"Px", "Py", "Pz", "Q0", "Q1", "Q2", "Q3"};
  for (int k = 0; k < 7; ++k)
    if (!ReadNumbers(p, keys[k], 1, &v[k], g_)) return false;
  const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);  // Q0..Q3 = x y z w
  if (q.norm() < 1e-12) return g_->Error(p, "the placement's quaternion is zero", "re-save the file"), false;
  *pose = {q.normalized().toRotationMatrix(), Vec3(v[0], v[1], v[2]) * 1e-3};  // FreeCAD stores mm
  return true;
}

Pose FcReader::ObjectPlacement(const std::string& object) const {
  Pose p;
  const XMLElement* link = Prop(object, "LinkPlacement");  // an App::Link's own placement
  PlacementOf(link ? link : Prop(object, "Placement"), &p);
  return p;
}

bool FcReader::BoolProp(const std::string& object, const char* name, bool otherwise) const {
  const XMLElement* prop = Prop(object, name);
  const XMLElement* b = prop ? prop->FirstChildElement("Bool") : nullptr;
  if (!b || !b->Attribute("value")) return otherwise;
  return std::strcmp(b->Attribute("value"), "true") == 0;
}

// JointType: an index into the file's CustomEnumList when it has one (FreeCAD writes
// the list: JointObject sets it from Python), else into FreeCAD's list; nullptr after an error.
const FcJoint* FcReader::JointTypeOf(const std::string& object) {
  const XMLElement* e = objects_.at(object);
  const XMLElement* type = Prop(object, "JointType");
  const XMLElement* index = type ? type->FirstChildElement("Integer") : nullptr;
  int k = -1;
  if (!index || index->QueryIntAttribute("value", &k) != tinyxml2::XML_SUCCESS)
    return g_->Error(type ? type : e, "JointType holds no <Integer value>", "re-save the file"), nullptr;
  std::vector<std::string> names;
  const XMLElement* list = type->FirstChildElement("CustomEnumList");
  for (const XMLElement* n = list ? list->FirstChildElement("Enum") : nullptr; n; n = n->NextSiblingElement("Enum"))
    names.push_back(n->Attribute("value") ? n->Attribute("value") : "");
  if (names.empty())
    for (const FcJoint& t : kFcJoints) names.push_back(t.name);
  if (k < 0 || k >= static_cast<int>(names.size()))
    return g_->Error(index,
                     "JointType " + std::to_string(k) + " is not in its list of " + std::to_string(names.size()) +
                         " joint types",
                     "re-save the file"),
           nullptr;
  for (const FcJoint& t : kFcJoints)
    if (names[k] == t.name) return &t;
  g_->Error(index, "JointType '" + names[k] + "' is not one of FreeCAD 1.x's joint types",
            "types: Fixed, Revolute, Cylindrical, Slider, Ball, Distance, Parallel, Perpendicular, Angle, RackPinion, "
            "Screw, Gears, Belt");
  return nullptr;
}

std::string FcReader::NameOf(const std::string& object) const {
  const XMLElement* label = Prop(object, "Label");
  const XMLElement* s = label ? label->FirstChildElement("String") : nullptr;
  return s && s->Attribute("value") && *s->Attribute("value") ? s->Attribute("value") : object;
}

std::string FcReader::AddPart(const std::string& object, const Pose& global) {
  auto it = part_link_.find(object);
  if (it != part_link_.end()) return it->second;
  Link l;
  l.name = NameOf(object);
  if (g_->FindLink(l.name)) l.name = object;
  l.place = g_->PlaceOf(objects_.count(object) ? objects_.at(object) : nullptr);
  l.world = global;
  g_->AddLink(l, objects_.count(object) ? objects_.at(object) : nullptr);
  return part_link_[object] = l.name;
}

// An object that can be a moving part: not an assembly or a group.
bool FcReader::IsMovingPart(const std::string& object) const {
  auto t = types_.find(object);
  const std::string type = t == types_.end() ? "" : t->second;
  return type != "Assembly::AssemblyObject" && type != "App::DocumentObjectGroup" && type != "Assembly::JointGroup";
}

// Side k (1, 2) of a joint: its part and the joint frame in it.
bool FcReader::Side(const std::string& joint, int k, std::string* part, Pose* frame) {
  const std::string n = std::to_string(k);
  const XMLElement* ref = Prop(joint, ("Reference" + n).c_str());
  const XMLElement* link = ref ? ref->FirstChildElement("XLinkSub") : nullptr;
  const XMLElement* place = objects_.at(joint);
  if (!link || !link->Attribute("name"))
    return g_->Error(place, "Reference" + n + " names no part", "attach the joint to two parts in FreeCAD"), false;
  const XMLElement* sub = link->FirstChildElement("Sub");
  const char* text = sub ? sub->Attribute("value") : link->Attribute("sub");
  std::vector<std::string> path;
  for (std::string rest = text ? text : ""; !rest.empty();) {
    const auto dot = rest.find('.');
    path.push_back(rest.substr(0, dot));
    rest = dot == std::string::npos ? "" : rest.substr(dot + 1);
  }
  const std::string root = link->Attribute("name");
  if (!objects_.count(root)) return g_->Error(ref, "Reference" + n + ": no object '" + root + "'"), false;
  // The moving part: the first object of [root, path…] after the assembly that is not a
  // document group (UtilsAssembly.getMovingPart); the JCS is relative to the last object
  // before the element (the global placements multiplied along the path).
  std::vector<std::string> names{root};
  for (const std::string& c : path)
    if (objects_.count(c)) names.push_back(c);
  size_t first = 0;
  for (size_t c = 0; c < names.size(); ++c)
    if (types_.count(names[c]) && types_.at(names[c]) == "Assembly::AssemblyObject") first = c + 1;
  Pose global, part_global;
  part->clear();
  for (size_t c = 0; c < names.size(); ++c) {
    global = global * ObjectPlacement(names[c]);
    if (c >= first && part->empty() && IsMovingPart(names[c])) *part = names[c], part_global = global;
  }
  if (part->empty())
    return g_->Error(ref, "Reference" + n + " names no part ('" + root + "." + (text ? text : "") + "')",
                     "attach the joint to a part of the assembly"),
           false;
  Pose jcs;
  if (!PlacementOf(Prop(joint, ("Placement" + n).c_str()), &jcs))
    return g_->Error(place, "the joint has no Placement" + n, "re-create the joint in FreeCAD"), false;
  const std::string name = AddPart(*part, part_global);
  *frame = part_global.Inverse() * global * jcs;  // Offset_k is in Placement_k already
  *part = name;
  return true;
}

void FcReader::ReadJoint(const std::string& object) {
  const XMLElement* e = objects_.at(object);
  const FcJoint* type = JointTypeOf(object);
  if (!type) return;
  const FcJoint& t = *type;
  if (BoolProp(object, "Suppressed", false))
    return g_->Warn(e, "suppressed " + std::string(t.name) + " joint '" + NameOf(object) + "': not imported");
  if (!BoolProp(object, "Activated", true))
    return g_->Warn(
        e, std::string(t.name) + " joint '" + NameOf(object) + "' is not activated (Activated=false): not imported",
        "activate it in FreeCAD to import it");
  if (!t.supported)
    return g_->Error(e, std::string("FreeCAD's ") + t.name + " joint is not supported",
                     std::string("it would need ") + t.needs);
  Joint j;
  j.name = NameOf(object), j.kind = t.kind, j.place = g_->PlaceOf(e);
  if (!Side(object, 1, &j.parent, &j.in_parent) || !Side(object, 2, &j.child, &j.in_child)) return;
  if (j.parent == j.child)
    return g_->Error(e, "both references are on the part '" + j.parent + "'", "attach the joint to two parts");
  const Vec3 z1 = g_->FindLink(j.parent)->world.R * j.in_parent.R.col(2);
  const Vec3 z2 = g_->FindLink(j.child)->world.R * j.in_child.R.col(2);
  if (j.kind != Kind::Spherical && j.kind != Kind::Fixed && z1.dot(z2) < 0) {
    j.in_child.R = j.in_child.R * AxisAngle(Vec3::UnitX(), M_PI);
    g_->Warn(e,
             "the joint's two frames have opposite z axes as saved: the second is turned over (a half turn "
             "about its x) so that both share the axis");
  }
  j.axis = Vec3::UnitZ();
  j.axis2 = Vec3::UnitX();
  g_->AddJoint(std::move(j), e);
}

void FcReader::Read(const XMLElement* document) {
  const XMLElement* objects = document->FirstChildElement("Objects");
  const XMLElement* data = document->FirstChildElement("ObjectData");
  if (!objects || !data) return g_->Error(document, "a FreeCAD Document.xml holds <Objects> and <ObjectData>");
  for (const XMLElement* o = objects->FirstChildElement("Object"); o; o = o->NextSiblingElement("Object"))
    if (o->Attribute("name")) {
      order_.push_back(o->Attribute("name"));
      types_[o->Attribute("name")] = o->Attribute("type") ? o->Attribute("type") : "";
    }
  for (const XMLElement* o = data->FirstChildElement("Object"); o; o = o->NextSiblingElement("Object")) {
    if (!o->Attribute("name")) continue;
    objects_[o->Attribute("name")] = o;
    const XMLElement* ps = o->FirstChildElement("Properties");
    for (const XMLElement* p = ps ? ps->FirstChildElement("Property") : nullptr; p;
         p = p->NextSiblingElement("Property"))
      if (p->Attribute("name")) props_[o->Attribute("name")][p->Attribute("name")] = p;
  }
  g_->AddLink(Link{"ground", Pose{}, std::nullopt, Place{}, true}, nullptr);
  for (const std::string& o : order_) {
    const XMLElement* ground = Prop(o, "ObjectToGround");
    const XMLElement* to = ground ? ground->FirstChildElement("Link") : nullptr;
    if (!ground) continue;
    if (!to || !to->Attribute("value") || !objects_.count(to->Attribute("value"))) {
      g_->Error(ground, "ObjectToGround names no part", "ground a part of the assembly");
      continue;
    }
    Joint fix;
    fix.name = NameOf(o), fix.kind = Kind::Fixed, fix.parent = "ground", fix.place = g_->PlaceOf(objects_.at(o));
    fix.child = AddPart(to->Attribute("value"), ObjectPlacement(to->Attribute("value")));
    g_->AddJoint(std::move(fix), objects_.at(o));
  }
  for (const std::string& o : order_)
    if (objects_.count(o) && Prop(o, "JointType")) ReadJoint(o);
  if (g_->joints.empty())
    g_->Error(document, "the document has no assembly joints", "give a FreeCAD 1.x Assembly file");
}

}  // namespace

void ReadFreeCad(const XMLElement* document, Graph* g) { FcReader(g).Read(document); }

}  // namespace mechkin::importers
