// The graph → MechanismSpec (docs/import.md "What the written file holds"):
//  * links joined by fixed joints (a chain of them, or a loop closed by one) are one
//    rigid body, named after its first link in the file (ground for the fixed frame's);
//  * every other joint is a joint on two markers named after it, at its frame in each
//    body with the marker's z along the joint axis: the joint coordinate is 0 where
//    the markers coincide — the file's own zero (URDF q = 0, MJCF qpos0 = ref);
//  * bodies keep their written poses as the assembly's starting guess, so a loop
//    written open (a loop joint's two frames apart) is closed by mechkin's assembly;
//  * units m, rad, kg (the formats' own).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "importers/graph.hpp"

namespace mechkin::importers {

namespace {

const char* const kTypeName[] = {"revolute", "prismatic", "cylindrical", "screw", "universal", "spherical", "planar",
                                 "fixed"};

struct Groups {
  std::vector<size_t> parent;
  size_t Find(size_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
};

// A name mechkin accepts (1-64 letters, digits, '_', '-', a letter or '_' first), unique in `taken`.
std::string Legal(const std::string& raw, std::set<std::string>* taken) {
  std::string s;
  for (char c : raw) s += std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ? c : '_';
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) s = "_" + s;
  if (s.size() > 60) s.resize(60);
  std::string unique = s;
  for (int k = 2; taken->count(unique); ++k) unique = s + "_" + std::to_string(k);
  taken->insert(unique);
  return unique;
}

Vector3Spec V(const Vec3& v, const std::string& key, const std::string& pointer) {
  return Vector3Spec::Of(v.x(), v.y(), v.z(), key, pointer + "/" + key);
}

class Builder {
 public:
  Builder(const Graph& g, const ImportOptions& o, ImportResult* r) : g_(g), options_(o), result_(r) {}
  void Run();

 private:
  void Group();
  void Bodies();
  void AddInertia(size_t body, const Link& link);
  std::string Marker(size_t group, const std::string& joint, const Pose& frame_in_link, size_t link, const Vec3& z,
                     const Vec3& x);
  void Joints();
  void Couplings();
  void Drivers();
  void Error(const Place& at, const std::string& msg, const std::string& fix = "") {
    result_->errors.push_back({g_.file(), at.line, at.element, msg, fix});
  }

  const Graph& g_;
  const ImportOptions& options_;
  ImportResult* result_;
  MechanismSpec spec_;
  Groups groups_;
  std::map<std::string, size_t> link_;   // link name → index
  std::map<size_t, int> body_of_root_;   // group root → body index (-1: ground)
  std::vector<Pose> body_world_;         // per body
  std::map<std::string, std::string> joint_name_;  // file joint name → spec joint name
  std::map<std::string, Kind> joint_kind_;
  std::set<std::string> body_names_{"ground"}, joint_names_;
  std::vector<std::set<std::string>> marker_names_;  // per body; ground's last
  std::set<std::string> ground_marker_names_;
};

void Builder::Group() {
  groups_.parent.resize(g_.links.size());
  for (size_t i = 0; i < g_.links.size(); ++i) groups_.parent[i] = i, link_[g_.links[i].name] = i;
  for (const Joint& j : g_.joints) {
    if (j.kind != Kind::Fixed) continue;
    const size_t a = groups_.Find(link_.at(j.parent)), b = groups_.Find(link_.at(j.child));
    // The ground's group keeps a ground link as its root; otherwise the earlier link.
    const bool b_first = g_.links[b].ground || (!g_.links[a].ground && b < a);
    if (a != b) groups_.parent[b_first ? a : b] = b_first ? b : a;
  }
  for (size_t i = 0; i < g_.links.size(); ++i)
    if (g_.links[i].ground && groups_.Find(i) != i && !g_.links[groups_.Find(i)].ground)
      groups_.parent[groups_.Find(i)] = i;
}

void Builder::Bodies() {
  for (size_t i = 0; i < g_.links.size(); ++i) {
    const size_t root = groups_.Find(i);
    if (root != i) continue;
    const Link& l = g_.links[i];
    if (l.ground) {
      body_of_root_[root] = -1;
      continue;
    }
    BodySpec b;
    const std::string ptr = "/bodies/" + std::to_string(spec_.bodies.size());
    b.name = Legal(l.name, &body_names_);
    b.pointer = ptr;
    b.position = V(l.world.p, "position", ptr);
    OrientationSpec o;
    o.form = OrientationSpec::Form::Matrix;
    o.pointer = ptr + "/orientation";
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) o.matrix[r][c] = Scalar::Of(l.world.R(r, c), o.pointer + "/matrix");
    b.orientation = o;
    result_->origins[ptr] = ImportMessage{g_.file(), l.place.line, l.place.element, "", ""}.Place();
    body_of_root_[root] = static_cast<int>(spec_.bodies.size());
    spec_.bodies.push_back(std::move(b));
    body_world_.push_back(l.world);
  }
  marker_names_.resize(spec_.bodies.size());
  for (size_t i = 0; i < g_.links.size(); ++i) {
    const int body = body_of_root_.at(groups_.Find(i));
    if (body >= 0 && g_.links[i].inertia) AddInertia(static_cast<size_t>(body), g_.links[i]);
  }
}

// Adds a link's mass properties to its body's (global design coordinates, summed about the joint centre).
void Builder::AddInertia(size_t body, const Link& link) {
  const LinkInertia& in = *link.inertia;
  const Pose frame = link.world * in.frame;
  const Mat3 I = frame.R * in.moments * frame.R.transpose();
  BodySpec& b = spec_.bodies[body];
  double m0 = 0;
  Vec3 c0 = Vec3::Zero();
  Mat3 I0 = Mat3::Zero();
  if (b.inertia) {
    m0 = b.inertia->mass->number;
    for (int k = 0; k < 3; ++k) c0[k] = b.inertia->center->c[k].number;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) I0(r, c) = (*b.inertia->moments)[r].c[c].number;
  }
  const double m = m0 + in.mass;
  const Vec3 c = m > 0 ? Vec3((m0 * c0 + in.mass * frame.p) / m) : frame.p;
  auto shift = [&](double mass, const Vec3& d) { return Mat3(mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose())); };
  const Mat3 total = I0 + shift(m0, c0 - c) + I + shift(in.mass, frame.p - c);
  InertiaSpec s;
  s.pointer = b.pointer + "/inertia";
  s.mass = Scalar::Of(m, s.pointer + "/mass");
  s.center = V(c, "center", s.pointer);
  s.has_moments = true;
  std::array<Vector3Spec, 3> rows;
  for (int r = 0; r < 3; ++r) rows[r] = V(Vec3(total.row(r).transpose()), "moments", s.pointer);
  s.moments = rows;
  b.inertia = s;
}

// A marker on the link's body at the joint frame, its z along `z` and x along `x` (joint-frame directions).
std::string Builder::Marker(size_t group, const std::string& joint, const Pose& frame_in_link, size_t link,
                            const Vec3& z, const Vec3& x) {
  const int body = body_of_root_.at(group);
  const Pose world = g_.links[link].world * frame_in_link;
  const Pose in_body = body < 0 ? world : body_world_[body].Inverse() * world;
  std::set<std::string>& taken = body < 0 ? ground_marker_names_ : marker_names_[body];
  MarkerSpec m;
  m.name = Legal(joint, &taken);
  const std::string base = body < 0 ? "/ground/markers/" : "/bodies/" + std::to_string(body) + "/markers/";
  m.pointer = base + m.name;
  m.point = V(in_body.p, "point", m.pointer);
  m.axis = V(in_body.R * z, "axis", m.pointer);
  m.x_axis = V(in_body.R * x, "x_axis", m.pointer);
  (body < 0 ? spec_.ground_markers : spec_.bodies[body].markers).push_back(m);
  return m.name;
}

void Builder::Joints() {
  for (const Joint& j : g_.joints) {
    if (j.kind == Kind::Fixed) continue;
    const size_t pl = link_.at(j.parent), cl = link_.at(j.child);
    const size_t a = groups_.Find(pl), b = groups_.Find(cl);
    if (a == b) {
      Error(j.place, "the joint joins '" + j.parent + "' and '" + j.child +
                         "', which fixed joints (or welds) already make one rigid body",
            "remove the joint or the fixed connection that duplicates it");
      continue;
    }
    const std::string ptr = "/joints/" + std::to_string(spec_.joints.size());
    JointSpec s;
    s.name = Legal(j.name, &joint_names_);
    joint_name_[j.name] = *s.name;
    joint_kind_[j.name] = j.kind;
    s.type = kTypeName[static_cast<int>(j.kind)];
    s.pointer = ptr;
    const int b1 = body_of_root_.at(a), b2 = body_of_root_.at(b);
    s.body1 = b1 < 0 ? "ground" : *spec_.bodies[b1].name;
    s.body2 = b2 < 0 ? "ground" : *spec_.bodies[b2].name;
    const Mat3 align = ZTo(j.axis);
    const bool cross = j.kind == Kind::Universal;
    const Vec3 x1 = cross ? j.axis2 : Vec3(align.col(0)), z2 = cross ? j.axis2 : j.axis;
    s.marker1 = Marker(a, *s.name, j.in_parent, pl, j.axis, x1);
    s.marker2 = Marker(b, *s.name, j.in_child, cl, z2, cross ? j.axis : x1);
    if (j.kind == Kind::Screw) s.pitch = Scalar::Of(j.pitch, ptr + "/pitch");
    if (j.limits)
      s.limits = std::array<Scalar, 2>{Scalar::Of((*j.limits)[0], ptr + "/limits/0"),
                                       Scalar::Of((*j.limits)[1], ptr + "/limits/1")};
    result_->origins[ptr] = ImportMessage{g_.file(), j.place.line, j.place.element, "", ""}.Place();
    spec_.joints.push_back(std::move(s));
  }
}

void Builder::Couplings() {
  std::set<std::string> names;
  for (const Coupling& c : g_.couplings) {
    CouplerSpec s;
    const std::string ptr = "/couplers/" + std::to_string(spec_.couplers.size());
    s.name = Legal(c.name, &names);
    s.type = "coupling";
    s.pointer = ptr;
    bool ok = true;
    for (const std::string& j : c.joints) {
      auto it = joint_name_.find(j);
      if (it == joint_name_.end()) {
        Error(c.place, "the coupling names joint '" + j + "', which is not a moving joint of the file",
              "name a revolute or prismatic joint");
        ok = false;
        continue;
      }
      s.joints.push_back(it->second);
    }
    for (double k : c.coefficients) s.coefficients.push_back(Scalar::Of(k, ptr + "/coefficients"));
    s.constant = Scalar::Of(c.constant, ptr + "/constant");
    result_->origins[ptr] = ImportMessage{g_.file(), c.place.line, c.place.element, "", ""}.Place();
    if (ok) spec_.couplers.push_back(std::move(s));
  }
}

void Builder::Drivers() {
  for (const auto& [joint, function] : options_.drives) {
    auto it = joint_name_.find(joint);
    const Place cli{0, "--drive " + joint};
    if (it == joint_name_.end()) {
      Error(cli, "no moving joint named '" + joint + "' in the file", "name one of the file's joints");
      continue;
    }
    const Kind k = joint_kind_.at(joint);
    if (k != Kind::Revolute && k != Kind::Prismatic && k != Kind::Cylindrical && k != Kind::Screw) {
      Error(cli, "joint '" + joint + "' has no single coordinate to drive", "drive a revolute or prismatic joint");
      continue;
    }
    DriverSpec d;
    d.pointer = "/drivers/" + std::to_string(spec_.drivers.size());
    d.name = "drive_" + it->second;
    d.type = k == Kind::Prismatic ? "translation" : "rotation";
    d.joint = it->second;
    FunctionSpec f;
    f.text = function;
    f.pointer = d.pointer + "/function";
    d.function = f;
    spec_.drivers.push_back(std::move(d));
  }
  if (options_.drives.empty() && !options_.span_given) return;
  AnalysisSpec a;
  a.start = Scalar::Of(options_.start, "/analysis/start");
  a.end = Scalar::Of(options_.end, "/analysis/end");
  a.steps = Scalar::Of(options_.steps, "/analysis/steps");
  spec_.analysis = a;
}

void Builder::Run() {
  spec_.version = Scalar::Of(1, "/mechkin");
  spec_.name = g_.name;
  spec_.description = g_.description;
  spec_.source = g_.file();
  spec_.units = UnitsSpec{std::string("m"), std::string("rad"), std::string("kg"), std::nullopt, std::nullopt};
  Group();
  Bodies();
  Joints();
  Couplings();
  Drivers();
  if (result_->errors.empty()) result_->spec = std::move(spec_);
}

}  // namespace

void BuildSpec(const Graph& graph, const ImportOptions& options, ImportResult* result) {
  Builder(graph, options, result).Run();
}

}  // namespace mechkin::importers
