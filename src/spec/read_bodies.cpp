// "bodies": name, position, orientation, inertia, shape.
#include "spec/json_reader.hpp"

namespace mechkin::spec_reader {

namespace {

void ReadEulerParameters(JsonReader& rd, const json& e, const std::string& p, OrientationSpec* out) {
  if (!e.is_array() || e.size() != 4) {
    rd.Error(p, "'euler_parameters' must be an array of 4 numbers [e0, e1, e2, e3] (scalar first)");
    out->ok = false;
    return;
  }
  for (int k = 0; k < 4; ++k) out->euler[k] = rd.ScalarValue(e[k], p + "/" + std::to_string(k), "component");
}

void ReadRotationMatrix(JsonReader& rd, const json& m, const std::string& p, OrientationSpec* out) {
  if (!m.is_array() || m.size() != 3) {
    rd.Error(p, "'matrix' must be 3 rows of 3 numbers");
    out->ok = false;
    return;
  }
  for (int i = 0; i < 3; ++i) {
    if (!m[i].is_array() || m[i].size() != 3) {
      rd.Error(p + "/" + std::to_string(i), "each matrix row must be an array of 3 numbers");
      out->ok = false;
      return;
    }
    for (int j = 0; j < 3; ++j)
      out->matrix[i][j] =
          rd.ScalarValue(m[i][j], p + "/" + std::to_string(i) + "/" + std::to_string(j), "matrix entry");
  }
}

// Orientation forms (format-v1 "orientation").
OrientationSpec ReadOrientation(JsonReader& rd, const json& o, const std::string& ptr) {
  OrientationSpec out;
  out.pointer = ptr;
  if (!o.is_object()) {
    rd.Error(ptr, "'orientation' must be an object, not " + TypeName(o),
             "use {\"axis\": [x,y,z], \"angle\": a}, {\"euler_parameters\": [e0,e1,e2,e3]} or {\"matrix\": "
             "[[..],[..],[..]]}");
    out.ok = false;
    return out;
  }
  rd.CheckObject(o, ptr, {"axis", "angle", "euler_parameters", "matrix"}, {}, "an orientation");
  const int forms = (o.contains("axis") || o.contains("angle")) + o.contains("euler_parameters") + o.contains("matrix");
  if (forms != 1) {
    rd.Error(ptr, forms == 0 ? "orientation gives no form" : "orientation gives more than one form",
             "give exactly one of axis+angle, euler_parameters, matrix");
    out.ok = false;
  } else if (o.contains("axis") || o.contains("angle")) {
    out.form = OrientationSpec::Form::AxisAngle;
    if (!o.contains("axis")) {
      rd.Error(ptr + "/axis", "missing key 'axis' next to 'angle'", "add the rotation axis");
      out.ok = false;
    } else if (!o.contains("angle")) {
      rd.Error(ptr + "/angle", "missing key 'angle' next to 'axis'", "add the rotation angle");
      out.ok = false;
    } else {
      out.axis = *rd.Vector(o, "axis", ptr);
      out.angle = *rd.Number(o, "angle", ptr);
    }
  } else if (o.contains("euler_parameters")) {
    out.form = OrientationSpec::Form::EulerParameters;
    ReadEulerParameters(rd, o.at("euler_parameters"), ptr + "/euler_parameters", &out);
  } else {
    out.form = OrientationSpec::Form::Matrix;
    ReadRotationMatrix(rd, o.at("matrix"), ptr + "/matrix", &out);
  }
  return out;
}

// "inertia": {"mass", "center" (global design coordinates), and "moments"
// (3×3 about the centre, global design axes) or "principal" + "axes"}.
InertiaSpec ReadInertia(JsonReader& rd, const json& in, const std::string& ptr) {
  InertiaSpec out;
  out.pointer = ptr;
  if (!rd.CheckObject(in, ptr, {"mass", "center", "moments", "principal", "axes"}, {"mass", "center"}, "'inertia'")) {
    out.ok = false;
    return out;
  }
  out.mass = rd.Number(in, "mass", ptr);
  out.center = rd.Vector(in, "center", ptr);
  out.has_moments = in.contains("moments");
  out.has_principal = in.contains("principal");
  out.has_axes = in.contains("axes");
  out.moments = rd.Matrix(in, "moments", ptr, &out.moments_error);
  out.principal = rd.Vector(in, "principal", ptr);
  out.axes = rd.Matrix(in, "axes", ptr, &out.axes_error);
  return out;
}

}  // namespace

// In a file whose joints name markers, "position" is an optional starting guess.
void ReadBody(JsonReader& rd, const json& b, const std::string& ptr, bool by_markers, MechanismSpec* spec) {
  const std::vector<std::string> required =
      by_markers ? std::vector<std::string>{"name"} : std::vector<std::string>{"name", "position"};
  if (!rd.CheckObject(b, ptr, {"name", "description", "position", "orientation", "inertia", "shape", "shapes", "markers"},
                      required, "a body"))
    return;
  BodySpec body;
  body.pointer = ptr;
  body.name = rd.Name(b, ptr, "body");
  body.position = rd.Vector(b, "position", ptr);
  if (b.contains("orientation")) body.orientation = ReadOrientation(rd, b.at("orientation"), ptr + "/orientation");
  if (b.contains("shape")) {
    body.shape = ReadShape(rd, b.at("shape"), ptr + "/shape");
    if (!body.shape) body.shape = ShapeSpec{}, body.shape->ok = false, body.shape->pointer = ptr + "/shape";
  }
  if (b.contains("shapes")) body.shapes = ReadShapeList(rd, b.at("shapes"), ptr + "/shapes");
  if (b.contains("markers")) body.markers = ReadMarkers(rd, b.at("markers"), ptr + "/markers");
  if (b.contains("inertia")) body.inertia = ReadInertia(rd, b.at("inertia"), ptr + "/inertia");
  spec->bodies.push_back(std::move(body));
}

}  // namespace mechkin::spec_reader
