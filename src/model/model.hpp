// The immutable mechanism model, compiled once from a format-v1 file.
//
// Frames: "global" is ground. Body k has origin r_k and Euler parameters p_k at
// the design configuration. Primed (local) quantities are body-frame components;
// for ground, local == global. Everything is SI (m, rad, s).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "joints/descriptor.hpp"
#include "math/rotation.hpp"
#include "model/time_function.hpp"
#include "model/units.hpp"

namespace mechkin {

struct MechanismSpec;  // spec/spec.hpp: what the file says (a model keeps it for its variants)
class ExpressionCache;  // model/expression_cache.hpp: the spec's expressions, parsed once

/// Index of a moving body in Model::bodies, or kGround.
using BodyIndex = int;
constexpr BodyIndex kGround = -1;

/// Mass properties of a body (SI), in body coordinates.
struct Inertia {
  double mass = 0;
  Vec3 center = Vec3::Zero();      // centre of mass s'_c (body frame)
  Mat3 moments = Mat3::Zero();     // inertia tensor J'_c about the centre (body axes)
};

/// Geometry of a body, in body coordinates (SI): the drawing's `shape` and what
/// clearance outputs measure (docs/format.md "Clearance").
struct Shape {
  enum class Kind { Box, Cylinder, Sphere, Capsule, Convex, Mesh } kind = Kind::Box;
  Vec3 size = Vec3::Zero();    // box: edge lengths along the body axes
  double radius = 0, length = 0;  // cylinder, capsule (along `axis`; length between the caps' centres), sphere
  Vec3 center = Vec3::Zero(), axis = Vec3::UnitZ();
  // Convex: the hull's vertices (relative to `center`) and its faces, each as
  // [n, i0, …, i(n−1)] counter-clockwise seen from outside (math/convex_hull.hpp).
  // Mesh: `points` are its vertices (relative to `center`) and `triangles` index them
  // (the file's triangles, scaled; its surface is what clearance measures).
  std::vector<Vec3> points;
  std::vector<int> faces;
  int num_faces = 0;
  std::vector<std::array<int, 3>> triangles;
};

struct Body {
  std::string name;
  Vec3 position;  // r at the design configuration (global, m)
  Vec4 euler;     // p at the design configuration (unit, scalar first)
  std::optional<Inertia> inertia;
  std::optional<Shape> shape;
  std::vector<Shape> shapes;  // "shapes": clearance geometry besides `shape`
};

enum class LoadKind { Force, Torque, Spring };

/// An applied load (SI). Force: on `body1` at `point1`; torque: on `body1`;
/// components are functions of t, in global axes or (in_body_axes) body1's.
/// Spring-damper: between point1 on body1 and point2 on body2; tension
/// k (L − L0) + c L̇ + preload pulls the points together.
struct Load {
  std::string name;
  LoadKind kind = LoadKind::Force;
  BodyIndex body1 = kGround, body2 = kGround;
  Vec3 point1 = Vec3::Zero(), point2 = Vec3::Zero();  // local points
  std::array<TimeFunction, 3> components;
  bool in_body_axes = false;
  double stiffness = 0, free_length = 0, damping = 0, preload = 0;
};

/// Joint definition frame fixed in one body (constraints.md §4): origin s' and
/// orthonormal axes f', g', h' in that body's frame.
struct JointFrame {
  Vec3 origin = Vec3::Zero();
  Vec3 f = Vec3::UnitX(), g = Vec3::UnitY(), h = Vec3::UnitZ();
};

struct Joint {
  std::string name;
  // The joint's type (joints/registry.hpp): every layer reads what it needs from it.
  const JointDescriptor* type = nullptr;
  BodyIndex body1 = kGround, body2 = kGround;
  JointFrame frame1, frame2;  // local frames on body1 and body2 (coincide globally at design)
  double pitch = 0;           // screw: metres per revolution (right-handed positive)
  double length = 0;          // distance: link length (m)
  // Defined on two markers: its frames are the markers' (not the design pose's), so
  // its coordinate is 0 where the markers coincide, whatever the pose drawn.
  bool on_markers = false;
  // [lo, hi] (SI) of the angle (revolute, screw) or slide (prismatic, cylindrical),
  // from the coordinate's zero; a run that reaches one stops there (analysis/joint_limits.hpp).
  std::optional<std::pair<double, double>> limits;
};

enum class CouplerKind { Gear, Belt, RackPinion, ScrewCoupling, Coupling };

/// One joint coordinate a coupler reads: the joint's rotation (rad) or slide (m),
/// 0 at the design pose (a joint on markers: where its markers coincide).
struct CouplerCoordinate {
  int joint = -1;
  bool rotation = true;
  double coefficient = 1;  // c_k of the general coupling (SI: per rad, per m)
};

/// A gear pair's mesh on bearings in one frame body (constraints.md §3.11.1), from a
/// gear's `pitch_radius`: where and along which line the tooth force acts, in the
/// frame body's coordinates (constant there).
struct GearMesh {
  BodyIndex frame = kGround;    // body1 of both revolute joints
  double pitch_radius = 0;      // ρ₁ (m), gear 1's
  double tan_pressure = 0;      // tan φ
  Vec3 axis = Vec3::UnitZ();    // h₁' (joint1's axis): Q₁ turns gear 1 about it
  Vec3 radial = Vec3::UnitX();  // e', unit, from joint1's axis to the pitch point
  // +1: gear 1's teeth are internal (the ring), the radial part pushes it outwards;
  // −1: external teeth, pushed towards its own axis.
  double radial_sign = -1;
  double axial_offset = 0;      // a = (O₁ − O₂)ᵀh₁' (m): joint2's origin off the pitch plane
};

/// A coupler between joint coordinates (docs/format.md "couplers", constraints.md
/// §3.11): one equation Σ c_k q_k = c_0 (SI).
struct Coupler {
  std::string name;
  CouplerKind kind = CouplerKind::Gear;
  std::vector<CouplerCoordinate> coordinates;  // 2 (3 for a coupling)
  // gear, belt: the ratio r (θ₂ = r θ₁); rack_pinion: the pitch radius (m);
  // screw_coupling: the pitch (m per turn). Unused by a coupling.
  double ratio = 0;
  double constant = 0;  // c_0 of a coupling (SI, after the scaling of §3.11)
  std::optional<GearMesh> mesh;  // gear with `pitch_radius`: the tooth force enters the reactions
};

enum class DriverKind { JointRotation, BodyRotation, JointTranslation, Distance };

struct Driver {
  std::string name;
  DriverKind kind;
  int joint = -1;                    // JointRotation / JointTranslation
  BodyIndex body1 = kGround, body2 = kGround;
  JointFrame frame1, frame2;         // frames of the driven coordinate (joint or body/ground)
  Vec3 point1 = Vec3::Zero(), point2 = Vec3::Zero();  // Distance: local points
  TimeFunction function;             // SI value: rad or m
  // BodyRotation between two bodies no revolute keeps aligned (an `angle` driver):
  // the general rotation driver's right-hand sides (constraints/families.hpp AngleDriver).
  bool general_angle = false;
};

enum class OutputKind { Point, JointCoordinate, Distance, Angle, VelocityRatio, Orientation, Clearance, Expression };

/// One column an expression output reads: an earlier output (`component` 0..2 of a
/// point output, 0 for a single-valued one).
struct ExpressionInput {
  int output = -1;
  int component = 0;
};

struct Output {
  std::string name;
  OutputKind kind;
  BodyIndex body1 = kGround, body2 = kGround;
  Vec3 point1 = Vec3::Zero(), point2 = Vec3::Zero();  // local points
  int joint = -1;
  // Angle: unit vectors fixed in body1 and body2 (local); with `signed_about`, the
  // angle from vector1 to vector2 about `about` (unit, fixed in body1, local).
  Vec3 vector1 = Vec3::UnitX(), vector2 = Vec3::UnitX(), about = Vec3::UnitZ();
  bool signed_about = false;
  // Point: the body whose frame the coordinates are in (ground: global).
  BodyIndex frame = kGround;
  // VelocityRatio: d(outputs[ratio_of])/d(input), the input an output or a driver.
  int ratio_of = -1, ratio_input_output = -1, ratio_input_driver = -1;
  // Orientation (and a spherical joint's output): body2 relative to body1; "XYZ" …
  // "ZYX", "ZXZ" … (intrinsic rotation sequences), "axis-angle" or "euler-parameters".
  std::string sequence;
  // Expression: the text parsed with the parameters as constants (file units) and
  // slot k reading inputs[k] in the file's units (docs/format.md "Expression outputs").
  std::shared_ptr<const Expression> expression;
  std::vector<ExpressionInput> inputs;
};

/// Rows a run computes at most (steps + 1): the file's /analysis/steps and every
/// front end that replaces the span (Python run(steps=)) stop here.
constexpr int kMaxSteps = 10000000;
/// What is wrong with a span, or "" when it is valid: one message for the file's
/// /analysis and Python's run(start=, end=, steps=) ("'steps' is larger than 10,000,000").
std::string SpanProblem(double start, double end, double steps);

struct Analysis {
  double start = 0, end = 1;
  int steps = 100;
  // "branch": {"joints": {J: value}}: approximate joint coordinates (SI; from the
  // design pose, or for a joint on markers from their coincidence) of the assembly
  // branch wanted, at the drivers' design values.
  std::vector<std::pair<int, double>> branch_joints;
  // "branch": {"flip": [J, ...]}: take the other closure of the loop at each joint
  // (the nearest assembly whose coordinate of J differs).
  std::vector<int> branch_flips;
};

/// One loop of a file placed by its markers: a joint outside the spanning tree
/// and the tree joints of the path it closes.
struct AssemblyLoop {
  int joint = -1;          // the joint closing the loop
  std::vector<int> path;   // tree joints from body1 of `joint` to body2, in order
  // Largest miss of the loop's joints (m; an angle miss counts as L·angle), at the
  // starting pose (tree placement or sketch) and after the assembly.
  double error_before = 0, error_after = 0;
};

/// How compile (the spanning tree) and the assembly (analysis/assemble_model.hpp:
/// the loop closures) placed the bodies of a file whose joints name markers.
struct AssemblyRecord {
  std::vector<int> tree_joint;   // per body: the joint that placed it (-1: none, a root)
  std::vector<bool> sketched;    // per body: its position was given (the starting guess)
  std::vector<Vec3> guess_position;  // per body: the starting pose (sketch or tree placement)
  std::vector<Vec4> guess_euler;
  std::vector<AssemblyLoop> loops;
  int iterations = 0;             // Newton iterations of the closure (all loops at once)
  bool assembled = false;         // the loops were closed (the model's poses are the closed ones)
};

/// A named number of the file ("parameters"), in the units of the places that use it.
struct Parameter {
  std::string name;
  double value = 0;
  std::string expression;              // non-empty when defined from other parameters
  std::optional<double> tolerance;     // ± band (tolerance stack-up)
  std::optional<double> min, max;      // sweep range (--samples)
  bool overridden = false;             // value set by --set / with_parameters
};

/// A column an output contributes (a reduction's `of`, an `expect` bound's key), as an
/// expression reads it.
using OutputColumn = ExpressionInput;

/// `expect: {"min": {name: v}}` (the column's minimum over the run ≥ v) or "max" (≤ v),
/// v in the column's unit in the file's units (docs/format.md "Assertions on the motion").
struct MotionBound {
  std::string key;  // the output name as written ("tip.x")
  OutputColumn column;
  bool is_min = true;
  double value = 0;
};

struct Expect {
  std::optional<int> grubler, mobility, redundant, idle;
  std::optional<std::string> driven;  // "full", "under", "over"
  std::optional<double> min_clearance;  // m: every clearance along the motion at least this
  std::vector<MotionBound> bounds;      // "min" then "max", each in file order
};

enum class ReduceKind { Min, Max, Rms, Mean, At, Sse };

/// {"type": "reduction", "of", "reduce", "t"}: one number per run from a column
/// (docs/format.md "Reductions"; computed by analysis/reduction.hpp).
struct Reduction {
  std::string name;
  std::string of;  // the column's output name as written ("transmission", "tip.x")
  OutputColumn column;
  ReduceKind kind = ReduceKind::Min;
  double t = 0;  // At: the time (s)
  // Sse (docs/format.md "Targets"): the columns (`column` is the first), their names as
  // written, and the targets: per time target_t[i] one value per column (file units).
  std::vector<OutputColumn> columns;
  std::vector<std::string> column_names;
  std::vector<double> target_t;
  std::vector<std::vector<double>> target_values;
};

/// How `mechkin view` shows the model (the file's "view"; no effect on the motion).
struct ViewSettings {
  std::optional<Vec3> up;                        // drawn upwards (unit); nullopt: from gravity or --up
  std::vector<std::vector<std::string>> plots;   // panels of column names; empty: the defaults
  bool paused = false;                           // the page opens still
};

struct Model {
  std::string name, description, source;
  Units units;
  std::vector<Body> bodies;  // moving bodies only
  std::vector<Shape> ground_shapes;  // "ground": {"shapes"}: clearance geometry of the frame (global)
  std::vector<Joint> joints;
  std::vector<Coupler> couplers;  // between joint coordinates, after the joints in Φ
  std::vector<Driver> drivers;
  std::vector<Output> outputs;
  std::vector<Reduction> reductions;  // "reduction" outputs: per run, not per row
  Vec3 gravity = Vec3::Zero();  // m/s²
  std::vector<Load> loads;
  /// Inertia or loads given: the run also computes driver efforts and reactions.
  bool HasForces() const;
  std::optional<Analysis> analysis;
  Expect expect;
  ViewSettings view;
  double characteristic_length = 1.0;  // m; scale for every length tolerance
  std::vector<Parameter> parameters;
  /// What the file says (shared by every variant), to compile variants with other
  /// parameter values; the model keeps no file text.
  std::shared_ptr<const MechanismSpec> spec;
  /// The spec's expressions parsed once, for compiling its variants without parsing.
  std::shared_ptr<const ExpressionCache> expressions;
  /// Set for a file whose joints name markers: the bodies were placed from them.
  std::optional<AssemblyRecord> assembly;

  const Parameter* FindParameter(const std::string& name) const;

  int num_bodies() const { return static_cast<int>(bodies.size()); }
  std::string BodyName(BodyIndex b) const { return b == kGround ? "ground" : bodies[b].name; }
};

/// A driver whose value is an angle (rotation of a joint, of a body, or between bodies).
inline bool IsAngleDriver(const Driver& d) {
  return d.kind == DriverKind::JointRotation || d.kind == DriverKind::BodyRotation;
}

/// "gear", "belt", "rack_pinion", "screw_coupling", "coupling" (the file's words).
const char* CouplerKindName(CouplerKind kind);

}  // namespace mechkin
