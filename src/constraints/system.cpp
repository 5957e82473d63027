#include "constraints/system.hpp"

#include <stdexcept>
#include <type_traits>

#include "constraints/couplers.hpp"

namespace mechkin {
namespace {

void Add(std::vector<ConstraintEntry>* out, std::unique_ptr<Constraint> c, bool from_driver, int source,
         std::vector<std::string> what) {
  ConstraintEntry e;
  e.constraint = std::move(c);
  e.from_driver = from_driver;
  e.source = source;
  e.row_what = std::move(what);
  out->push_back(std::move(e));
}

const Vec3& Axis(const JointFrame& frame, FrameAxis axis) {
  return axis == FrameAxis::F ? frame.f : axis == FrameAxis::G ? frame.g : frame.h;
}

// One primitive of a joint's descriptor as its family (constraints.md §3).
std::unique_ptr<Constraint> MakePrimitive(const Joint& jt, const JointEquation& eq) {
  const BodyIndex i = jt.body1, j = jt.body2;
  const JointFrame &a = jt.frame1, &b = jt.frame2;
  switch (eq.primitive) {
    case JointPrimitive::Spherical: return std::make_unique<SphericalConstraint>(i, j, a.origin, b.origin);
    case JointPrimitive::Distance: return std::make_unique<DistanceConstraint>(i, j, a.origin, b.origin, jt.length);
    case JointPrimitive::Dot1: return std::make_unique<Dot1Constraint>(i, j, Axis(a, eq.first), Axis(b, eq.second));
    case JointPrimitive::Dot2: return std::make_unique<Dot2Constraint>(i, j, Axis(a, eq.first), a.origin, b.origin);
    case JointPrimitive::Screw: return std::make_unique<ScrewConstraint>(i, j, a, b, jt.pitch);
  }
  throw std::logic_error("joint primitive out of range");
}

// Haug's construction of each joint from primitives (constraints.md §5), as its
// descriptor lists them.
void AddJoint(const Joint& jt, int index, std::vector<ConstraintEntry>* out) {
  for (const JointEquation& eq : jt.type->equations) Add(out, MakePrimitive(jt, eq), false, index, eq.rows);
}

CoordinateTerm TermOf(const Model& model, const CouplerCoordinate& cc) {
  const Joint& jt = model.joints[cc.joint];
  return CoordinateTerm{cc.rotation, jt.body1, jt.body2, jt.frame1, jt.frame2, cc.coefficient};
}

// §3.11: each coupler kind as its family.
std::unique_ptr<Constraint> MakeCoupler(const Model& model, const Coupler& cp) {
  std::vector<CoordinateTerm> terms;
  for (const CouplerCoordinate& cc : cp.coordinates) terms.push_back(TermOf(model, cc));
  switch (cp.kind) {
    case CouplerKind::Gear: return std::make_unique<GearConstraint>(terms[0], terms[1], cp.ratio);
    case CouplerKind::Belt: return std::make_unique<BeltConstraint>(terms[0], terms[1], cp.ratio);
    case CouplerKind::RackPinion: return std::make_unique<RackPinionConstraint>(terms[0], terms[1], cp.ratio);
    case CouplerKind::ScrewCoupling: return std::make_unique<ScrewCouplingConstraint>(terms[0], terms[1], cp.ratio);
    case CouplerKind::Coupling: break;
  }
  return std::make_unique<CouplingConstraint>(terms, cp.constant);
}

void AddDriver(const Driver& d, int index, std::vector<ConstraintEntry>* out) {
  switch (d.kind) {
    case DriverKind::JointRotation:
    case DriverKind::BodyRotation:
      if (d.general_angle)
        Add(out, std::make_unique<AngleDriver>(d.body1, d.body2, d.frame1, d.frame2), true, index, {"driven angle"});
      else
        Add(out, std::make_unique<RotationDriver>(d.body1, d.body2, d.frame1, d.frame2), true, index, {"driven angle"});
      break;
    case DriverKind::JointTranslation:
      Add(out, std::make_unique<Dot2DistanceDriver>(d.body1, d.body2, d.frame1.h, d.frame1.origin, d.frame2.origin),
          true, index, {"driven slide"});
      break;
    case DriverKind::Distance:
      Add(out, std::make_unique<DistanceConstraint>(d.body1, d.body2, d.point1, d.point2, 0.0), true, index,
          {"driven distance"});
      break;
  }
}

}  // namespace

ConstraintSystem::ConstraintSystem(const Model& model, bool include_drivers) : model_(&model) {
  for (size_t k = 0; k < model.joints.size(); ++k) AddJoint(model.joints[k], static_cast<int>(k), &entries_);
  for (size_t k = 0; k < model.couplers.size(); ++k) {
    const Coupler& cp = model.couplers[k];
    Add(&entries_, MakeCoupler(model, cp), false, static_cast<int>(k),
        {std::string(cp.kind == CouplerKind::Coupling ? "joint coordinates coupled" : "coordinates coupled by the ") +
         (cp.kind == CouplerKind::Coupling ? "" : CouplerKindName(cp.kind))});
    entries_.back().from_coupler = true;
  }
  const size_t joint_entries = entries_.size();
  if (include_drivers)
    for (size_t k = 0; k < model.drivers.size(); ++k) AddDriver(model.drivers[k], static_cast<int>(k), &entries_);
  int row = 0;
  for (size_t e = 0; e < entries_.size(); ++e) {
    entries_[e].first_row = row;
    for (int r = 0; r < entries_[e].constraint->size(); ++r) row_owner_.emplace_back(static_cast<int>(e), r);
    row += entries_[e].constraint->size();
    if (e + 1 == joint_entries) num_joint_rows_ = row;
  }
  num_rows_ = row;
  num_angle_slots_ = static_cast<int>(entries_.size());
  for (ConstraintEntry& e : entries_)
    if (e.constraint->NumAngles() > 1) {
      e.extra_angle_slot = num_angle_slots_;
      num_angle_slots_ += e.constraint->NumAngles() - 1;
    }
}

std::string ConstraintSystem::SourceName(int row) const {
  const ConstraintEntry& e = entries_[row_owner_[row].first];
  if (e.from_coupler) return model_->couplers[e.source].name;
  return e.from_driver ? model_->drivers[e.source].name : model_->joints[e.source].name;
}

std::string ConstraintSystem::DescribeRow(int row) const {
  const auto [ei, r] = row_owner_[row];
  const ConstraintEntry& e = entries_[ei];
  if (e.from_driver) return "driver `" + model_->drivers[e.source].name + "`: " + e.row_what[r];
  if (e.from_coupler) {
    const Coupler& cp = model_->couplers[e.source];
    return "coupler `" + cp.name + "` (" + CouplerKindName(cp.kind) + "): " + e.row_what[r];
  }
  const Joint& j = model_->joints[e.source];
  return "joint `" + j.name + "` (" + j.type->name + "): " + e.row_what[r];
}

SystemState::SystemState(const ConstraintSystem& system)
    : bodies(system.num_bodies()), driver_values(system.model().drivers.size()),
      angle_ref(system.num_angle_slots(), 0.0) {
  SetDesignPose(system.model());
}

void SystemState::SetDesignPose(const Model& model) {
  for (int k = 0; k < model.num_bodies(); ++k) bodies[k].SetPose(model.bodies[k].position, model.bodies[k].euler);
  std::fill(angle_ref.begin(), angle_ref.end(), 0.0);
}

void EvalDriverFunctions(const Model& model, double t, SystemState* state) {
  state->t = t;
  for (size_t k = 0; k < model.drivers.size(); ++k) {
    try {
      state->driver_values[k] = model.drivers[k].function.Eval(t);
    } catch (const std::exception& e) {
      throw std::runtime_error("driver `" + model.drivers[k].name + "` at t = " + std::to_string(t) + " s: " + e.what());
    }
  }
}

ConstraintInput MakeInput(const ConstraintSystem& sys, const SystemState& s, size_t e) {
  const ConstraintEntry& entry = sys.entries()[e];
  const Constraint& c = *entry.constraint;
  ConstraintInput in{s.Kin(c.body_i()), s.Kin(c.body_j()), entry.from_driver ? s.driver_values[entry.source] : Jet{},
                     s.angle_ref[e]};
  // Only couplers have more sides or angles (§3.11): the joint and driver entries of
  // the step loop skip the virtual NumAngles() (checked: spatial slider-crank step).
  if (!entry.from_coupler) return in;
  for (int side = 2; side < c.num_sides(); ++side) in.more[side - 2] = &s.Kin(c.body(side));
  if (entry.extra_angle_slot >= 0)
    for (int a = 1; a < c.NumAngles(); ++a) in.more_angle_refs[a - 1] = s.angle_ref[entry.extra_angle_slot + a - 1];
  return in;
}

void CalcPhi(const ConstraintSystem& sys, const SystemState& s, Eigen::VectorXd* phi) {
  phi->resize(sys.num_rows());
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    const ConstraintInput in = MakeInput(sys, s, e);
    entries[e].constraint->CalcPhi(in, phi->data() + entries[e].first_row);
  }
}

void EvalDriverValuesExtended(const Model& model, double t, std::vector<Real>* values) {
  values->resize(model.drivers.size());
  for (size_t k = 0; k < model.drivers.size(); ++k) (*values)[k] = model.drivers[k].function.ValueExtended(t);
}

void CalcPhiExtended(const ConstraintSystem& sys, const std::vector<ExtendedPose>& poses,
                     const std::vector<Real>& driver_values, const std::vector<double>& angle_ref,
                     Eigen::Matrix<Real, Eigen::Dynamic, 1>* phi) {
  static const ExtendedPose kGroundPose;
  phi->resize(sys.num_rows());
  const auto pose = [&](BodyIndex b) -> const ExtendedPose& { return b == kGround ? kGroundPose : poses[b]; };
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    const Constraint& c = *entries[e].constraint;
    ExtendedInput in{pose(c.body_i()), pose(c.body_j()),
                     entries[e].from_driver ? driver_values[entries[e].source] : Real(0), angle_ref[e]};
    for (int side = 2; side < c.num_sides(); ++side) in.more[side - 2] = &pose(c.body(side));
    if (entries[e].extra_angle_slot >= 0)
      for (int a = 1; a < c.NumAngles(); ++a) in.more_angle_refs[a - 1] = angle_ref[entries[e].extra_angle_slot + a - 1];
    c.CalcPhiExtended(in, phi->data() + entries[e].first_row);
  }
}

// As CalcPhiExtended, on series: the ground is the constant identity pose.
void CalcPhiJets(const ConstraintSystem& sys, const std::vector<JetPose>& poses,
                 const std::vector<ExtendedJet>& drivers, const std::vector<double>& angle_ref,
                 std::vector<ExtendedJet>* phi) {
  static const JetPose kGroundPose;
  phi->resize(sys.num_rows());
  const auto pose = [&](BodyIndex b) -> const JetPose& { return b == kGround ? kGroundPose : poses[b]; };
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    const Constraint& c = *entries[e].constraint;
    JetInput in{pose(c.body_i()), pose(c.body_j()),
                entries[e].from_driver ? drivers[entries[e].source] : ExtendedJet(0), angle_ref[e]};
    for (int side = 2; side < c.num_sides(); ++side) in.more[side - 2] = &pose(c.body(side));
    if (entries[e].extra_angle_slot >= 0)
      for (int a = 1; a < c.NumAngles(); ++a) in.more_angle_refs[a - 1] = angle_ref[entries[e].extra_angle_slot + a - 1];
    c.CalcPhiJet(in, phi->data() + entries[e].first_row);
  }
}

void CalcPhiQuad(const ConstraintSystem& sys, const std::vector<QuadPose>& poses,
                 const std::vector<ExtendedPose>& extended_poses, const std::vector<Real>& driver_values,
                 const std::vector<double>& angle_ref, std::vector<Quad>* phi) {
  static const QuadPose kGroundPose;
  static const ExtendedPose kGroundExtended;
  phi->resize(sys.num_rows());
  const auto pose = [&](BodyIndex b) -> const QuadPose& { return b == kGround ? kGroundPose : poses[b]; };
  const auto extended = [&](BodyIndex b) -> const ExtendedPose& { return b == kGround ? kGroundExtended : extended_poses[b]; };
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    const Constraint& c = *entries[e].constraint;
    const Real f = entries[e].from_driver ? driver_values[entries[e].source] : Real(0);
    Quad* out = phi->data() + entries[e].first_row;
    if (c.num_sides() == 2 && c.CalcPhiQuad(QuadInput{pose(c.body_i()), pose(c.body_j()), Quad(f), angle_ref[e]}, out)) continue;
    ExtendedInput in{extended(c.body_i()), extended(c.body_j()), f, angle_ref[e]};
    for (int side = 2; side < c.num_sides(); ++side) in.more[side - 2] = &extended(c.body(side));
    if (entries[e].extra_angle_slot >= 0)
      for (int a = 1; a < c.NumAngles(); ++a) in.more_angle_refs[a - 1] = angle_ref[entries[e].extra_angle_slot + a - 1];
    Real row[kMaxRows];
    c.CalcPhiExtended(in, row);
    for (int r = 0; r < c.size(); ++r) out[r] = static_cast<Quad>(row[r]);
  }
}

void CalcJacobianDense(const ConstraintSystem& sys, const SystemState& s, Formulation f, Eigen::MatrixXd* J) {
  const int n = sys.num_bodies(), m = sys.num_rows();
  const int nc = f == Formulation::Omega ? 6 : 7;
  J->setZero(m + (f == Formulation::P ? n : 0), nc * n);
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    const Constraint& c = *entries[e].constraint;
    const ConstraintInput in = MakeInput(sys, s, e);
    JacobianBlocks B;
    c.CalcJacobian(in, &B);
    const int r0 = entries[e].first_row, sz = c.size();
    for (int side = 0; side < c.num_sides(); ++side) {
      const BodyIndex b = c.body(side);
      if (b == kGround) continue;
      J->block(r0, nc * b, sz, 3) = B.R(side).topRows(sz);
      if (f == Formulation::Omega) J->block(r0, 6 * b + 3, sz, 3) = B.Pi(side).topRows(sz);
      else J->block(r0, 7 * b + 3, sz, 4) = PVersionBlock(in, B, side).topRows(sz);
    }
  }
  if (f == Formulation::P)
    for (int k = 0; k < n; ++k) J->block(m + k, 7 * k + 3, 1, 4) = EulerNormalization::Jacobian(s.bodies[k].p).transpose();
}

void CalcRhs(const ConstraintSystem& sys, const SystemState& s, int k, Formulation f, Eigen::VectorXd* rhs) {
  const int n = sys.num_bodies(), m = sys.num_rows();
  rhs->resize(m + (f == Formulation::P ? n : 0));
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    const ConstraintInput in = MakeInput(sys, s, e);
    double* out = rhs->data() + entries[e].first_row;
    if (f == Formulation::Omega) entries[e].constraint->CalcRhs(in, k, out);
    else CalcPVersionRhs(*entries[e].constraint, in, k, out);
  }
  if (f == Formulation::P) {
    Vec4 pd[kMaxOrder + 1];
    for (int b = 0; b < n; ++b) {
      s.bodies[b].CalcEulerDerivatives(k - 1, pd);
      (*rhs)[m + b] = EulerNormalization::Rhs(pd, k);
    }
  }
}

void UpdateAngleReferences(const ConstraintSystem& sys, SystemState* s) {
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    const Constraint& c = *entries[e].constraint;
    if (!c.HasAngle()) continue;
    const ConstraintInput in = MakeInput(sys, *s, e);
    double angles[kMaxAngles];
    c.CalcAngles(in, angles);
    s->angle_ref[e] = angles[0];
    for (int a = 1; a < c.NumAngles(); ++a) s->angle_ref[entries[e].extra_angle_slot + a - 1] = angles[a];
  }
}

SparseJacobian::SparseJacobian(const ConstraintSystem& sys, Formulation f, const std::vector<int>& rows)
    : f_(f), rows_(rows) {
  const int n = sys.num_bodies();
  const int nc = f == Formulation::Omega ? 6 : 7;
  const auto& entries = sys.entries();
  std::vector<int> compact(sys.num_rows(), -1);
  for (size_t r = 0; r < rows.size(); ++r) compact[rows[r]] = static_cast<int>(r);
  const int nrows = static_cast<int>(rows.size()) + (f == Formulation::P ? n : 0);
  std::vector<Eigen::Triplet<double>> trip;
  for (const auto& e : entries) {
    const Constraint& c = *e.constraint;
    for (int r = 0; r < c.size(); ++r) {
      const int row = compact[e.first_row + r];
      if (row < 0) continue;
      for (int side = 0; side < c.num_sides(); ++side)
        if (c.body(side) != kGround)
          for (int col = 0; col < nc; ++col) trip.emplace_back(row, nc * c.body(side) + col, 1.0);
    }
  }
  if (f == Formulation::P)
    for (int b = 0; b < n; ++b)
      for (int col = 3; col < 7; ++col) trip.emplace_back(static_cast<int>(rows.size()) + b, 7 * b + col, 1.0);
  J_.resize(nrows, nc * n);
  J_.setFromTriplets(trip.begin(), trip.end());
  J_.makeCompressed();
  // Pointers into the value array: stable, since the pattern never changes.
  for (const auto& e : entries) {
    const Constraint& c = *e.constraint;
    slot_start_.push_back(static_cast<int>(slot_.size()));
    for (int r = 0; r < c.size(); ++r) {
      const int row = compact[e.first_row + r];
      for (int side = 0; side < c.num_sides(); ++side)
        for (int col = 0; col < nc; ++col)
          slot_.push_back(row >= 0 && c.body(side) != kGround ? &J_.coeffRef(row, nc * c.body(side) + col) : nullptr);
    }
  }
  if (f == Formulation::P)
    for (int b = 0; b < n; ++b)
      for (int col = 3; col < 7; ++col) eul_slot_.push_back(&J_.coeffRef(static_cast<int>(rows.size()) + b, 7 * b + col));
  if (f == Formulation::Omega) ListCopies(sys);
}

// The ω' version's values straight from the blocks: the places in JacobianBlocks (a
// standard-layout struct of double matrices) counted in doubles from its start.
void SparseJacobian::ListCopies(const ConstraintSystem& sys) {
  static_assert(std::is_standard_layout<JacobianBlocks>::value, "JacobianBlocks is addressed by offsets");
  const JacobianBlocks probe;
  const auto offset = [&](const double& v) {
    return static_cast<int>((reinterpret_cast<const char*>(&v) - reinterpret_cast<const char*>(&probe)) / sizeof(double));
  };
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    const Constraint& c = *entries[e].constraint;
    copy_start_.push_back(static_cast<int>(copies_.size()));
    double* const* slot = slot_.data() + slot_start_[e];
    for (int r = 0; r < c.size(); ++r)
      for (int side = 0; side < c.num_sides(); ++side)
        for (int col = 0; col < 6; ++col, ++slot)
          if (*slot) copies_.push_back({offset(col < 3 ? probe.R(side)(r, col) : probe.Pi(side)(r, col - 3)), *slot});
  }
  copy_start_.push_back(static_cast<int>(copies_.size()));
}

void SparseJacobian::Fill(const ConstraintSystem& sys, const SystemState& s) {
  if (f_ == Formulation::P) return FillPVersion(sys, s);
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    JacobianBlocks B;
    entries[e].constraint->CalcJacobian(MakeInput(sys, s, e), &B);
    const double* values = reinterpret_cast<const double*>(&B);
    for (int k = copy_start_[e]; k < copy_start_[e + 1]; ++k) *copies_[k].to = values[copies_[k].from];
  }
}

void SparseJacobian::FillPVersion(const ConstraintSystem& sys, const SystemState& s) {
  const auto& entries = sys.entries();
  for (size_t e = 0; e < entries.size(); ++e) {
    const Constraint& c = *entries[e].constraint;
    const ConstraintInput in = MakeInput(sys, s, e);
    JacobianBlocks B;
    c.CalcJacobian(in, &B);
    Eigen::Matrix<double, kMaxRows, 4> P[kMaxSides];
    for (int side = 0; side < c.num_sides(); ++side) P[side] = PVersionBlock(in, B, side);
    double* const* slot = slot_.data() + slot_start_[e];
    for (int r = 0; r < c.size(); ++r)
      for (int side = 0; side < c.num_sides(); ++side)
        for (int col = 0; col < 7; ++col, ++slot)
          if (*slot) **slot = col < 3 ? B.R(side)(r, col) : P[side](r, col - 3);
  }
  for (size_t b = 0; b < s.bodies.size(); ++b)
    for (int col = 0; col < 4; ++col) *eul_slot_[4 * b + col] = 2 * s.bodies[b].p[col];
}

}  // namespace mechkin
