// The typed result of a driven run (issue "One library core with typed results").
//
// MotionLayout describes the columns of a motion table once per model and
// selection: each column carries what it is (quantity, subject, component,
// derivative order, unit), so no consumer ever has to read meaning out of a
// column name. RowEvaluator turns a solved SystemState into one row of values
// in the layout's units (joint coordinates are computed here, continuously
// from the design pose). Motion keeps rows in one row-major buffer that
// front ends can view without copying; the CLI streams rows to a file instead.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/clearance.hpp"
#include "analysis/kinematic_analysis.hpp"
#include "analysis/reduction_result.hpp"

namespace mechkin {

enum class Quantity {
  Time,
  BodyPosition,       // r, component x/y/z, order 0..4
  EulerParameter,     // p, component e0..e3 (order 0)
  AngularVelocity,    // global ω and derivatives, order 1..4 (".wx" is order 1)
  PointPosition,      // output point, x/y/z
  Distance,           // output distance
  JointAngle,         // revolute angle / cylindrical & screw ".angle"
  JointSlide,         // prismatic slide / cylindrical & screw ".slide"
  Angle,              // angle output: between two body-fixed vectors
  VelocityRatio,      // d(output)/d(input); its order k column is the k-th time derivative of the ratio
  OrientationAngle,   // orientation output: the sequence's angles, component 0..2
  OrientationParameter,  // orientation output: relative Euler parameters e0..e3
  RotationVector,     // orientation output "axis-angle": θn, component x/y/z
  GimbalLock,         // orientation output: 1 where the sequence's first and third angles are undefined
  Clearance,          // clearance output: the bodies' minimum distance, order 0..1 (analysis/clearance.hpp)
  ClearancePoint,     // its closest points, global: component 0..2 on body1, 3..5 on body2
  Expression,         // expression output: computed from earlier outputs (file units), order 0..order
  DriverEffort,       // torque or force a driver applies (".effort"), order 0..1
  DriverPower,        // ".power"
  JointForce,         // reaction force on body2 by body1, global x/y/z (".fx")
  JointMoment,        // reaction moment about the joint origin, global (".mx")
  JointForceLocal,    // the force in body2's joint frame f/g/h (".ff")
  JointMomentLocal,   // the moment in body2's joint frame (".mf")
  CouplerEffort,      // a coupler's torque or force on its k-th coordinate (".effort1" …), component k
  CouplerPower,       // the power a coupler takes from its first coordinate (".power")
  KineticEnergy,
  PotentialEnergy,
  EnergyBalance,      // Σ driver + load power − d(kinetic + potential)/dt: round-off
  NewtonIterations,
  Residual,
  Condition,
  ErrorBound,         // relative error bound of the order
};

/// One column: `name` is the format-v1 column name without the unit ("crank.x_t"),
/// `subject` the body or output it belongs to ("" for time and diagnostics).
struct ColumnDescriptor {
  std::string name, unit, subject;
  Quantity quantity = Quantity::Time;
  int subject_index = -1;  // body index or output index
  int component = -1;      // 0..2 for x/y/z, 0..3 for e0..e3, −1 when none
  int order = 0;           // time-derivative order
  // Sensitivity column "piston.x/d(crank)": the parameter's index in
  // TableOptions::sensitivity and the column it differentiates (−1 otherwise).
  int wrt = -1, base = -1;
  /// "crank.x_t [mm/s]" as in the table's header (no brackets when unitless).
  std::string Header() const;
  bool IsDiagnostic() const { return quantity >= Quantity::NewtonIterations; }
};

/// What a table shows: derivative order, units, and the selected bodies/outputs.
struct TableOptions {
  int order = 3;
  bool si = false;
  bool all_bodies = true, all_outputs = true;
  std::vector<std::string> bodies, outputs;  // selections when not all
  bool forces = false;  // driver efforts, joint reactions, energies (after the outputs)
  // Parameters: d(every body and output column)/d(parameter) after all other columns.
  std::vector<std::string> sensitivity;
};

class MotionLayout {
 public:
  /// Throws std::invalid_argument for a selected body/output that does not exist.
  MotionLayout(const Model& model, const TableOptions& options);

  const std::vector<ColumnDescriptor>& columns() const { return columns_; }
  int size() const { return static_cast<int>(columns_.size()); }
  const TableOptions& options() const { return options_; }
  /// Index of the column named `name` (without unit), or −1.
  int Find(const std::string& name) const;
  /// First column of a body's or output's series of the given quantity, component and order, or −1.
  int Find(Quantity q, int subject_index, int component, int order) const;
  /// The typed accessors (issue 32: no code outside the layout composes a column
  /// name). Column d(column)/d(parameter), parameter an index into
  /// options().sensitivity or its name; −1 when the table has none.
  int SensitivityOf(int column, int parameter) const;
  int SensitivityOf(const std::string& column, const std::string& parameter) const;
  /// A driver's effort (torque or force) or power column of the given order (0 or 1), by name; −1 if none.
  int EffortOf(const std::string& driver, int order) const;
  int PowerOf(const std::string& driver, int order) const;
  double length_factor() const { return len_; }  // SI → table unit
  double angle_factor() const { return ang_; }
  /// Bodies whose motion the selection reads (for the block-by-block path).
  std::vector<int> NeededBodies(const Model& model) const;

  struct Item { bool is_body; int index; };
  const std::vector<Item>& items() const { return items_; }

  /// The columns in runs that one extractor fills (issue 32, "columns that carry
  /// their values"): each segment knows where its columns start and how many there
  /// are, and RowEvaluator writes each at its own offset and checks the count, so
  /// the layout and the values cannot drift apart.
  struct Segment {
    enum class Kind { Time, Body, Output, Forces, Diagnostics, Sensitivities } kind;
    int index;        // the body or output (−1 otherwise)
    int first, count;  // its columns
  };
  const std::vector<Segment>& segments() const { return segments_; }

 private:
  void AddBody(const Model& model, int b);
  void AddOutput(const Model& model, int o);
  void AddForces(const Model& model);
  void AddSensitivities();
  void AddVelocityRatio(const Model& model, int o);
  void AddOrientation(const Output& out, int o, const std::string& angle_unit);
  void AddJointCoordinates(JointCoordinates c, const Output& out, int o, const std::string& length_unit,
                           const std::string& angle_unit);
  void AddClearance(const Output& out, int o, const std::string& length_unit);
  void AddRated(Quantity q, const std::string& subject, int index, const std::string& name, int component,
                const std::string& unit);
  void AddSeries(Quantity q, const std::string& subject, int index, const std::string& name, int component,
                 const std::string& unit, int first_order);

  void Close(Segment::Kind kind, int index, int first);

  TableOptions options_;
  std::vector<Item> items_;
  std::vector<Segment> segments_;
  std::vector<ColumnDescriptor> columns_;
  double len_ = 1, ang_ = 1;
};

/// Computes rows of a layout from solved states. Holds the joint-angle
/// continuity state, so use one evaluator per run.
class RowEvaluator {
 public:
  RowEvaluator(const Model& model, const MotionLayout& layout);
  /// Writes layout.size() values into `row`.
  void Evaluate(const SystemState& s, const StepDiagnostics& d, double* row);
  /// Follows a pose that makes no row (the assembly and the move to the start):
  /// angles keep their turn from the design pose across it.
  void Follow(const SystemState& s);
  /// Takes another evaluator's angle references (same outputs): the sides of a
  /// sensitivity unwrap nearest the base row instead of nearest 0.
  void ContinueFrom(const RowEvaluator& base);

 private:
  double* BodyValues(const BodyKinematics& b, double* out) const;
  double* OutputValues(const SystemState& s, int o, double* out);
  double* ForceValues(const ForceResults* f, double* out) const;
  double* SegmentValues(const MotionLayout::Segment& g, const SystemState& s, const StepDiagnostics& d, double* row);
  double* DiagnosticValues(const StepDiagnostics& d, double* out) const;
  void SensitivityValues(const StepDiagnostics& d, double* row);

  // The same layout evaluated on the model compiled at p ± h (sensitivity columns).
  struct PerturbedRows {
    std::unique_ptr<MotionLayout> layout;
    std::unique_ptr<RowEvaluator> eval;
    std::vector<double> row;
    std::vector<int> column;  // per sensitivity column of the parameter: its base column there
  };
  std::vector<PerturbedRows> perturbed_;  // per parameter: + then −

  double JointAngle(const SystemState& s, int o, double raw_sin, double raw_cos);
  double* AngleValues(const SystemState& s, int o, double* out);
  double* PointValues(const SystemState& s, int o, double* out) const;
  double* VelocityRatioValues(const SystemState& s, int o, double* out) const;
  double* OrientationValues(const SystemState& s, int o, double* out);
  double* UniversalValues(const SystemState& s, int o, double* out);
  double* PlanarSlides(const SystemState& s, int o, double* out) const;
  double* ClearanceValues(const SystemState& s, int o, double* out);
  double* ExpressionValues(const SystemState& s, int o, double* out);
  void PrepareExpressions();
  Jet ScalarOutputJet(const SystemState& s, int o) const;

  const Model& model_;
  const MotionLayout& layout_;
  std::vector<double> angle_ref_;    // per output: the last joint angle (SI), for continuity
  std::vector<double> angle_rate_;   // per output: its last angular velocity (SI)
  std::vector<int> angle_driver_;    // per output: the rotation driver of its joint, or −1
  // Orientation outputs: the last row's angles / Euler parameters, for continuity.
  std::vector<std::array<double, 4>> orientation_ref_;
  std::vector<std::array<double, 3>> orientation_rate_;
  double last_t_ = 0;
  bool first_row_ = true;
  std::vector<double> follow_row_;  // scratch for Follow (outside the step loop)
  // Clearance outputs: their pairs' evaluator (made on the first row) and, per output, its pair.
  std::shared_ptr<ClearanceEvaluator> clearance_;
  std::vector<int> clearance_pair_;
  // Expression outputs read earlier outputs in the file's units, whatever this table's
  // units and selection. A layout with every output in file units reads them from the
  // row it is filling (each input computed once, earlier in the row); any other has an
  // evaluator over such a layout, whose row it fills first and copies the expressions
  // from. Per input of each expression output: the row column of its order-k value
  // (−1: no such order).
  std::unique_ptr<MotionLayout> file_layout_;
  std::unique_ptr<RowEvaluator> file_units_;
  std::vector<double> file_row_;
  std::vector<int> file_block_;  // per output: its first column in file_row_
  std::vector<std::vector<std::array<int, kMaxOrder + 1>>> expression_offsets_;
  std::vector<Jet> expression_jets_;
  const double* current_row_ = nullptr;  // the row Evaluate is filling
  bool following_ = false;               // in Follow: no row, expressions not computed
};

struct MotionStop {
  StopKind kind = StopKind::None;
  std::string message;                      // the full explanation
  std::optional<SingularPosition> singular;  // for SingularPosition
  /// First line of the message (the `# PARTIAL TABLE:` note).
  std::string Summary() const { return message.substr(0, message.find('\n')); }
};

/// Receives rows as the run computes them.
class RowSink {
 public:
  virtual ~RowSink() = default;
  /// Returns false to stop the run (e.g. a failed write).
  virtual bool Append(const double* row, int size) = 0;
};

/// The whole motion in memory: one row-major buffer, rows × columns.
class Motion : public RowSink {
 public:
  explicit Motion(MotionLayout layout) : layout_(std::move(layout)) {}

  const MotionLayout& layout() const { return layout_; }
  const std::vector<ColumnDescriptor>& columns() const { return layout_.columns(); }
  int rows() const { return cols() ? static_cast<int>(values_.size() / cols()) : 0; }
  int cols() const { return layout_.size(); }
  double at(int row, int col) const { return values_[static_cast<size_t>(row) * cols() + col]; }
  const std::vector<double>& values() const { return values_; }
  std::vector<double>& mutable_values() { return values_; }  // for unpickling
  /// A copy of one column.
  std::vector<double> Column(int col) const;

  bool complete = false;
  MotionStop stop;
  AnalysisReport report;  // assembly, redundancy, blocks, per-step timing
  std::vector<ReductionResult> reductions;  // the model's reductions over these rows (analysis/reduction.hpp)

  bool Append(const double* row, int size) override;

 private:
  MotionLayout layout_;
  std::vector<double> values_;
};

/// A Motion filled from solved states (for callers that drive the analysis themselves).
class MotionRecorder {
 public:
  MotionRecorder(const Model& model, const TableOptions& table)
      : motion_(MotionLayout(model, table)), eval_(model, motion_.layout()), row_(motion_.cols()) {}
  MotionRecorder(const MotionRecorder&) = delete;
  MotionRecorder& operator=(const MotionRecorder&) = delete;
  bool Record(const SystemState& s, const StepDiagnostics& d) {
    eval_.Evaluate(s, d, row_.data());
    return motion_.Append(row_.data(), motion_.cols());
  }
  Motion& motion() { return motion_; }

 private:
  Motion motion_;
  RowEvaluator eval_;
  std::vector<double> row_;
};

/// Runs the analysis into `sink` through a RowEvaluator; the report says how it ended.
AnalysisReport RunIntoSink(const Model& model, const AnalysisOptions& options, const MotionLayout& layout,
                           RowSink* sink);
/// Runs the analysis and returns the whole Motion (never throws for a mechanism that
/// cannot move as asked; the Motion says why it stopped). The table decides the solved
/// order, forces, sensitivities and blocks (DecideComputation, analysis/run_request.hpp);
/// `options` gives the solver's settings. Front ends use RunMotion(model, RunRequest).
Motion RunMotion(const Model& model, const AnalysisOptions& options, const TableOptions& table);
/// The stop classification of a report.
MotionStop StopOf(const AnalysisReport& report);

}  // namespace mechkin
