#include "io/viewer.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "io/output_file.hpp"
#include "io/plot_marks.hpp"
#include "io/table_writer.hpp"

namespace mechkin {

extern const char kViewerJs[];
extern const char kLiveJs[];

namespace {

// Points of each body in body coordinates (SI), and ground's, from the model.
struct ScenePoints {
  std::vector<std::vector<Vec3>> body;
  std::vector<Vec3> ground;
};

void AddPoint(ScenePoints* sp, BodyIndex b, const Vec3& p, double tol) {
  auto& list = b == kGround ? sp->ground : sp->body[b];
  for (const auto& q : list)
    if ((q - p).norm() <= tol) return;
  list.push_back(p);
}

ScenePoints CollectPoints(const Model& m) {
  ScenePoints sp;
  sp.body.resize(m.num_bodies());
  const double tol = 1e-9 * m.characteristic_length;
  for (const Joint& j : m.joints) {
    AddPoint(&sp, j.body1, j.frame1.origin, tol);
    AddPoint(&sp, j.body2, j.frame2.origin, tol);
  }
  for (const Output& o : m.outputs) {
    if (o.kind != OutputKind::Point && o.kind != OutputKind::Distance) continue;
    AddPoint(&sp, o.body1, o.point1, tol);
    if (o.kind == OutputKind::Distance) AddPoint(&sp, o.body2, o.point2, tol);
  }
  for (const Driver& d : m.drivers)
    if (d.kind == DriverKind::Distance) AddPoint(&sp, d.body1, d.point1, tol), AddPoint(&sp, d.body2, d.point2, tol);
  for (const Load& l : m.loads) {
    AddPoint(&sp, l.body1, l.point1, tol);
    if (l.kind == LoadKind::Spring) AddPoint(&sp, l.body2, l.point2, tol);
  }
  for (int b = 0; b < m.num_bodies(); ++b) {
    if (m.bodies[b].inertia) AddPoint(&sp, b, m.bodies[b].inertia->center, tol);
    if (sp.body[b].empty()) sp.body[b].push_back(Vec3::Zero());
  }
  return sp;
}

// Rows shown: all, or max_frames evenly spaced ones (first and last included).
std::vector<int> Frames(int rows, int max_frames) {
  std::vector<int> f;
  if (rows <= max_frames) {
    for (int r = 0; r < rows; ++r) f.push_back(r);
    return f;
  }
  for (int k = 0; k < max_frames; ++k) f.push_back(static_cast<int>(std::llround(double(k) * (rows - 1) / (max_frames - 1))));
  return f;
}

class Json {  // a small writer: the page's data, numbers in shortest round-trip form
 public:
  void Raw(const std::string& s) { out_ += s; }
  void Num(double v) {
    if (!std::isfinite(v)) { out_ += "null"; return; }
    char buf[32];
    out_.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
  }
  void Str(const std::string& s) { out_ += "\"" + JsonEscape(s) + "\""; }
  void Vec(const Vec3& v, double scale) {
    out_ += "[";
    for (int a = 0; a < 3; ++a) { if (a) out_ += ","; Num(v[a] * scale); }
    out_ += "]";
  }
  void Key(const std::string& k) { out_ += "\"" + k + "\":"; }
  const std::string& str() const { return out_; }

 private:
  std::string out_;
};

struct BodyColumns { int x, e0; };

BodyColumns ColumnsOf(const Motion& m, int b) {
  return {m.layout().Find(Quantity::BodyPosition, b, 0, 0), m.layout().Find(Quantity::EulerParameter, b, 0, 0)};
}

// The page draws boxes, cylinders, spheres and triangles: a capsule as the cylinder
// of its whole length, a convex hull as its faces (fans) and a mesh as its triangles.
Shape DrawnShape(const Shape& sh) {
  Shape out = sh;
  if (sh.kind == Shape::Kind::Capsule) {
    out.kind = Shape::Kind::Cylinder;
    out.length = sh.length + 2 * sh.radius;
  } else if (sh.kind == Shape::Kind::Convex) {
    out.kind = Shape::Kind::Mesh;
    for (size_t at = 0; at < sh.faces.size(); at += 1 + sh.faces[at])
      for (int k = 2; k < sh.faces[at]; ++k)
        out.triangles.push_back({sh.faces[at + 1], sh.faces[at + k], sh.faces[at + k + 1]});
  }
  return out;
}

// One shape of the page: {"type": "box" | "cylinder" | "sphere" | "mesh", its sizes,
// "center", "axis"; a mesh's "positions" [x, y, z, …] and "triangles" [i, j, k, …]}.
void WriteShape(const Shape& drawn, double L, Json* j) {
  static const char* kKinds[] = {"box", "cylinder", "sphere", "capsule", "convex", "mesh"};
  const Shape sh = DrawnShape(drawn);
  j->Raw("{"), j->Key("type"), j->Str(kKinds[static_cast<int>(sh.kind)]), j->Raw(",");
  j->Key("size"), j->Vec(sh.size, L), j->Raw(","), j->Key("radius"), j->Num(sh.radius * L), j->Raw(",");
  j->Key("length"), j->Num(sh.length * L), j->Raw(","), j->Key("center"), j->Vec(sh.center, L), j->Raw(",");
  j->Key("axis"), j->Vec(sh.axis, 1);
  if (sh.kind == Shape::Kind::Mesh) {
    j->Raw(","), j->Key("positions"), j->Raw("[");
    for (size_t k = 0; k < sh.points.size(); ++k) {
      for (int a = 0; a < 3; ++a) { if (k || a) j->Raw(","); j->Num(sh.points[k][a] * L); }
    }
    j->Raw("],"), j->Key("triangles"), j->Raw("[");
    for (size_t k = 0; k < sh.triangles.size(); ++k)
      for (int a = 0; a < 3; ++a) { if (k || a) j->Raw(","); j->Num(sh.triangles[k][a]); }
    j->Raw("]");
  }
  j->Raw("}");
}

// A body's (or ground's) clearance shapes: its "shape", then its "shapes".
void WriteShapes(const Model& model, BodyIndex b, const char* key, double L, Json* j) {
  j->Key(key), j->Raw("[");
  const std::vector<const Shape*> shapes = ClearanceShapes(model, b);
  for (size_t k = 0; k < shapes.size(); ++k) {
    if (k) j->Raw(",");
    WriteShape(*shapes[k], L, j);
  }
  j->Raw("]");
}

double Col(const Motion& m, int row, int col, int offset) { return m.at(row, col + offset); }

void WriteBodies(const Model& model, const Motion& m, const ScenePoints& sp, const std::vector<int>& frames, double L, Json* j) {
  const int order = m.layout().options().order;
  j->Key("bodies");
  j->Raw("[");
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyColumns c = ColumnsOf(m, b);
    j->Raw(b ? ",{" : "{");
    j->Key("name"), j->Str(model.bodies[b].name), j->Raw(","), j->Key("points"), j->Raw("[");
    for (size_t k = 0; k < sp.body[b].size(); ++k) { if (k) j->Raw(","); j->Vec(sp.body[b][k], L); }
    j->Raw("],");
    WriteShapes(model, b, "shapes", L, j);
    j->Raw(",");
    j->Key("poses"), j->Raw("[");
    for (size_t f = 0; f < frames.size(); ++f) {
      const int r = frames[f];
      if (f) j->Raw(",");
      // x, y, z (table columns x, x_t.. so y is order+1 further), then q = (e1, e2, e3, e0).
      for (int a = 0; a < 3; ++a) j->Num(Col(m, r, c.x, a * (order + 1))), j->Raw(",");
      for (int a : {1, 2, 3, 0}) { j->Num(Col(m, r, c.e0, a)); if (a) j->Raw(","); }
    }
    j->Raw("]}");
  }
  j->Raw("]");
}

// Joint glyphs: origin and axis in body1 coordinates; a universal's second axis
// (fixed in body2) brought into body1 at the design pose; a distance link's points.
void WriteJoints(const Model& model, double L, Json* j) {
  auto design_A = [&](BodyIndex b) { return b == kGround ? Mat3::Identity() : CalcA(model.bodies[b].euler); };
  j->Key("joints");
  j->Raw("[");
  for (size_t k = 0; k < model.joints.size(); ++k) {
    const Joint& jt = model.joints[k];
    const Vec3 axis2 = design_A(jt.body1).transpose() * (design_A(jt.body2) * jt.frame2.h);
    j->Raw(k ? ",{" : "{");
    j->Key("name"), j->Str(jt.name), j->Raw(","), j->Key("type"), j->Str(jt.type->name), j->Raw(",");
    j->Key("glyph"), j->Str(jt.type->glyph), j->Raw(",");
    j->Key("body1"), j->Num(jt.body1), j->Raw(","), j->Key("body2"), j->Num(jt.body2), j->Raw(",");
    j->Key("origin"), j->Vec(jt.frame1.origin, L), j->Raw(","), j->Key("origin2"), j->Vec(jt.frame2.origin, L), j->Raw(",");
    j->Key("axis"), j->Vec(jt.frame1.h, 1), j->Raw(","), j->Key("axis2"), j->Vec(axis2, 1), j->Raw("}");
  }
  j->Raw("]");
}

// Couplers (constraints.md §3.11): the joints each one ties, drawn as a dashed line
// through the joints' origins.
void WriteCouplers(const Model& model, Json* j) {
  j->Key("couplers");
  j->Raw("[");
  for (size_t k = 0; k < model.couplers.size(); ++k) {
    const Coupler& c = model.couplers[k];
    j->Raw(k ? ",{" : "{");
    j->Key("name"), j->Str(c.name), j->Raw(","), j->Key("type"), j->Str(CouplerKindName(c.kind)), j->Raw(",");
    j->Key("joints"), j->Raw("[");
    for (size_t t = 0; t < c.coordinates.size(); ++t) { if (t) j->Raw(","); j->Num(c.coordinates[t].joint); }
    j->Raw("]}");
  }
  j->Raw("]");
}

// Columns the page can plot: all but Euler parameters (the pose's rotation).
bool Plottable(const ColumnDescriptor& d) { return d.quantity != Quantity::EulerParameter && d.quantity != Quantity::Time; }

void WriteSeries(const Motion& m, const std::vector<int>& frames, Json* j) {
  j->Key("series");
  j->Raw("[");
  bool first = true;
  for (int c = 1; c < m.cols(); ++c) {
    const ColumnDescriptor& d = m.columns()[c];
    if (!Plottable(d)) continue;
    j->Raw(first ? "{" : ",{");
    first = false;
    j->Key("name"), j->Str(d.name), j->Raw(","), j->Key("unit"), j->Str(d.unit), j->Raw(","), j->Key("values"), j->Raw("[");
    for (size_t f = 0; f < frames.size(); ++f) { if (f) j->Raw(","); j->Num(m.at(frames[f], c)); }
    j->Raw("]}");
  }
  j->Raw("]");
}

bool Varies(const Motion& m, int c) {
  for (int r = 1; r < m.rows(); ++r)
    if (std::abs(m.at(r, c) - m.at(0, c)) > 1e-9 * std::max(1.0, std::abs(m.at(0, c)))) return true;
  return false;
}

// Columns (order 0) whose subject is one of `names`; those that vary when any does.
std::vector<int> ColumnsOfSubjects(const Model& model, const Motion& m, const std::vector<std::string>& names, bool bodies) {
  std::vector<int> all, varying;
  for (int c = 1; c < m.cols(); ++c) {
    const ColumnDescriptor& d = m.columns()[c];
    if (!Plottable(d) || d.order != 0 || d.IsDiagnostic() || d.quantity == Quantity::ClearancePoint) continue;
    if (bodies != (d.quantity == Quantity::BodyPosition)) continue;
    if (std::find(names.begin(), names.end(), d.subject) == names.end()) continue;
    all.push_back(c);
    if (Varies(m, c)) varying.push_back(c);
  }
  (void)model;
  return varying.empty() ? all : varying;
}

// What the file is about: its outputs, else its drivers, else the first moving body's position.
std::vector<int> DefaultColumns(const Model& model, const Motion& m) {
  std::vector<std::string> names;
  for (const Output& o : model.outputs) names.push_back(o.name);
  std::vector<int> cols = ColumnsOfSubjects(model, m, names, false);
  if (!cols.empty()) return cols;
  names.clear();
  for (const Driver& d : model.drivers) names.push_back(d.name);
  cols = ColumnsOfSubjects(model, m, names, false);
  for (int b = 0; cols.empty() && b < model.num_bodies(); ++b) {
    cols = ColumnsOfSubjects(model, m, {model.bodies[b].name}, true);
    bool moves = false;
    for (int c : cols) moves = moves || Varies(m, c);
    if (!moves && b + 1 < model.num_bodies()) cols.clear();
  }
  return cols;
}

// Default panels: the default columns grouped by unit, in table order.
std::vector<std::vector<std::string>> DefaultPanels(const Model& model, const Motion& m) {
  std::vector<std::vector<std::string>> panels;
  std::vector<std::string> units;
  for (int c : DefaultColumns(model, m)) {
    const ColumnDescriptor& d = m.columns()[c];
    const auto at = std::find(units.begin(), units.end(), d.unit);
    if (at == units.end()) units.push_back(d.unit), panels.push_back({d.name});
    else panels[at - units.begin()].push_back(d.name);
  }
  return panels;
}

void WritePanels(const std::vector<std::vector<std::string>>& panels, Json* j) {
  j->Key("plots"), j->Raw("[");
  for (size_t p = 0; p < panels.size(); ++p) {
    j->Raw(p ? ",[" : "[");
    for (size_t k = 0; k < panels[p].size(); ++k) { if (k) j->Raw(","); j->Str(panels[p][k]); }
    j->Raw("]");
  }
  j->Raw("]");
}

// Rotation of body b at a row from its Euler parameter columns.
Mat3 RotationAt(const Motion& m, int row, int e0) {
  const Eigen::Quaterniond q(m.at(row, e0), m.at(row, e0 + 1), m.at(row, e0 + 2), m.at(row, e0 + 3));
  return q.normalized().toRotationMatrix();
}

// The box every drawn point stays in over the whole run, and whether every point
// moves in one plane: the second moment of the points' displacements from their
// first positions has a null direction (the plane's normal) while the others do not.
void WriteExtent(const Model& model, const Motion& m, const ScenePoints& sp, const std::vector<int>& frames, double L, Json* j) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  Mat3 moment = Mat3::Zero();
  const int order = m.layout().options().order;
  auto grow = [&](const Vec3& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); };
  for (const Vec3& p : sp.ground) grow(p * L);
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyColumns c = ColumnsOf(m, b);
    std::vector<Vec3> first(sp.body[b].size());
    for (size_t f = 0; f < frames.size(); ++f) {
      const int r = frames[f];
      const Vec3 x(m.at(r, c.x), m.at(r, c.x + order + 1), m.at(r, c.x + 2 * (order + 1)));
      const Mat3 A = RotationAt(m, r, c.e0);
      for (size_t k = 0; k < sp.body[b].size(); ++k) {
        const Vec3 p = x + A * (sp.body[b][k] * L);
        grow(p);
        if (f == 0) first[k] = p;
        moment += (p - first[k]) * (p - first[k]).transpose();
      }
    }
  }
  if (!(lo.x() <= hi.x())) lo = hi = Vec3::Zero();
  j->Key("bounds"), j->Raw("{"), j->Key("lo"), j->Vec(lo, 1), j->Raw(","), j->Key("hi"), j->Vec(hi, 1), j->Raw("},");
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(moment);
  const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);  // ascending
  const bool planar = ev[1] > 0 && std::sqrt(ev[0]) <= 1e-6 * std::sqrt(ev[2]);
  j->Key("planar");
  if (planar) j->Vec(eig.eigenvectors().col(0), 1);
  else j->Raw("null");
}

// Clearance outputs (docs/format.md "Clearance"): per frame the distance and the
// closest points (the table's columns, found by their descriptors), and the located
// first contacts, for the page's marks and its contact highlight.
void WriteClearances(const Model& model, const Motion& m, const std::vector<int>& frames, double L, Json* j) {
  j->Key("clearances"), j->Raw("[");
  bool first = true;
  for (size_t o = 0; o < model.outputs.size(); ++o) {
    const Output& out = model.outputs[o];
    const int d = m.layout().Find(Quantity::Clearance, static_cast<int>(o), -1, 0);
    std::array<int, 6> p{};
    for (int c = 0; c < 6; ++c) p[c] = m.layout().Find(Quantity::ClearancePoint, static_cast<int>(o), c, 0);
    if (out.kind != OutputKind::Clearance || d < 0 || *std::min_element(p.begin(), p.end()) < 0) continue;
    j->Raw(first ? "{" : ",{");
    first = false;
    j->Key("name"), j->Str(out.name), j->Raw(","), j->Key("body1"), j->Num(out.body1), j->Raw(",");
    j->Key("body2"), j->Num(out.body2), j->Raw(","), j->Key("distance"), j->Raw("[");
    for (size_t f = 0; f < frames.size(); ++f) { if (f) j->Raw(","); j->Num(m.at(frames[f], d)); }
    j->Raw("],"), j->Key("points"), j->Raw("[");
    for (size_t f = 0; f < frames.size(); ++f)
      for (int c = 0; c < 6; ++c) { if (f || c) j->Raw(","); j->Num(m.at(frames[f], p[c])); }
    j->Raw("],"), j->Key("contacts"), j->Raw("[");
    bool first_hit = true;
    for (const ContactHit& hit : m.report.contacts) {
      if (hit.output != static_cast<int>(o)) continue;
      j->Raw(first_hit ? "{" : ",{");
      first_hit = false;
      j->Key("t"), j->Num(hit.t), j->Raw(","), j->Key("point"), j->Vec(hit.point, L), j->Raw("}");
    }
    j->Raw("]}");
  }
  j->Raw("]");
}

// Times every plot marks (io/plot_marks.hpp).
void WriteMarks(const Model& model, const Motion& m, Json* j) {
  j->Key("marks"), j->Raw("[");
  bool first = true;
  for (const PlotMark& mark : PlotMarks(model, m)) {
    j->Raw(first ? "{" : ",{");
    first = false;
    j->Key("t"), j->Num(mark.t), j->Raw(","), j->Key("kind"), j->Str(mark.kind), j->Raw(","), j->Key("label");
    j->Str(mark.label), j->Raw("}");
  }
  j->Raw("]");
}

// The page's up direction: the option (--up), else the file's "view", else against
// gravity, else y.
Vec3 UpOf(const Model& model, const SceneOptions& o) {
  if (o.up) return o.up->normalized();
  if (model.view.up) return *model.view.up;
  return model.gravity.norm() > 0 ? Vec3(-model.gravity.normalized()) : Vec3::UnitY();
}

// Distance drivers (a Stewart platform's legs): drawn as lines between their points,
// as distance joints are; and ground's points, drawn as fixed pivots.
void WriteLinksAndGround(const Model& model, const ScenePoints& sp, double L, Json* j) {
  j->Key("links"), j->Raw("[");
  bool first = true;
  for (const Driver& d : model.drivers)
    if (d.kind == DriverKind::Distance) {
      j->Raw(first ? "{" : ",{");
      first = false;
      j->Key("name"), j->Str(d.name), j->Raw(","), j->Key("body1"), j->Num(d.body1), j->Raw(","), j->Key("origin"), j->Vec(d.point1, L), j->Raw(",");
      j->Key("body2"), j->Num(d.body2), j->Raw(","), j->Key("origin2"), j->Vec(d.point2, L), j->Raw("}");
    }
  j->Raw("],"), j->Key("ground"), j->Raw("[");
  for (size_t k = 0; k < sp.ground.size(); ++k) { if (k) j->Raw(","); j->Vec(sp.ground[k], L); }
  j->Raw("]");
}

void WriteTraces(const Model& model, double L, Json* j) {
  j->Key("traces"), j->Raw("[");
  bool first = true;
  for (const Output& out : model.outputs)
    if (out.kind == OutputKind::Point) {
      j->Raw(first ? "{" : ",{");
      first = false;
      j->Key("name"), j->Str(out.name), j->Raw(","), j->Key("body"), j->Num(out.body1), j->Raw(","), j->Key("point"), j->Vec(out.point1, L), j->Raw("}");
    }
  j->Raw("]");
}

std::string SceneData(const Model& model, const Motion& m, const SceneOptions& o) {
  const ScenePoints sp = CollectPoints(model);
  const std::vector<int> frames = Frames(m.rows(), std::max(2, o.max_frames));
  const double L = m.layout().length_factor();  // SI → table length unit
  Json j;
  j.Raw("{"), j.Key("name"), j.Str(model.name), j.Raw(","), j.Key("size"), j.Num(model.characteristic_length * L), j.Raw(",");
  Vec3 center = Vec3::Zero();
  for (const Body& b : model.bodies) center += b.position / std::max(1, model.num_bodies());
  j.Key("center"), j.Vec(center, L), j.Raw(","), j.Key("up"), j.Vec(UpOf(model, o), 1), j.Raw(",");
  WriteExtent(model, m, sp, frames, L, &j);
  j.Raw(","), j.Key("times"), j.Raw("[");
  for (size_t f = 0; f < frames.size(); ++f) { if (f) j.Raw(","); j.Num(m.at(frames[f], 0)); }
  j.Raw("],");
  WriteBodies(model, m, sp, frames, L, &j);
  j.Raw(",");
  WriteJoints(model, L, &j);
  j.Raw(",");
  WriteCouplers(model, &j);
  j.Raw(",");
  WriteTraces(model, L, &j);
  j.Raw(",");
  WriteLinksAndGround(model, sp, L, &j);
  j.Raw(",");
  WriteShapes(model, kGround, "ground_shapes", L, &j);
  j.Raw(",");
  WriteSeries(m, frames, &j);
  j.Raw(",");
  WritePanels(!o.plots.empty() ? o.plots : !model.view.plots.empty() ? model.view.plots : DefaultPanels(model, m), &j);
  const double stop_t = StopTime(m);
  j.Raw(",");
  WriteMarks(model, m, &j);
  j.Raw(",");
  WriteClearances(model, m, frames, L, &j);
  j.Raw(","), j.Key("stop"), j.Raw("{"), j.Key("complete"), j.Raw(m.complete ? "true" : "false"), j.Raw(",");
  j.Key("t"), j.Num(stop_t), j.Raw(","), j.Key("message"), j.Str(m.stop.Summary()), j.Raw("},");
  j.Key("paused"), j.Raw(model.view.paused ? "true" : "false"), j.Raw("}");
  return j.str();
}

bool ReadText(const std::string& path, std::string* out) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  std::stringstream s;
  s << f.rdbuf();
  *out = s.str();
  return true;
}

// </script> must not end the inline script early.
std::string ScriptSafe(std::string s) {
  for (size_t at = 0; (at = s.find("</", at)) != std::string::npos; at += 3) s.replace(at, 2, "<\\/");
  return s;
}

// The scene's JSON inside its <script>: every '<' (only inside JSON strings) as
// \u003c, so no text of the file ("</script>", "<!--<script>", which puts the HTML
// parser in its double-escaped state where the script's own end tag no longer ends
// it) reaches the parser as markup.
std::string JsonScriptSafe(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (char c : json) {
    if (c == '<') out += "\\u003c";
    else out += c;
  }
  return out;
}

const char kPageHead[] = R"HTML(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width">
<title>)HTML";

const char kPageStyle[] = R"HTML(</title>
<style>
body{margin:0;font:13px sans-serif;display:grid;grid-template-columns:1fr 560px;grid-template-rows:auto 1fr auto;height:100vh;overflow:hidden}
#bar{grid-column:1/3;padding:5px 6px;background:#333;color:#eee;display:flex;gap:6px;align-items:center;flex-wrap:wrap}
#bar input[type=range]{width:200px} #bar a{color:#9cf} #view{position:relative;min-height:0;grid-row:2/4}
#panels{overflow:hidden;padding:2px 6px 0 6px;border-left:1px solid #ccc;min-height:0}
.panel>div{text-align:right;font-size:11px;height:14px} .panel a{color:#06c} #chooser{padding:4px 6px;border-left:1px solid #ccc;font-size:12px}
#columns{width:540px;height:64px} #label{position:fixed;background:#fff;border:1px solid #999;padding:2px 4px;pointer-events:none}
#status{color:#f66} #contact{color:#fa4} #export{display:none} #label:empty{display:none}
</style></head><body>
<div id="bar"><b id="title"></b><button id="play">play</button><input id="time" type="range" min="0" max="1000" value="0">
<span id="clock"></span> speed <select id="speed"><option>0.1</option><option>0.25</option><option selected>1</option><option>2</option><option>5</option></select>
<label><input id="loop" type="checkbox" checked> loop</label>
<button id="fit" title="fit the whole motion (a)">fit</button><button id="v-front" title="front view (f)">front</button>
<button id="v-side" title="side view (s)">side</button><button id="v-top" title="top view (t)">top</button><button id="v-iso" title="isometric view (i)">iso</button>
<label title="orthographic projection (o)"><input id="ortho" type="checkbox"> ortho</label>
<label><input id="traces" type="checkbox" checked> paths</label><label><input id="labels" type="checkbox" checked> labels</label>
<a id="csv" href="#" title="the page's table (as decimated for the page)">table CSV</a>
<span id="contact"></span><span id="status"></span></div>
<div id="view"></div>
<div id="panels"></div>
<div id="chooser">plotted columns (ctrl-click for several; one panel per unit):<br><select id="columns" multiple></select>
<br>against: <select id="xaxis"></select></div><div id="label"></div><pre id="export"></pre>
)HTML";

}  // namespace

bool CheckPlots(const Motion& motion, const std::vector<std::vector<std::string>>& panels, const std::string& where,
                std::string* error) {
  std::vector<std::string> names;
  for (const ColumnDescriptor& d : motion.columns())
    if (Plottable(d)) names.push_back(d.name);
  for (const auto& panel : panels)
    for (const std::string& name : panel)
      if (std::find(names.begin(), names.end(), name) == names.end()) {
        std::string choices;
        for (const auto& n : names) choices += (choices.empty() ? "" : ", ") + n;
        *error = where + ": no column '" + name + "'; the columns are: " + choices;
        return false;
      }
  return true;
}

bool ParsePlots(const Motion& motion, const std::string& spec, std::vector<std::vector<std::string>>* panels,
                std::string* error) {
  panels->clear();
  std::stringstream groups(spec);
  for (std::string group; std::getline(groups, group, ';');) {
    std::vector<std::string> panel;
    std::stringstream items(group);
    for (std::string name; std::getline(items, name, ',');) {
      name.erase(0, name.find_first_not_of(" \t"));
      name.erase(name.find_last_not_of(" \t") + 1);
      if (!name.empty()) panel.push_back(name);
    }
    if (!panel.empty()) panels->push_back(panel);
  }
  if (panels->empty()) {
    *error = "--plots: no column given; write names separated by ',' within a plot and ';' between plots";
    return false;
  }
  return CheckPlots(motion, *panels, "--plots", error);
}

std::string DefaultThreeJsDir() {
  const char* env = std::getenv("MECHKIN_THREE_JS_DIR");
  return env && *env ? env : "/usr/share/javascript/three";
}

bool WriteViewerHtml(const Model& model, const Motion& motion, const SceneOptions& options, OutputFile* page,
                     std::string* error) {
  const std::string dir = options.three_js_dir.empty() ? DefaultThreeJsDir() : options.three_js_dir;
  std::string three, orbit;
  if (!ReadText(dir + "/three.min.js", &three) || !ReadText(dir + "/examples/js/controls/OrbitControls.js", &orbit)) {
    *error = "three.js not found in " + dir + ": install Debian's libjs-three (apt-get install libjs-three)";
    page->Abort();
    return false;
  }
  if (options.plots.empty() && !CheckPlots(motion, model.view.plots, "/view/plots", error)) {
    page->Abort();
    return false;
  }
  OutputFile& file = *page;
  file.Write(kPageHead);
  file.Write(XmlEscape("mechkin: " + (model.name.empty() ? model.source : model.name)));
  file.Write(kPageStyle);
  // Errors anywhere on the page (also inside three.js) are collected for the tests and the status line.
  file.Write("<script>window.MECHKIN_ERRORS=[];window.addEventListener('error',function(e){MECHKIN_ERRORS.push(e.message);});"
             "(function(){var f=console.error;console.error=function(){MECHKIN_ERRORS.push(Array.prototype.join.call(arguments,' '));"
             "f.apply(console,arguments);};})();</script>\n");
  file.Write("<script>" + ScriptSafe(three) + "</script>\n<script>" + ScriptSafe(orbit) + "</script>\n");
  file.Write("<script>window.MECHKIN_DATA=" + JsonScriptSafe(SceneData(model, motion, options)) + ";</script>\n");
  file.Write("<script>document.getElementById('title').textContent=window.MECHKIN_DATA.name;</script>\n");
  file.Write("<script>" + ScriptSafe(kViewerJs) + "</script>\n");
  if (!options.live_module.empty()) {  // the live page: the module, the file and the sliders' program
    file.Write("<script>" + ScriptSafe(options.live_module) + "</script>\n");
    file.Write("<script>window.MECHKIN_LIVE=" + JsonScriptSafe(options.live_data) + ";</script>\n");
    file.Write("<script>" + ScriptSafe(kLiveJs) + "</script>\n");
  }
  file.Write("</body></html>\n");
  return file.Commit("", error);
}

}  // namespace mechkin
