// The whole mechanism's constraint system (constraints.md §5, §1.6):
// joints built from the primitive families, drivers, and their assembly into
// Φ, the Jacobian (ω' and p versions) and the right-hand sides.
//
// ConstraintSystem is immutable and built once per model. SystemState holds
// everything that changes with t; it is built once and reused every step.
//
// Column layout. ω' version: body k owns columns 6k..6k+5 = (r_k, π'_k).
// p version: body k owns 7k..7k+6 = (r_k, p_k), and one EUL row per body is
// appended after the constraint rows (row m + k).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>
#include <string>
#include <vector>

#include "constraints/constraint.hpp"
#include "model/model.hpp"

namespace mechkin {

enum class Formulation { Omega, P };

/// One family instance with its place in Φ and where it came from.
struct ConstraintEntry {
  std::unique_ptr<Constraint> constraint;
  int first_row = 0;
  bool from_driver = false;
  bool from_coupler = false;          // a coupler between joint coordinates (§3.11)
  int source = -1;                    // joint, coupler or driver index in the model
  int extra_angle_slot = -1;          // SystemState::angle_ref of its second and third angle
  std::vector<std::string> row_what;  // per equation: what it fixes, in joint vocabulary
};

class ConstraintSystem {
 public:
  /// Joints only (mobility analysis) or joints followed by drivers.
  ConstraintSystem(const Model& model, bool include_drivers);

  const Model& model() const { return *model_; }
  const std::vector<ConstraintEntry>& entries() const { return entries_; }
  int num_rows() const { return num_rows_; }
  /// Rows of the mechanism itself: joints, then couplers (drivers follow).
  int num_joint_rows() const { return num_joint_rows_; }
  /// Length of SystemState::angle_ref: one per entry, then the couplers' further angles.
  int num_angle_slots() const { return num_angle_slots_; }
  int num_bodies() const { return model_->num_bodies(); }
  int num_columns(Formulation f) const { return (f == Formulation::Omega ? 6 : 7) * num_bodies(); }
  /// Entry owning equation `row`, and the equation's index inside it.
  std::pair<int, int> Locate(int row) const { return row_owner_[row]; }
  /// "joint `J4` (revolute): rotation about its frame's f axis".
  std::string DescribeRow(int row) const;
  /// Name of the joint, coupler or driver that owns `row`.
  std::string SourceName(int row) const;

 private:
  const Model* model_;
  std::vector<ConstraintEntry> entries_;
  std::vector<std::pair<int, int>> row_owner_;
  int num_rows_ = 0, num_joint_rows_ = 0, num_angle_slots_ = 0;
};

/// Per-instant state: body kinematics, driver function values, angle references.
struct SystemState {
  double t = 0;
  std::vector<BodyKinematics> bodies;
  std::vector<Jet> driver_values;    // per model driver, SI
  std::vector<double> angle_ref;     // per angle slot (ConstraintSystem::num_angle_slots), multi-turn angles

  explicit SystemState(const ConstraintSystem& system);
  const BodyKinematics& Kin(BodyIndex b) const { return b == kGround ? GroundKinematics() : bodies[b]; }
  /// Sets every body to the design pose of the model, rates zero.
  void SetDesignPose(const Model& model);
};

/// Evaluates every driver function at t into state->driver_values. Throws
/// std::runtime_error naming the driver when a function cannot be evaluated.
void EvalDriverFunctions(const Model& model, double t, SystemState* state);
/// The inputs of entry `e` at state `s`.
ConstraintInput MakeInput(const ConstraintSystem& sys, const SystemState& s, size_t e);

/// Φ (num_rows).
void CalcPhi(const ConstraintSystem& sys, const SystemState& s, Eigen::VectorXd* phi);
/// Dense Jacobian: ω' version num_rows × 6n; p version (num_rows + n) × 7n with EUL rows.
void CalcJacobianDense(const ConstraintSystem& sys, const SystemState& s, Formulation f, Eigen::MatrixXd* J);
/// RHS_k (k = 1..4): ω' version num_rows; p version num_rows + n (EUL rows last).
void CalcRhs(const ConstraintSystem& sys, const SystemState& s, int k, Formulation f, Eigen::VectorXd* rhs);
/// Every driver function's value at t in extended precision (per model driver, SI).
void EvalDriverValuesExtended(const Model& model, double t, std::vector<Real>* values);
/// Φ (num_rows) in extended precision at per-body poses, with extended driver values
/// and the state's angle references.
void CalcPhiExtended(const ConstraintSystem& sys, const std::vector<ExtendedPose>& poses,
                     const std::vector<Real>& driver_values, const std::vector<double>& angle_ref,
                     Eigen::Matrix<Real, Eigen::Dynamic, 1>* phi);
/// Φ (num_rows) on Taylor series in time: per-body poses and driver functions as series
/// (constraints.md §8, "Measured", step 3), with the state's angle references.
void CalcPhiJets(const ConstraintSystem& sys, const std::vector<JetPose>& poses,
                 const std::vector<ExtendedJet>& drivers, const std::vector<double>& angle_ref,
                 std::vector<ExtendedJet>* phi);
/// Φ (num_rows) in quadruple precision at per-body poses (constraints.md §8, "Measured",
/// step 1); the families that read angles (CalcPhiQuad false) in extended precision at
/// `extended_poses`, the same poses rounded.
void CalcPhiQuad(const ConstraintSystem& sys, const std::vector<QuadPose>& poses,
                 const std::vector<ExtendedPose>& extended_poses, const std::vector<Real>& driver_values,
                 const std::vector<double>& angle_ref, std::vector<Quad>* phi);
/// Updates the multi-turn angle references to the current angles (after a step is accepted).
void UpdateAngleReferences(const ConstraintSystem& sys, SystemState* s);

/// The sparse Jacobian with a pattern fixed once per system and row subset:
/// Fill() writes values in place, no allocation.
class SparseJacobian {
 public:
  /// `rows`: the constraint rows to include, in order (p version: EUL rows are appended).
  SparseJacobian(const ConstraintSystem& sys, Formulation f, const std::vector<int>& rows);
  void Fill(const ConstraintSystem& sys, const SystemState& s);
  const Eigen::SparseMatrix<double>& matrix() const { return J_; }
  Formulation formulation() const { return f_; }
  const std::vector<int>& rows() const { return rows_; }

 private:
  Formulation f_;
  std::vector<int> rows_;
  std::vector<int> entry_rows_;       // per (entry, local row): compact row or −1
  std::vector<int> entry_row_start_;  // per entry: offset into entry_rows_
  std::vector<double*> slot_;         // per (entry, local row, 12 or 14 columns) pointer into J_ values
  std::vector<int> slot_start_;       // per entry
  std::vector<double*> eul_slot_;     // p version: 4 per body
  // ω' version: per entry (from copy_start_[e]), each Jacobian value to write: its
  // place in the entry's JacobianBlocks (in doubles from the start) and in J_.
  struct Copy {
    int from;
    double* to;
  };
  std::vector<Copy> copies_;
  std::vector<int> copy_start_;
  Eigen::SparseMatrix<double> J_;
  void ListCopies(const ConstraintSystem& sys);
  void FillPVersion(const ConstraintSystem& sys, const SystemState& s);
};

}  // namespace mechkin
