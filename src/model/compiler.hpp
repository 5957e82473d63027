// Internal to src/model: the compile step's state, one section per method
// (compile.cpp: values, header, parameters, units, analysis, expect, gravity;
// compile_bodies.cpp; compile_joints.cpp (joints, drivers); compile_outputs.cpp
// (outputs, loads, functions); compile_checks.cpp (the warning passes)).
//
// A failed element is known by name (index -2) so that references to it do not
// produce a second, misleading error; a failed parameter likewise silences the
// expressions that use it.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "model/compile.hpp"
#include "model/expression_cache.hpp"
#include "model/frames.hpp"

namespace mechkin {

class Compiler {
 public:
  /// `expressions`: the spec's parsed expressions from an earlier compile, or null
  /// (this compile records them).
  Compiler(const MechanismSpec& spec, const ParameterOverrides& overrides, DiagnosticLog* out,
           std::shared_ptr<const ExpressionCache> expressions);
  /// Every section, then (when nothing failed) the warning passes.
  std::optional<Model> Run();

 private:
  void Error(const std::string& ptr, const std::string& msg, const std::string& fix = "") { out_.Error(ptr, msg, fix); }
  void Warn(const std::string& ptr, const std::string& msg, const std::string& fix = "") { out_.Warn(ptr, msg, fix); }
  void Place(Section section, const std::string& element_pointer);

  // Values (compile.cpp).
  std::optional<double> Value(const Scalar& s);
  std::optional<double> Value(const std::optional<Scalar>& s) { return s ? Value(*s) : std::nullopt; }
  std::optional<double> ConstantExpression(const std::string& text, const std::string& p);
  std::string UnknownNameFix(const ExpressionError& err) const;
  bool UsesFailedParameter(const std::string& text) const;
  std::optional<double> CachedConstant(const std::string& text);
  std::shared_ptr<const Expression> CachedTimeFunction(const std::string& text);
  const std::vector<std::string>& NamesUsed(const std::string& text);
  void SetParameterValue(const std::string& name, double value);
  std::optional<int> Integer(const std::optional<Scalar>& s, const std::string& key);
  std::optional<Vec3> Vector(const std::optional<Vector3Spec>& v, bool nonzero);
  std::optional<Vec3> VectorValue(const Vector3Spec& v, bool nonzero);
  std::optional<Vec3> LengthVector(const std::optional<Vector3Spec>& v);
  std::optional<BodyIndex> BodyRef(const std::optional<std::string>& name, const std::string& key,
                                   const std::string& ptr);

  // Sections (compile.cpp).
  void CompileHeader();
  void CompileParameters();
  void ResolveParameters(const std::vector<size_t>& pending);
  bool ResolveParameter(const ParameterSpec& ps);
  void ReportCycles(const std::vector<size_t>& pending, const std::vector<size_t>& remaining,
                    const std::vector<std::vector<size_t>>& deps);
  void CompileUnits();
  void CompileAnalysis();
  void CompileBranch(const BranchSpec& b, Analysis* an);
  std::optional<int> BranchJoint(const std::string& name, const std::string& pointer);
  void CompileExpect();
  void CompileGravity();
  void CompileView();

  // Bodies (compile_bodies.cpp).
  void CompileBody(const BodySpec& b);
  std::optional<Vec4> CompileOrientation(const OrientationSpec& o);
  std::optional<Vec4> CompileRotationMatrix(const OrientationSpec& o);
  std::optional<Inertia> CompileInertia(const InertiaSpec& in, const Vec3& r, const Vec4& euler);
  std::optional<Mat3> CompileMatrix(const std::optional<std::array<Vector3Spec, 3>>& rows, const std::string& error,
                                    const std::string& ptr);
  std::optional<Mat3> CompilePrincipal(const InertiaSpec& in);
  bool CheckInertiaTensor(const Mat3& J, const std::string& ptr);

  // Shapes (compile_shapes.cpp).
  std::optional<Shape> CompileShape(const ShapeSpec& o);
  std::vector<Shape> CompileShapes(const std::vector<ShapeSpec>& shapes);
  bool CompileRoundShape(const ShapeSpec& o, Shape* sh);
  bool CompileConvex(const ShapeSpec& o, Shape* sh);
  bool CompileMesh(const ShapeSpec& o, Shape* sh);

  // Markers (compile_markers.cpp).
  void CompileMarkers(BodyIndex body, const std::vector<MarkerSpec>& markers);
  std::optional<JointFrame> Marker(BodyIndex body, const std::optional<std::string>& name, const std::string& ptr);
  void CompileMarkerJoint(const JointSpec& j, const JointDescriptor& type, const std::string* name, std::optional<BodyIndex> body1,
                          std::optional<BodyIndex> body2);
  /// Ground, or a body whose position the file gives.
  bool HasFilePose(BodyIndex b) const { return b == kGround || sketched_[b]; }

  // Placement by markers (compile_placement.cpp): the spanning tree.
  void PlaceByMarkers();
  void PlaceChild(int joint, BodyIndex parent);

  // Joints and drivers (compile_joints.cpp).
  void CompileJoint(const JointSpec& j);
  void CompileJointGeometry(const JointSpec& j, const JointDescriptor& type, const std::string* name, BodyIndex body1,
                            BodyIndex body2);
  bool CompileScrewPitch(const JointSpec& j, Joint* joint);
  bool CompileDistanceLength(const JointSpec& j, const Vec3& p1, const Vec3& p2, bool ok, const char* point2_key,
                             Joint* joint);
  void AddJoint(const std::string& name, const std::optional<Vec3>& origin, const std::optional<Vec3>& axis,
                const std::optional<Vec3>& axis1, const std::optional<Vec3>& axis2,
                const std::optional<Vec3>& normal, const std::optional<Vec3>& p1, const std::optional<Vec3>& p2,
                Joint* joint);
  void CompileJointLimits(const JointSpec& j);
  void SetBothFrames(const JointFrame& global, Joint* joint);
  void CompileDriver(const DriverSpec& d);
  bool DriverOnBody(const DriverSpec& d, Driver* drv);
  bool DriverOnJoint(const DriverSpec& d, bool rotation, Driver* drv);
  bool DriverOnCoordinate(const DriverSpec& d, Driver* drv);
  bool DriverOnAngle(const DriverSpec& d, Driver* drv);
  bool DriverBetweenPoints(const DriverSpec& d, Driver* drv);
  std::optional<int> FindJoint(const std::optional<std::string>& name, const std::string& ptr, bool did_you_mean);

  // Couplers (compile_couplers.cpp).
  void CompileCoupler(const CouplerSpec& c);
  bool CompileCoupling(const CouplerSpec& c, Coupler* cp);
  std::optional<int> CouplerJoint(const std::string& name, const std::string& ptr);
  std::optional<CouplerCoordinate> CouplerTerm(const std::string& name, const std::string& ptr,
                                               std::optional<bool> rotation, const std::string& type);
  std::optional<double> CouplerFactor(const std::optional<Scalar>& s, const std::string& key, const std::string& ptr,
                                      double unit);
  std::optional<GearMesh> CompileGearMesh(const CouplerSpec& c, const Coupler& cp);
  bool GearMeshJoints(const std::string& ptr, const Joint& j1, const Joint& j2);

  // Outputs, loads, functions (compile_outputs.cpp).
  std::optional<TimeFunction> CompileFunction(const FunctionSpec& f, double scale);
  std::optional<TimeFunction> CompileTable(const FunctionSpec& f, double scale);
  void CompileOutput(const OutputSpec& o);
  bool CheckOutputName(const std::string& name, const std::string& ptr);
  bool CompileExpressionOutput(const OutputSpec& o, Output* out);
  bool ResolveExpressionName(const std::string& name, const std::string& ptr, ExpressionInput* in);
  void UnknownExpressionName(const std::string& name, const std::string& ptr);
  bool ResolveColumnName(const std::string& name, const std::string& ptr, const std::string& what, OutputColumn* in);
  void CompileReduction(const OutputSpec& o);
  bool CompileTargets(const OutputSpec& o, Reduction* r);
  bool TimeInRun(double t, const std::string& ptr);
  void CompileBounds(const std::vector<std::pair<std::string, Scalar>>& bounds, bool is_min);
  std::vector<const OutputSpec*> pending_reductions_;
  bool CompileOutputGeometry(const OutputSpec& o, Output* out);
  bool CompileJointOutput(const OutputSpec& o, Output* out);
  bool CompileVelocityRatio(const OutputSpec& o, Output* out);
  bool IsScalarOutput(const Output& o) const;
  bool CompileOrientationOutput(const OutputSpec& o, Output* out);
  bool CompileSequence(const OutputSpec& o, Output* out);
  bool CompileAngleOutput(const OutputSpec& o, Output* out);
  // Clearance outputs (compile_shapes.cpp).
  std::optional<std::string> DefaultOutputName(const OutputSpec& o) const;
  bool CompileClearanceOutput(const OutputSpec& o, Output* out);
  void CompileLoad(const LoadSpec& o);
  bool CompileForceOrTorque(const LoadSpec& o, bool force, Load* load);
  bool CompileSpring(const LoadSpec& o, Load* load);

  // Warning passes (compile_checks.cpp).
  void WarnFarPoints();
  void WarnRadiansInDegrees(const Driver& drv, const std::string& ptr, double swing);
  void WarnStrayJointPoints();
  void WarnOddLengths();
  void CheckDriverSpans();
  void CheckLoadSpans();

  // Frames of the design pose.
  std::pair<Vec3, Mat3> Pose(BodyIndex b) const {
    if (b == kGround) return {Vec3::Zero(), Mat3::Identity()};
    return {model_.bodies[b].position, CalcA(model_.bodies[b].euler)};
  }
  Vec3 LocalPoint(BodyIndex b, const Vec3& global) const {
    auto [r, A] = Pose(b);
    return Vec3(A.transpose() * (global - r));
  }
  JointFrame LocalFrame(BodyIndex b, const JointFrame& global) const {
    auto [r, A] = Pose(b);
    return ToLocal(global, r, A);
  }
  // A driver between body1 and body2 on one global frame, held in each body's axes.
  void SetDriverFrames(Driver* drv, BodyIndex body1, BodyIndex body2, const JointFrame& global) const {
    drv->body1 = body1;
    drv->body2 = body2;
    drv->frame1 = LocalFrame(body1, global);
    drv->frame2 = LocalFrame(body2, global);
  }

  static constexpr double kMaxCoordinate = 1e12;  // m

  const MechanismSpec& spec_;
  const ParameterOverrides& overrides_;
  DiagnosticLog& out_;
  Model model_;
  ExpressionSymbols symbols_;
  std::shared_ptr<const ExpressionCache> expressions_;  // what this compile reads
  std::shared_ptr<ExpressionCache> recording_;          // first compile of a spec: what it records
  std::vector<double> slot_values_;                     // per parameter slot, its value once resolved
  std::vector<char> slot_known_;
  std::vector<std::string> names_scratch_;
  std::set<std::string> failed_parameters_;
  std::map<std::string, BodyIndex> body_index_;
  std::map<BodyIndex, std::map<std::string, std::optional<JointFrame>>> markers_;  // nullopt: the marker failed
  std::map<std::string, int> joint_index_;
  std::set<std::string> driver_names_, output_names_, coupler_names_;
  std::vector<std::string> driver_pointers_;  // per model driver, its place in the file
  double length_ = 1, angle_ = 1;
  bool by_markers_ = false;       // some joint names markers: positions are optional guesses
  std::vector<bool> sketched_;    // per model body: the file gives its position
};

}  // namespace mechkin
