#include "io/viewer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "io/output_file.hpp"
#include "io/table_writer.hpp"

namespace mechkin {

extern const char kViewerJs[];

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
    if (const auto& sh = model.bodies[b].shape) {
      static const char* kKinds[] = {"box", "cylinder", "sphere"};
      j->Key("shape"), j->Raw("{"), j->Key("type"), j->Str(kKinds[static_cast<int>(sh->kind)]), j->Raw(",");
      j->Key("size"), j->Vec(sh->size, L), j->Raw(","), j->Key("radius"), j->Num(sh->radius * L), j->Raw(",");
      j->Key("length"), j->Num(sh->length * L), j->Raw(","), j->Key("center"), j->Vec(sh->center, L), j->Raw(",");
      j->Key("axis"), j->Vec(sh->axis, 1), j->Raw("},");
    }
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
    j->Key("name"), j->Str(jt.name), j->Raw(","), j->Key("type"), j->Str(JointTypeName(jt.type)), j->Raw(",");
    j->Key("body1"), j->Num(jt.body1), j->Raw(","), j->Key("body2"), j->Num(jt.body2), j->Raw(",");
    j->Key("origin"), j->Vec(jt.frame1.origin, L), j->Raw(","), j->Key("origin2"), j->Vec(jt.frame2.origin, L), j->Raw(",");
    j->Key("axis"), j->Vec(jt.frame1.h, 1), j->Raw(","), j->Key("axis2"), j->Vec(axis2, 1), j->Raw("}");
  }
  j->Raw("]");
}

void WriteSeries(const Motion& m, const std::vector<int>& frames, Json* j) {
  j->Key("series");
  j->Raw("[");
  bool first = true, any_default = false;
  for (int c = 1; c < m.cols(); ++c) {
    const ColumnDescriptor& d = m.columns()[c];
    if (d.quantity == Quantity::EulerParameter) continue;
    const bool by_default = (d.order == 0 && (d.quantity == Quantity::PointPosition || d.quantity == Quantity::JointAngle || d.quantity == Quantity::Angle ||
                                              d.quantity == Quantity::JointSlide || d.quantity == Quantity::Distance ||
                                              d.quantity == Quantity::DriverEffort));
    any_default = any_default || by_default;
    j->Raw(first ? "{" : ",{");
    first = false;
    j->Key("name"), j->Str(d.name), j->Raw(","), j->Key("unit"), j->Str(d.unit), j->Raw(",");
    j->Key("default"), j->Raw(by_default || (!any_default && c == 1) ? "true" : "false"), j->Raw(","), j->Key("values"), j->Raw("[");
    for (size_t f = 0; f < frames.size(); ++f) { if (f) j->Raw(","); j->Num(m.at(frames[f], c)); }
    j->Raw("]}");
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
  double floor = 0;
  for (const Body& b : model.bodies) center += b.position / std::max(1, model.num_bodies()), floor = std::min(floor, b.position.y());
  j.Key("center"), j.Vec(center, L), j.Raw(","), j.Key("floor"), j.Num((floor - 0.5 * model.characteristic_length) * L), j.Raw(",");
  j.Key("times"), j.Raw("[");
  for (size_t f = 0; f < frames.size(); ++f) { if (f) j.Raw(","); j.Num(m.at(frames[f], 0)); }
  j.Raw("],");
  WriteBodies(model, m, sp, frames, L, &j);
  j.Raw(",");
  WriteJoints(model, L, &j);
  j.Raw(","), j.Key("traces"), j.Raw("[");
  bool first = true;
  for (const Output& out : model.outputs)
    if (out.kind == OutputKind::Point) {
      j.Raw(first ? "{" : ",{");
      first = false;
      j.Key("name"), j.Str(out.name), j.Raw(","), j.Key("body"), j.Num(out.body1), j.Raw(","), j.Key("point"), j.Vec(out.point1, L), j.Raw("}");
    }
  j.Raw("],");
  WriteSeries(m, frames, &j);
  const double stop_t = m.stop.singular ? m.stop.singular->t : (m.rows() ? m.at(m.rows() - 1, 0) : 0);
  j.Raw(","), j.Key("marks");
  if (m.complete) {
    j.Raw("[]");
  } else {
    j.Raw("[{\"t\":");
    j.Num(stop_t);
    j.Raw("}]");
  }
  j.Raw(","), j.Key("stop"), j.Raw("{"), j.Key("complete"), j.Raw(m.complete ? "true" : "false"), j.Raw(",");
  j.Key("t"), j.Num(stop_t), j.Raw(","), j.Key("message"), j.Str(m.stop.Summary()), j.Raw("}}");
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

const char kPageHead[] = R"HTML(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width">
<title>)HTML";

const char kPageStyle[] = R"HTML(</title>
<style>
body{margin:0;font:13px sans-serif;display:grid;grid-template-columns:1fr 500px;grid-template-rows:auto 1fr;height:100vh}
#bar{grid-column:1/3;padding:6px;background:#333;color:#eee;display:flex;gap:8px;align-items:center;flex-wrap:wrap}
#bar input[type=range]{width:240px} #view{position:relative;min-height:0} #side{overflow:auto;padding:6px;border-left:1px solid #ccc}
#columns{width:480px;height:140px} #label{position:fixed;background:#fff;border:1px solid #999;padding:2px 4px;pointer-events:none}
#status{color:#f66}
</style></head><body>
<div id="bar"><b id="title"></b><button id="play">play</button><input id="time" type="range" min="0" max="1000" value="0">
<span id="clock"></span> speed <select id="speed"><option>0.1</option><option>0.25</option><option selected>1</option><option>2</option><option>5</option></select>
<label><input id="loop" type="checkbox" checked> loop</label><button id="reset">reset view</button>
<label><input id="traces" type="checkbox" checked> traces</label><label><input id="labels" type="checkbox" checked> labels</label>
<span id="status"></span></div>
<div id="view"></div>
<div id="side"><div>columns (ctrl-click for several):</div><select id="columns" multiple></select>
<div>against: <select id="xaxis"></select></div><svg id="plot" width="480" height="260"></svg></div><div id="label"></div>
)HTML";

}  // namespace

std::string DefaultThreeJsDir() {
  const char* env = std::getenv("MECHKIN_THREE_JS_DIR");
  return env && *env ? env : "/usr/share/javascript/three";
}

bool WriteViewerHtml(const Model& model, const Motion& motion, const SceneOptions& options, const std::string& path,
                     std::string* error) {
  const std::string dir = options.three_js_dir.empty() ? DefaultThreeJsDir() : options.three_js_dir;
  std::string three, orbit;
  if (!ReadText(dir + "/three.min.js", &three) || !ReadText(dir + "/examples/js/controls/OrbitControls.js", &orbit)) {
    *error = "three.js not found in " + dir + ": install Debian's libjs-three (apt-get install libjs-three)";
    return false;
  }
  OutputFile file;
  if (!file.Open(path, {}, error)) return false;
  file.Write(kPageHead);
  file.Write(XmlEscape("mechkin: " + (model.name.empty() ? model.source : model.name)));
  file.Write(kPageStyle);
  // Errors anywhere on the page (also inside three.js) are collected for the tests and the status line.
  file.Write("<script>window.MECHKIN_ERRORS=[];window.addEventListener('error',function(e){MECHKIN_ERRORS.push(e.message);});"
             "(function(){var f=console.error;console.error=function(){MECHKIN_ERRORS.push(Array.prototype.join.call(arguments,' '));"
             "f.apply(console,arguments);};})();</script>\n");
  file.Write("<script>" + ScriptSafe(three) + "</script>\n<script>" + ScriptSafe(orbit) + "</script>\n");
  file.Write("<script>window.MECHKIN_DATA=" + ScriptSafe(SceneData(model, motion, options)) + ";</script>\n");
  file.Write("<script>document.getElementById('title').textContent=window.MECHKIN_DATA.name;</script>\n");
  file.Write("<script>" + ScriptSafe(kViewerJs) + "</script>\n</body></html>\n");
  return file.Commit("", error);
}

}  // namespace mechkin
