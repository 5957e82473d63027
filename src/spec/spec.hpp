// The spec layer: plain structs mirroring a format-v1 mechanism file (docs/format.md).
//
// A spec is what the file says, in the file's units and by name: numbers that
// may be parameter expressions stay unresolved (Scalar), bodies are referenced
// by name, nothing is converted. Compile (src/model/compile.hpp) turns a spec
// and parameter overrides into a Model; every variant of a sweep, a tolerance
// study or `with_parameters` compiles the same spec, never the file text again.
// Every element keeps its JSON pointer so that compile's diagnostics name it.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mechkin {

/// A number of the file: a literal, an expression over the parameters, or a value
/// the reader found unusable (its error is reported when the number is compiled,
/// so that the diagnostics keep the file's order).
struct Scalar {
  enum class Kind { Number, Expression, Invalid };
  Kind kind = Kind::Number;
  double number = 0;
  std::string text;     // Expression: its text; Invalid: the error message
  std::string fix;      // Invalid: how to fix it
  std::string pointer;  // JSON pointer of the value

  static Scalar Of(double value, std::string pointer = "") {
    Scalar s;
    s.number = value;
    s.pointer = std::move(pointer);
    return s;
  }
  static Scalar Expr(std::string text, std::string pointer = "") {
    Scalar s;
    s.kind = Kind::Expression;
    s.text = std::move(text);
    s.pointer = std::move(pointer);
    return s;
  }
};

/// [x, y, z] of Scalars. `error` non-empty: the value was not 3 numbers (reported at compile).
struct Vector3Spec {
  std::array<Scalar, 3> c;
  std::string key;      // the key naming it in messages ("axis", "row", ...)
  std::string pointer;
  std::string error;

  static Vector3Spec Of(double x, double y, double z, std::string key = "", std::string pointer = "");
};

/// "orientation": one of axis+angle, euler_parameters, matrix.
struct OrientationSpec {
  enum class Form { AxisAngle, EulerParameters, Matrix };
  Form form = Form::AxisAngle;
  Vector3Spec axis;
  Scalar angle;
  std::array<Scalar, 4> euler;
  std::array<std::array<Scalar, 3>, 3> matrix;
  std::string pointer;
  bool ok = true;  // false: the reader reported a structural error
};

/// "inertia": mass, centre (global design coordinates), moments or principal + axes.
struct InertiaSpec {
  std::optional<Scalar> mass;
  std::optional<Vector3Spec> center, principal;
  std::optional<std::array<Vector3Spec, 3>> moments, axes;  // rows
  std::string moments_error, axes_error;  // "'moments' must be 3 rows of 3 numbers"
  bool has_moments = false, has_principal = false, has_axes = false;
  std::string pointer;
  bool ok = true;
};

/// The triangles of a mesh shape's file (spec/mesh_file.hpp), as the file gives
/// them: its own numbers, before "scale" and the file's length unit.
struct MeshSpec {
  std::string path;  // as opened (the mechanism file's folder joined with "file")
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;  // indices into vertices
};

/// "shape" (drawn, and measured by clearance outputs) or an element of "shapes":
/// box, cylinder, sphere, capsule (radius, length, axis), convex (the hull of
/// "points") or mesh (the triangles of an STL or OBJ "file"), in the body's coordinates.
struct ShapeSpec {
  std::optional<std::string> type;
  std::optional<Vector3Spec> center, size, axis;
  std::optional<Scalar> radius, length;
  std::vector<Vector3Spec> points;  // convex
  std::string points_error;         // convex: "'points' must be an array of [x, y, z]"
  std::optional<std::string> file;  // mesh: the file's name as written (relative to the mechanism file)
  std::optional<Scalar> scale;      // mesh: file numbers → the mechanism file's length unit (default 1)
  std::shared_ptr<const MeshSpec> mesh;  // mesh: read by the reader (nullptr: none, or reported)
  std::string pointer;
  bool ok = true;
};

/// A named frame fixed in a body, in the body's coordinates (file units): "point",
/// "axis" (the frame's z; default the body's z) and "x_axis" (fixes the frame's x;
/// default the body's x made normal to the axis).
struct MarkerSpec {
  std::string name;
  std::optional<Vector3Spec> point, axis, x_axis;
  std::string pointer;
};

struct BodySpec {
  std::optional<std::string> name;  // nullopt: missing or invalid (reported)
  std::optional<Vector3Spec> position;
  std::optional<OrientationSpec> orientation;
  std::optional<InertiaSpec> inertia;
  std::optional<ShapeSpec> shape;
  std::vector<ShapeSpec> shapes;  // "shapes": more clearance geometry (docs/format.md "Clearance")
  std::vector<MarkerSpec> markers;
  std::string pointer;
};

struct JointSpec {
  std::optional<std::string> name;
  std::optional<std::string> type;   // a known joint type name, or nullopt (reported)
  std::optional<std::string> body1, body2;
  std::optional<Vector3Spec> origin, axis, axis1, axis2, normal, point1, point2;
  std::optional<Scalar> pitch, length;
  std::optional<std::string> marker1, marker2;  // markers of body1 and body2 instead of global geometry
  // "limits": [lo, hi] of a revolute or screw joint's angle, a prismatic or cylindrical
  // joint's slide (file units, from the design pose or the markers' coincidence).
  std::optional<std::array<Scalar, 2>> limits;
  bool geometry_complete = true;     // every required geometry key is present
  std::string pointer;
};

/// A coupler between joint coordinates ("couplers", docs/format.md): gear, belt,
/// rack_pinion, screw_coupling (joint1, joint2 and ratio / pitch_radius / pitch) or
/// coupling (joints, coefficients, constant, optional coordinates).
struct CouplerSpec {
  std::optional<std::string> name, type;
  std::optional<std::string> joint1, joint2;
  std::vector<std::string> joints, coordinates;  // coupling
  std::vector<Scalar> coefficients;              // coupling
  std::optional<Scalar> ratio, pitch_radius, pitch, constant;
  std::optional<Scalar> pressure_angle;  // gear with pitch_radius (file angle unit)
  std::string pointer;
  bool ok = true;  // false: the reader reported a structural error
};

/// A function of time: an expression in t or a table of (t, value) rows.
struct FunctionSpec {
  enum class Kind { Expression, Table, Invalid };
  Kind kind = Kind::Expression;
  std::string text;  // Expression
  std::vector<double> times, values;  // Table
  std::string interpolation = "quintic";
  std::string pointer;
};

struct DriverSpec {
  std::optional<std::string> name, type;  // type: rotation, translation, distance, coordinate, angle
  bool by_body = false;                   // rotation of a body about an axis
  std::optional<std::string> joint, body, body1, body2, axis_body;
  std::optional<Vector3Spec> axis, point, point1, point2, about, vector;
  std::optional<FunctionSpec> function;
  std::string pointer;
};

struct OutputSpec {
  std::optional<std::string> name, type;
  std::optional<std::string> body, frame, joint, body1, body2, output, input, relative_to, sequence, marker;
  std::optional<std::string> value;  // "expression": the text over earlier outputs, parameters and t
  std::optional<std::string> of, reduce;  // "reduction": the output reduced and how (min max rms mean at)
  std::optional<Scalar> t;                // "reduction" "at": the time (s)
  // "reduction" "sse": "of" as an array of columns (empty: "of" is one column, a string).
  std::vector<std::string> of_columns;
  // "reduction" "sse": {"t": [t_i], "values": [v_i] or [[v_i1 … v_iK]]}, the target of
  // each column at each time, in the column's file unit.
  struct Targets {
    std::vector<double> t;
    std::vector<std::vector<double>> values;  // one row per t, one value per column
  };
  std::optional<Targets> targets;
  std::optional<Vector3Spec> point, point1, point2, vector1, vector2, about;
  std::string pointer;
};

struct LoadSpec {
  std::optional<std::string> name;
  std::string type;  // force, torque, spring
  std::optional<std::string> body, body1, body2, frame;
  std::optional<Vector3Spec> point, point1, point2;
  std::optional<std::array<FunctionSpec, 3>> components;
  std::string components_error;
  std::optional<Scalar> stiffness, free_length, damping, preload;
  std::string pointer;
};

struct ParameterSpec {
  std::string name;
  std::optional<Scalar> value;  // nullopt: the object form lacks "value" (reported)
  std::optional<double> tolerance, min, max;
};

struct BranchSpec {
  std::vector<std::pair<std::string, Scalar>> joints;  // joint name, approximate coordinate
  std::vector<std::pair<std::string, std::string>> flip;  // joint name, its JSON pointer: the other closure there
};

struct AnalysisSpec {
  std::optional<Scalar> start, end, steps;
  std::optional<BranchSpec> branch;
  bool ok = true;
};

struct UnitsSpec {
  std::optional<std::string> length, angle, mass;
  std::optional<std::string> force, torque;  // named force and torque units (default: derived)
};

struct ExpectSpec {
  std::optional<Scalar> grubler, mobility, redundant, idle;
  std::optional<std::string> driven;
  std::optional<Scalar> min_clearance;  // file length units: `check` sweeps the clearances
  // "min": {output: v}, "max": {output: v}: bounds on a column over the run (its units), keys in file order
  std::vector<std::pair<std::string, Scalar>> min, max;
};

/// "view": how `mechkin view` shows the file (the motion does not depend on it).
struct ViewSpec {
  std::optional<std::string> up;                 // "x", "y" or "z" (checked by the reader)
  std::vector<std::vector<std::string>> plots;   // panels of column names; empty: the defaults
  bool paused = false;                           // open still instead of playing
};

struct MechanismSpec {
  std::optional<Scalar> version;  // "mechkin"
  std::string name, description;
  std::string source;             // the file name (or "inline")
  std::optional<UnitsSpec> units;
  std::vector<ParameterSpec> parameters;
  std::vector<MarkerSpec> ground_markers;  // "ground": {"markers": {...}}, global coordinates
  std::vector<ShapeSpec> ground_shapes;    // "ground": {"shapes": [...]}, global coordinates
  std::vector<BodySpec> bodies;
  std::vector<JointSpec> joints;
  std::vector<CouplerSpec> couplers;
  std::vector<DriverSpec> drivers;
  std::optional<AnalysisSpec> analysis;
  std::vector<OutputSpec> outputs;
  std::optional<ExpectSpec> expect;
  std::optional<Vector3Spec> gravity;
  std::vector<LoadSpec> loads;
  std::optional<ViewSpec> view;
  /// Some joint names "marker1"/"marker2": bodies' positions are then optional
  /// starting guesses (a sketch), and compile places the bodies from the markers.
  bool UsesMarkers() const {
    for (const JointSpec& j : joints)
      if (j.marker1 || j.marker2) return true;
    return false;
  }
  /// False when the reader reported errors: compile then reports the values'
  /// errors too but builds no model.
  bool valid = true;
};

}  // namespace mechkin
