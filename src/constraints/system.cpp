#include "constraints/system.hpp"

#include <stdexcept>

#include "constraints/families.hpp"

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

// Haug's construction of each joint from primitives (constraints.md §5).
void AddJoint(const Joint& jt, int index, std::vector<ConstraintEntry>* out) {
  const BodyIndex i = jt.body1, j = jt.body2;
  const JointFrame &a = jt.frame1, &b = jt.frame2;
  auto sph = [&] {
    Add(out, std::make_unique<SphericalConstraint>(i, j, a.origin, b.origin), false, index,
        {"translation along global x", "translation along global y", "translation along global z"});
  };
  // parallel-1: h_j ⟂ f_i and h_j ⟂ g_i keep h_j ∥ h_i.
  auto parallel1 = [&] {
    Add(out, std::make_unique<Dot1Constraint>(i, j, a.f, b.h), false, index, {"rotation about its frame's g axis"});
    Add(out, std::make_unique<Dot1Constraint>(i, j, a.g, b.h), false, index, {"rotation about its frame's f axis"});
  };
  // parallel-2: P_j stays on the axis of i.
  auto parallel2 = [&] {
    Add(out, std::make_unique<Dot2Constraint>(i, j, a.f, a.origin, b.origin), false, index,
        {"translation along its frame's f axis"});
    Add(out, std::make_unique<Dot2Constraint>(i, j, a.g, a.origin, b.origin), false, index,
        {"translation along its frame's g axis"});
  };
  switch (jt.type) {
    case JointType::Spherical: sph(); break;
    case JointType::Distance:
      Add(out, std::make_unique<DistanceConstraint>(i, j, a.origin, b.origin, jt.length), false, index,
          {"distance between its two points"});
      break;
    case JointType::Universal:
      sph();
      Add(out, std::make_unique<Dot1Constraint>(i, j, a.h, b.h), false, index,
          {"rotation about the common normal of its two axes"});
      break;
    case JointType::Revolute: sph(); parallel1(); break;
    case JointType::Cylindrical: parallel1(); parallel2(); break;
    case JointType::Prismatic:
      parallel1();
      parallel2();
      // f_iᵀg_j = −sin θ: regular at θ = 0 (§5, "Prismatic with aligned frames").
      Add(out, std::make_unique<Dot1Constraint>(i, j, a.f, b.g), false, index, {"rotation about its axis"});
      break;
    case JointType::Screw:
      parallel1();
      parallel2();
      Add(out, std::make_unique<ScrewConstraint>(i, j, a, b, jt.pitch), false, index,
          {"slide coupled to rotation by the pitch"});
      break;
    case JointType::Planar:
      parallel1();
      Add(out, std::make_unique<Dot2Constraint>(i, j, a.h, a.origin, b.origin), false, index,
          {"translation along its normal"});
      break;
  }
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
}

std::string ConstraintSystem::SourceName(int row) const {
  const ConstraintEntry& e = entries_[row_owner_[row].first];
  return e.from_driver ? model_->drivers[e.source].name : model_->joints[e.source].name;
}

std::string ConstraintSystem::DescribeRow(int row) const {
  const auto [ei, r] = row_owner_[row];
  const ConstraintEntry& e = entries_[ei];
  if (e.from_driver) return "driver `" + model_->drivers[e.source].name + "`: " + e.row_what[r];
  const Joint& j = model_->joints[e.source];
  return "joint `" + j.name + "` (" + JointTypeName(j.type) + "): " + e.row_what[r];
}

SystemState::SystemState(const ConstraintSystem& system)
    : bodies(system.num_bodies()), driver_values(system.model().drivers.size()),
      angle_ref(system.entries().size(), 0.0) {
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
  return ConstraintInput{s.Kin(entry.constraint->body_i()), s.Kin(entry.constraint->body_j()),
                         entry.from_driver ? s.driver_values[entry.source] : Jet{}, s.angle_ref[e]};
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
    const ExtendedInput in{pose(c.body_i()), pose(c.body_j()),
                           entries[e].from_driver ? driver_values[entries[e].source] : Real(0), angle_ref[e]};
    c.CalcPhiExtended(in, phi->data() + entries[e].first_row);
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
    if (f == Formulation::Omega) {
      if (c.body_i() != kGround) {
        J->block(r0, 6 * c.body_i(), sz, 3) = B.r_i.topRows(sz);
        J->block(r0, 6 * c.body_i() + 3, sz, 3) = B.pi_i.topRows(sz);
      }
      if (c.body_j() != kGround) {
        J->block(r0, 6 * c.body_j(), sz, 3) = B.r_j.topRows(sz);
        J->block(r0, 6 * c.body_j() + 3, sz, 3) = B.pi_j.topRows(sz);
      }
    } else {
      Eigen::Matrix<double, kMaxRows, 4> pi, pj;
      CalcPVersionJacobian(c, in, B, &pi, &pj);
      if (c.body_i() != kGround) {
        J->block(r0, 7 * c.body_i(), sz, 3) = B.r_i.topRows(sz);
        J->block(r0, 7 * c.body_i() + 3, sz, 4) = pi.topRows(sz);
      }
      if (c.body_j() != kGround) {
        J->block(r0, 7 * c.body_j(), sz, 3) = B.r_j.topRows(sz);
        J->block(r0, 7 * c.body_j() + 3, sz, 4) = pj.topRows(sz);
      }
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
    if (!entries[e].constraint->HasAngle()) continue;
    const ConstraintInput in = MakeInput(sys, *s, e);
    s->angle_ref[e] = entries[e].constraint->CalcAngle(in);
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
      for (BodyIndex b : {c.body_i(), c.body_j()})
        if (b != kGround)
          for (int col = 0; col < nc; ++col) trip.emplace_back(row, nc * b + col, 1.0);
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
      for (BodyIndex b : {c.body_i(), c.body_j()})
        for (int col = 0; col < nc; ++col)
          slot_.push_back(row >= 0 && b != kGround ? &J_.coeffRef(row, nc * b + col) : nullptr);
    }
  }
  if (f == Formulation::P)
    for (int b = 0; b < n; ++b)
      for (int col = 3; col < 7; ++col) eul_slot_.push_back(&J_.coeffRef(static_cast<int>(rows.size()) + b, 7 * b + col));
}

void SparseJacobian::Fill(const ConstraintSystem& sys, const SystemState& s) {
  const auto& entries = sys.entries();
  const int nc = f_ == Formulation::Omega ? 6 : 7;
  for (size_t e = 0; e < entries.size(); ++e) {
    const Constraint& c = *entries[e].constraint;
    const ConstraintInput in = MakeInput(sys, s, e);
    JacobianBlocks B;
    c.CalcJacobian(in, &B);
    Eigen::Matrix<double, kMaxRows, 4> pi, pj;
    if (f_ == Formulation::P) CalcPVersionJacobian(c, in, B, &pi, &pj);
    double* const* slot = slot_.data() + slot_start_[e];
    for (int r = 0; r < c.size(); ++r) {
      for (int side = 0; side < 2; ++side) {
        const RowBlock& Br = side == 0 ? B.r_i : B.r_j;
        const RowBlock& Bp = side == 0 ? B.pi_i : B.pi_j;
        const auto& Pp = side == 0 ? pi : pj;
        for (int col = 0; col < nc; ++col, ++slot) {
          if (!*slot) continue;
          **slot = col < 3 ? Br(r, col) : (f_ == Formulation::Omega ? Bp(r, col - 3) : Pp(r, col - 3));
        }
      }
    }
  }
  if (f_ == Formulation::P)
    for (size_t b = 0; b < s.bodies.size(); ++b)
      for (int col = 0; col < 4; ++col) *eul_slot_[4 * b + col] = 2 * s.bodies[b].p[col];
}

}  // namespace mechkin
