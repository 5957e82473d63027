// A spec written as a mechanism file (io/spec_writer.hpp), with convert's number
// rules (tidy decimals, round-off below 1e-13 written as 0) and its layout.
#include "io/spec_writer.hpp"

#include "io/convert_internal.hpp"

namespace mechkin {

namespace {

using convert::Json;

Json Num(const Scalar& s) {
  return s.kind == Scalar::Kind::Number ? convert::Number(s.number, 1) : convert::ScalarJson(s);
}

Json Vec(const Vector3Spec& v) { return Json::array({Num(v.c[0]), Num(v.c[1]), Num(v.c[2])}); }

Json Markers(const std::vector<MarkerSpec>& markers) {
  Json out = Json::object();
  for (const MarkerSpec& m : markers) {
    Json j = Json::object();
    if (m.point) j["point"] = Vec(*m.point);
    if (m.axis) j["axis"] = Vec(*m.axis);
    if (m.x_axis) j["x_axis"] = Vec(*m.x_axis);
    out[m.name] = std::move(j);
  }
  return out;
}

Json Orientation(const OrientationSpec& o) {
  switch (o.form) {
    case OrientationSpec::Form::AxisAngle: return Json{{"axis", Vec(o.axis)}, {"angle", Num(o.angle)}};
    case OrientationSpec::Form::EulerParameters:
      return Json{{"euler_parameters", Json::array({Num(o.euler[0]), Num(o.euler[1]), Num(o.euler[2]), Num(o.euler[3])})}};
    case OrientationSpec::Form::Matrix: break;
  }
  Json rows = Json::array();
  for (const auto& r : o.matrix) rows.push_back(Json::array({Num(r[0]), Num(r[1]), Num(r[2])}));
  return Json{{"matrix", rows}};
}

Json Inertia(const InertiaSpec& in) {
  Json j = Json::object();
  if (in.mass) j["mass"] = convert::ScalarJson(*in.mass);
  if (in.center) j["center"] = Vec(*in.center);
  if (in.moments) {
    Json rows = Json::array();
    for (const Vector3Spec& r : *in.moments) rows.push_back(convert::VectorJson(r));
    j["moments"] = rows;
  }
  if (in.principal) j["principal"] = convert::VectorJson(*in.principal);
  if (in.axes) {
    Json rows = Json::array();
    for (const Vector3Spec& r : *in.axes) rows.push_back(Vec(r));
    j["axes"] = rows;
  }
  return j;
}

Json BodyJson(const BodySpec& b) {
  Json j = Json::object();
  j["name"] = b.name.value_or("");
  if (b.position) j["position"] = Vec(*b.position);
  if (b.orientation) j["orientation"] = Orientation(*b.orientation);
  if (b.inertia) j["inertia"] = Inertia(*b.inertia);
  if (!b.markers.empty()) j["markers"] = Markers(b.markers);
  return j;
}

Json JointJson(const JointSpec& s) {
  Json j = Json::object();
  j["name"] = s.name.value_or("");
  j["type"] = s.type.value_or("");
  j["body1"] = s.body1.value_or("");
  if (s.marker1) j["marker1"] = *s.marker1;
  j["body2"] = s.body2.value_or("");
  if (s.marker2) j["marker2"] = *s.marker2;
  const std::pair<const char*, const std::optional<Vector3Spec>*> geometry[] = {
      {"origin", &s.origin}, {"axis", &s.axis},     {"axis1", &s.axis1},  {"axis2", &s.axis2},
      {"normal", &s.normal}, {"point1", &s.point1}, {"point2", &s.point2}};
  for (const auto& [key, v] : geometry)
    if (*v) j[key] = Vec(**v);
  if (s.pitch) j["pitch"] = Num(*s.pitch);
  if (s.length) j["length"] = Num(*s.length);
  if (s.limits) j["limits"] = Json::array({Num((*s.limits)[0]), Num((*s.limits)[1])});
  return j;
}

Json CouplerJson(const CouplerSpec& c) {
  Json j = Json::object();
  j["name"] = c.name.value_or("");
  j["type"] = c.type.value_or("");
  if (c.joint1) j["joint1"] = *c.joint1;
  if (c.joint2) j["joint2"] = *c.joint2;
  if (!c.joints.empty()) j["joints"] = c.joints;
  if (!c.coefficients.empty()) {
    Json k = Json::array();
    for (const Scalar& s : c.coefficients) k.push_back(Num(s));
    j["coefficients"] = k;
  }
  if (c.constant) j["constant"] = Num(*c.constant);
  if (!c.coordinates.empty()) j["coordinates"] = c.coordinates;
  const std::pair<const char*, const std::optional<Scalar>*> numbers[] = {
      {"ratio", &c.ratio}, {"pitch_radius", &c.pitch_radius}, {"pitch", &c.pitch}, {"pressure_angle", &c.pressure_angle}};
  for (const auto& [key, v] : numbers)
    if (*v) j[key] = Num(**v);
  return j;
}

Json DriverJson(const DriverSpec& d) {
  Json j = Json::object();
  j["name"] = d.name.value_or("");
  j["type"] = d.type.value_or("");
  if (d.joint) j["joint"] = *d.joint;
  if (d.function && d.function->kind == FunctionSpec::Kind::Expression) j["function"] = d.function->text;
  return j;
}

Json UnitsJson(const UnitsSpec& u) {
  Json j = Json::object();
  const std::pair<const char*, const std::optional<std::string>*> keys[] = {
      {"length", &u.length}, {"angle", &u.angle}, {"mass", &u.mass}, {"force", &u.force}, {"torque", &u.torque}};
  for (const auto& [key, v] : keys)
    if (*v) j[key] = **v;
  return j;
}

template <typename T, typename F>
Json List(const std::vector<T>& items, F f) {
  Json a = Json::array();
  for (const T& item : items) a.push_back(f(item));
  return a;
}

}  // namespace

std::string MechanismSpecJson(const MechanismSpec& spec) {
  Json doc = Json::object();
  doc["mechkin"] = 1;
  if (!spec.name.empty()) doc["name"] = spec.name;
  if (!spec.description.empty()) doc["description"] = spec.description;
  if (spec.units) doc["units"] = UnitsJson(*spec.units);
  if (!spec.ground_markers.empty()) doc["ground"] = Json{{"markers", Markers(spec.ground_markers)}};
  doc["bodies"] = List(spec.bodies, BodyJson);
  doc["joints"] = List(spec.joints, JointJson);
  if (!spec.couplers.empty()) doc["couplers"] = List(spec.couplers, CouplerJson);
  if (!spec.drivers.empty()) doc["drivers"] = List(spec.drivers, DriverJson);
  if (spec.analysis && spec.analysis->start && spec.analysis->end && spec.analysis->steps)
    doc["analysis"] = Json{{"start", Num(*spec.analysis->start)},
                           {"end", Num(*spec.analysis->end)},
                           {"steps", Num(*spec.analysis->steps)}};
  return convert::Dump(doc);
}

}  // namespace mechkin
