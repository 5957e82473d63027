#include "analysis/forces.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <map>

#include "constraints/couplers.hpp"

namespace mechkin {
namespace {

// d/dt of body-frame components Aᵀ v of a global vector v:  Aᵀ v̇ − ω' × Aᵀ v.
Vec3 LocalRate(const BodyKinematics& b, const Vec3& v, const Vec3& v_rate) {
  return b.A.transpose() * v_rate - b.w[0].cross(b.A.transpose() * v);
}

// Distance between two body points and its first two rates.
struct Span {
  Vec3 d, d1, d2;
  double L, L1, L2;
};

Span SpanOf(const SystemState& s, const Load& load) {
  const BodyKinematics& b1 = s.Kin(load.body1);
  const BodyKinematics& b2 = s.Kin(load.body2);
  Span sp;
  sp.d = b2.PointDerivative(load.point2, 0) - b1.PointDerivative(load.point1, 0);
  sp.d1 = b2.PointDerivative(load.point2, 1) - b1.PointDerivative(load.point1, 1);
  sp.d2 = b2.PointDerivative(load.point2, 2) - b1.PointDerivative(load.point1, 2);
  sp.L = sp.d.norm();
  sp.L1 = sp.L > 0 ? sp.d.dot(sp.d1) / sp.L : 0;
  sp.L2 = sp.L > 0 ? (sp.d1.dot(sp.d1) + sp.d.dot(sp.d2) - sp.L1 * sp.L1) / sp.L : 0;
  return sp;
}

// The body whose joint frame reports joint `jt`'s reaction: body2, or body1 when
// body2 is ground (minus the reaction on body1: action and reaction, §4).
struct ReportSide {
  BodyIndex body;
  const JointFrame& frame;
  double sign;
};

ReportSide ReportSideOf(const Joint& jt) {
  if (jt.body2 != kGround) return {jt.body2, jt.frame2, 1.0};
  return {jt.body1, jt.frame1, -1.0};
}

double Tension(const Load& l, const Span& sp) { return l.stiffness * (sp.L - l.free_length) + l.damping * sp.L1 + l.preload; }

}  // namespace

ForceSolver::ForceSolver(const ConstraintSystem& sys, const RowSelection& selection, int order)
    : sys_(sys), model_(sys.model()), selection_(selection), order_(order) {
  const int n6 = 6 * sys.num_bodies();
  redundant_ = !selection.set_aside.empty();
  R_.setZero(n6);
  R_rate_.setZero(n6);
  kappa_.setZero(n6);
  lambda_.setZero(sys.num_rows());
  lambda_rate_.setZero(sys.num_rows());
}

void ForceSolver::AddPointForce(const SystemState& s, BodyIndex b, const Vec3& local, const Vec3& f, const Vec3& f_rate,
                                bool rates) {
  if (b == kGround) return;
  const BodyKinematics& k = s.bodies[b];
  R_.segment<3>(6 * b) += f;
  R_.segment<3>(6 * b + 3) += local.cross(k.A.transpose() * f);
  if (!rates) return;
  R_rate_.segment<3>(6 * b) += f_rate;
  R_rate_.segment<3>(6 * b + 3) += local.cross(LocalRate(k, f, f_rate));
}

void ForceSolver::AddBodyTorque(const SystemState&, BodyIndex b, const Vec3& torque_local, const Vec3& rate_local,
                                bool rates) {
  if (b == kGround) return;
  R_.segment<3>(6 * b + 3) += torque_local;
  if (rates) R_rate_.segment<3>(6 * b + 3) += rate_local;
}

// Gravity on the centre and minus the inertial force and torque (R = Q^A − M q̈).
void ForceSolver::AddInertia(const SystemState& s, int b, bool rates) {
  const Inertia& in = *model_.bodies[b].inertia;
  const BodyKinematics& k = s.bodies[b];
  const Vec3 a_c = k.PointDerivative(in.center, 2);
  const Vec3 weight = in.mass * model_.gravity;
  const Vec3 w = k.w[0], w1 = k.w[1], w2 = k.w[2];
  const Vec3 Jw = in.moments * w;
  AddPointForce(s, b, in.center, weight, Vec3::Zero(), rates);
  R_.segment<3>(6 * b) -= in.mass * a_c;
  R_.segment<3>(6 * b + 3) -= in.moments * w1 + w.cross(Jw) + in.mass * in.center.cross(k.A.transpose() * a_c);
  if (!rates) return;
  const Vec3 j_c = k.PointDerivative(in.center, 3);
  R_rate_.segment<3>(6 * b) -= in.mass * j_c;
  R_rate_.segment<3>(6 * b + 3) -= in.moments * w2 + w1.cross(Jw) + w.cross(in.moments * w1) +
                                   in.mass * in.center.cross(LocalRate(k, a_c, j_c));
}

void ForceSolver::AddSpring(const SystemState& s, const Load& load, bool rates) {
  const Span sp = SpanOf(s, load);
  if (!(sp.L > 0)) return;
  const Vec3 u = sp.d / sp.L, u1 = (sp.d1 - u * sp.L1) / sp.L;
  const double T = Tension(load, sp), T1 = load.stiffness * sp.L1 + load.damping * sp.L2;
  const Vec3 f = T * u, f1 = T1 * u + T * u1;  // pulls body1's point towards body2's
  AddPointForce(s, load.body1, load.point1, f, f1, rates);
  AddPointForce(s, load.body2, load.point2, -f, -f1, rates);
}

void ForceSolver::AddLoads(const SystemState& s, bool rates) {
  for (const Load& load : model_.loads) {
    if (load.kind == LoadKind::Spring) {
      AddSpring(s, load, rates);
      continue;
    }
    Vec3 v, v1;
    for (int a = 0; a < 3; ++a) {
      const Jet j = load.components[a].Eval(s.t);
      v[a] = j.c[0];
      v1[a] = j.c[1];
    }
    const BodyKinematics& k = s.bodies[load.body1];
    if (load.kind == LoadKind::Force) {
      const Vec3 f = load.in_body_axes ? Vec3(k.A * v) : v;
      const Vec3 f1 = load.in_body_axes ? Vec3(k.A * (k.w[0].cross(v) + v1)) : v1;
      AddPointForce(s, load.body1, load.point1, f, f1, rates);
    } else if (load.in_body_axes) {
      AddBodyTorque(s, load.body1, v, v1, rates);
    } else {
      AddBodyTorque(s, load.body1, k.A.transpose() * v, LocalRate(k, v, v1), rates);
    }
  }
}

void ForceSolver::GeneralizedForces(const SystemState& s, bool rates) {
  R_.setZero();
  R_rate_.setZero();
  for (int b = 0; b < model_.num_bodies(); ++b)
    if (model_.bodies[b].inertia) AddInertia(s, b, rates);
  AddLoads(s, rates);
}

// κ(λ) = (d/dt Φ_qᵀ) λ, assembled from every family (§1.8).
void ForceSolver::Kappa(const SystemState& s) {
  kappa_.setZero();
  for (size_t e = 0; e < sys_.entries().size(); ++e) {
    const ConstraintEntry& en = sys_.entries()[e];
    KappaTerms k;
    en.constraint->CalcKappa(MakeInput(sys_, s, e), lambda_.data() + en.first_row, &k);
    for (int side = 0; side < en.constraint->num_sides(); ++side) {
      const BodyIndex b = en.constraint->body(side);
      if (b != kGround) kappa_.segment<3>(6 * b) += k.F(side), kappa_.segment<3>(6 * b + 3) += k.T(side);
    }
  }
}

// Φ_qᵀ λ = rhs over all rows: with the active rows a square solve with the
// step's factorization (set-aside rows carry 0); with redundant rows, the
// minimum-norm solution over all rows, whose determinate components are unique.
void ForceSolver::Multipliers(KinematicsWorkspace& ws, const SystemState& s, const Eigen::VectorXd& rhs,
                              Eigen::VectorXd* lambda) {
  lambda->setZero(sys_.num_rows());
  if (redundant_ && 6 * sys_.num_bodies() <= 1200) {
    CalcJacobianDense(sys_, s, Formulation::Omega, &J_);
    *lambda = J_.transpose().completeOrthogonalDecomposition().solve(rhs);
    return;
  }
  if (!SolveTranspose(ws, rhs, &lambda_active_)) throw std::runtime_error("forces need the whole-system factorization");
  for (size_t r = 0; r < selection_.active.size(); ++r) (*lambda)[selection_.active[r]] = lambda_active_[r];
}

// Rows whose multiplier changes along the null space of Φ_allᵀ: their reaction
// components are not determined by statics alone.
void ForceSolver::FindIndeterminate(const SystemState& s) {
  checked_indeterminate_ = true;
  if (!redundant_ || 6 * sys_.num_bodies() > 1200) return;
  CalcJacobianDense(sys_, s, Formulation::Omega, &J_);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J_, Eigen::ComputeFullU);
  const auto& sv = svd.singularValues();
  int rank = 0;
  for (int k = 0; k < sv.size(); ++k) rank += sv[k] > 1e-9 * sv[0];
  const Eigen::MatrixXd null = svd.matrixU().rightCols(J_.rows() - rank);
  std::map<std::string, std::string> by_joint;
  for (int row = 0; row < J_.rows(); ++row)
    if (null.row(row).norm() > 1e-8) {
      std::string& text = by_joint[sys_.SourceName(row)];
      const std::string what = sys_.DescribeRow(row);
      text += (text.empty() ? "" : "; ") + what.substr(what.find(':') + 2);
    }
  for (const auto& [joint, what] : by_joint) indeterminate_.push_back("joint `" + joint + "`: " + what);
}

void ForceSolver::Solve(KinematicsWorkspace& ws, const SystemState& s, ForceResults* out) {
  const bool rates = order_ >= 3;
  if (!checked_indeterminate_) FindIndeterminate(s);
  GeneralizedForces(s, rates);
  Multipliers(ws, s, R_, &lambda_);
  if (rates) {
    Kappa(s);
    rhs_ = R_rate_ - kappa_;
    Multipliers(ws, s, rhs_, &lambda_rate_);
  }
  out->rates = rates;
  Efforts(s, out);
  Reactions(s, out);
  CouplerEfforts(s, out);
  ToothForces(s, out);
  Energies(s, out);
}

// effort = −λ ∂Φ/∂c for the driver's coordinate c: 1 for angles and slides
// (Φ = c − f), 2c for a distance driver (Φ = dᵀd − f², §3.7).
void ForceSolver::Efforts(const SystemState& s, ForceResults* out) const {
  const size_t nd = model_.drivers.size();
  out->effort.assign(nd, 0);
  out->effort_rate.assign(nd, 0);
  out->power.assign(nd, 0);
  out->power_rate.assign(nd, 0);
  for (const ConstraintEntry& en : sys_.entries()) {
    if (!en.from_driver) continue;
    const int d = en.source;
    const Jet& f = s.driver_values[d];
    const bool distance = model_.drivers[d].kind == DriverKind::Distance;
    const double g = distance ? 2 * f.c[0] : 1, g1 = distance ? 2 * f.c[1] : 0;
    const double lam = lambda_[en.first_row], lam1 = lambda_rate_[en.first_row];
    out->effort[d] = -lam * g;
    out->effort_rate[d] = -(lam1 * g + lam * g1);
    out->power[d] = out->effort[d] * f.c[1];
    out->power_rate[d] = out->effort_rate[d] * f.c[1] + out->effort[d] * f.Derivative(2);
  }
}

void ForceSolver::Reactions(const SystemState& s, ForceResults* out) const {
  const size_t nj = model_.joints.size();
  for (auto* v : {&out->force, &out->moment, &out->force_rate, &out->moment_rate, &out->force_joint, &out->moment_joint,
                  &out->force_joint_rate, &out->moment_joint_rate})
    v->assign(nj, Vec3::Zero());
  for (size_t j = 0; j < nj; ++j) {
    const ReportSide side = ReportSideOf(model_.joints[j]);
    const BodyIndex b = side.body;
    const double sign = side.sign;
    const JointFrame& frame = side.frame;
    const BodyKinematics& k = s.bodies[b];
    Vec3 F = Vec3::Zero(), T = Vec3::Zero(), F1 = Vec3::Zero(), T1 = Vec3::Zero();
    for (size_t e = 0; e < sys_.entries().size(); ++e) {
      const ConstraintEntry& en = sys_.entries()[e];
      if (en.from_driver || en.from_coupler || en.source != static_cast<int>(j)) continue;
      const ConstraintInput in = MakeInput(sys_, s, e);
      JacobianBlocks blocks;
      en.constraint->CalcJacobian(in, &blocks);
      KappaTerms kap;
      en.constraint->CalcKappa(in, lambda_.data() + en.first_row, &kap);
      const bool as_j = en.constraint->body_j() == b;
      const int m = en.constraint->size();
      const auto lam = lambda_.segment(en.first_row, m), lam1 = lambda_rate_.segment(en.first_row, m);
      const auto& Jr = as_j ? blocks.r_j : blocks.r_i;
      const auto& Jp = as_j ? blocks.pi_j : blocks.pi_i;
      F -= Jr.topRows(m).transpose() * lam;
      T -= Jp.topRows(m).transpose() * lam;
      F1 -= Jr.topRows(m).transpose() * lam1 + (as_j ? kap.F_j : kap.F_i);
      T1 -= Jp.topRows(m).transpose() * lam1 + (as_j ? kap.T_j : kap.T_i);
    }
    // About the joint origin (body frame), then global and joint-frame components (§4).
    const Vec3 sP = frame.origin;
    const Vec3 TP = T - sP.cross(k.A.transpose() * F);
    const Vec3 TP1 = T1 - sP.cross(LocalRate(k, F, F1));
    Mat3 C;
    C << frame.f, frame.g, frame.h;
    out->force[j] = sign * F;
    out->moment[j] = sign * (k.A * TP);
    out->force_rate[j] = sign * F1;
    out->moment_rate[j] = sign * (k.A * (k.w[0].cross(TP) + TP1));
    out->force_joint[j] = sign * (C.transpose() * (k.A.transpose() * F));
    out->moment_joint[j] = sign * (C.transpose() * TP);
    out->force_joint_rate[j] = sign * (C.transpose() * LocalRate(k, F, F1));
    out->moment_joint_rate[j] = sign * (C.transpose() * TP1);
  }
}

// Q_k = −c_k λ on each coordinate of each coupler and the power −Q_1 q̇_1 (§3.11).
void ForceSolver::CouplerEfforts(const SystemState& s, ForceResults* out) const {
  const size_t nc = model_.couplers.size();
  out->coupler_effort.assign(nc, {0, 0, 0});
  out->coupler_effort_rate.assign(nc, {0, 0, 0});
  out->coupler_power.assign(nc, 0);
  out->coupler_power_rate.assign(nc, 0);
  for (size_t e = 0; e < sys_.entries().size(); ++e) {
    const ConstraintEntry& en = sys_.entries()[e];
    if (!en.from_coupler) continue;
    const auto& c = static_cast<const CouplerConstraint&>(*en.constraint);
    const double lam = lambda_[en.first_row], lam1 = lambda_rate_[en.first_row];
    for (int k = 0; k < c.num_terms(); ++k) {
      out->coupler_effort[en.source][k] = -c.coefficient(k) * lam;
      out->coupler_effort_rate[en.source][k] = -c.coefficient(k) * lam1;
    }
    const ConstraintInput in = MakeInput(sys_, s, e);
    const double q1 = c.CoordinateDerivative(in, 0, 1), q2 = order_ >= 2 ? c.CoordinateDerivative(in, 0, 2) : 0;
    const double Q = out->coupler_effort[en.source][0], Q1 = out->coupler_effort_rate[en.source][0];
    out->coupler_power[en.source] = -Q * q1;
    out->coupler_power_rate[en.source] = -(Q1 * q1 + Q * q2);
  }
}

// §3.11.1: a gear with a pitch radius meshes by a tooth force f on gear 1 at the
// pitch point (−f on gear 2), tangential part Q₁/ρ₁, radial part |Q₁/ρ₁| tan φ.
// Its difference from the coupler's torques is an equilibrated set that the two
// bearings on the common frame take: joint1's reaction on gear 1 changes by −f,
// joint2's on gear 2 by +f and, about joint2's origin, by a h × f (a: the origins'
// axial offset). In the frame body's axes, where the mesh geometry is constant.
void ForceSolver::ToothForces(const SystemState& s, ForceResults* out) const {
  for (size_t c = 0; c < model_.couplers.size(); ++c) {
    if (!model_.couplers[c].mesh) continue;
    const GearMesh& m = *model_.couplers[c].mesh;
    const BodyKinematics& k = s.Kin(m.frame);
    const double Ft = out->coupler_effort[c][0] / m.pitch_radius;
    const double Ft1 = out->coupler_effort_rate[c][0] / m.pitch_radius;
    const Vec3 tangent = m.axis.cross(m.radial), radial = m.radial_sign * m.tan_pressure * m.radial;
    const Vec3 f = Ft * tangent + std::abs(Ft) * radial;
    const Vec3 f1 = Ft1 * tangent + (Ft < 0 ? -Ft1 : Ft1) * radial;
    const Vec3 moment = m.axial_offset * m.axis.cross(f), moment1 = m.axial_offset * m.axis.cross(f1);
    const Vec3 zero = Vec3::Zero();
    AddReactionChange(s, model_.couplers[c].coordinates[0].joint, k, -f, -f1, zero, zero, out);
    AddReactionChange(s, model_.couplers[c].coordinates[1].joint, k, f, f1, moment, moment1, out);
  }
}

// Adds a change of joint j's reported reaction given in the axes of body `k` (and
// its rate there) to the global and joint-frame columns.
void ForceSolver::AddReactionChange(const SystemState& s, int j, const BodyKinematics& k, const Vec3& force,
                                    const Vec3& force1, const Vec3& moment, const Vec3& moment1,
                                    ForceResults* out) const {
  const Vec3 F = k.A * force, F1 = k.A * (k.w[0].cross(force) + force1);
  const Vec3 M = k.A * moment, M1 = k.A * (k.w[0].cross(moment) + moment1);
  const ReportSide side = ReportSideOf(model_.joints[j]);
  const BodyKinematics& b = s.Kin(side.body);
  Mat3 C;
  C << side.frame.f, side.frame.g, side.frame.h;
  out->force[j] += F;
  out->moment[j] += M;
  out->force_joint[j] += C.transpose() * (b.A.transpose() * F);
  out->moment_joint[j] += C.transpose() * (b.A.transpose() * M);
  if (!out->rates) return;
  out->force_rate[j] += F1;
  out->moment_rate[j] += M1;
  out->force_joint_rate[j] += C.transpose() * LocalRate(b, F, F1);
  out->moment_joint_rate[j] += C.transpose() * LocalRate(b, M, M1);
}

// Kinetic and potential (gravity, springs) energy and the balance
// Σ driver power + Σ load power (forces, torques, dampers) − d(T + V)/dt.
void ForceSolver::Energies(const SystemState& s, ForceResults* out) const {
  double T = 0, V = 0, dE = 0, power = 0;
  for (double p : out->power) power += p;
  for (int b = 0; b < model_.num_bodies(); ++b) {
    if (!model_.bodies[b].inertia) continue;
    const Inertia& in = *model_.bodies[b].inertia;
    const BodyKinematics& k = s.bodies[b];
    const Vec3 v = k.PointDerivative(in.center, 1), a = k.PointDerivative(in.center, 2);
    T += 0.5 * in.mass * v.squaredNorm() + 0.5 * k.w[0].dot(in.moments * k.w[0]);
    V -= in.mass * model_.gravity.dot(k.PointDerivative(in.center, 0));
    dE += in.mass * v.dot(a) + k.w[0].dot(in.moments * k.w[1]) - in.mass * model_.gravity.dot(v);
  }
  for (const Load& load : model_.loads) {
    if (load.kind == LoadKind::Spring) {
      const Span sp = SpanOf(s, load);
      V += 0.5 * load.stiffness * (sp.L - load.free_length) * (sp.L - load.free_length) + load.preload * sp.L;
      dE += (load.stiffness * (sp.L - load.free_length) + load.preload) * sp.L1;
      power -= load.damping * sp.L1 * sp.L1;
      continue;
    }
    const BodyKinematics& k = s.bodies[load.body1];
    Vec3 c;
    for (int a = 0; a < 3; ++a) c[a] = load.components[a].Eval(s.t).c[0];
    const Vec3 global = load.in_body_axes ? Vec3(k.A * c) : c;
    power += load.kind == LoadKind::Force ? global.dot(k.PointDerivative(load.point1, 1)) : global.dot(k.A * k.w[0]);
  }
  out->kinetic = T;
  out->potential = V;
  out->balance = power - dE;
}

}  // namespace mechkin
