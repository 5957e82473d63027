// One conformance harness for every constraint family (constraints.md §3):
// at ≥ 1000 seeded random poses and smooth trajectories per family it checks
//   * Φ against an independent re-implementation,
//   * Φ_r, Φ_π' against central differences on the rotation manifold,
//   * Φ_p = 2Φ_π'G against central differences of Φ(r, p/|p|),
//   * ν, γ, η, σ (ω' and p versions) against the exact time derivatives of
//     Φ(q(t), t) from test-only Taylor jets (test_jet.hpp): d^kΦ/dt^k = Φ_q q^(k) − RHS_k,
//   * κ against 4th-order central differences in time of Φ_qᵀλ.
// The trajectories do not satisfy the constraints (strong form), except that
// rotation drivers and screws move on their joint's rotation manifold.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <memory>
#include <random>

#include "constraints/couplers.hpp"
#include "constraints/families.hpp"
#include "test_jet.hpp"

namespace mechkin {
namespace conformance_test {

using testing::M3;
using testing::Q4;
using testing::TJet;
using testing::V3;

struct BodyTraj {
  bool ground = false;
  V3 r;
  Q4 p;
  M3 A;
  V3 w;  // ω' (body frame)
};

Vec3 Rand3(std::mt19937& g, double s = 1) {
  std::uniform_real_distribution<double> u(-s, s);
  return Vec3(u(g), u(g), u(g));
}

// ω̃' = AᵀȦ, read off the jets (independent of G(p)).
void FinishBody(BodyTraj* b) {
  b->A = testing::RotationOf(b->p);
  M3 Ad;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Ad[i][j] = b->A[i][j].Dt();
  auto W = [&](int i, int j) { return b->A[0][i] * Ad[0][j] + b->A[1][i] * Ad[1][j] + b->A[2][i] * Ad[2][j]; };
  b->w = {W(2, 1), W(0, 2), W(1, 0)};
}

Q4 NormalizedQuat(const std::array<TJet, 4>& P) {
  const TJet n = testing::Sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2] + P[3] * P[3]);
  const TJet inv = testing::Inverse(n);
  return {P[0] * inv, P[1] * inv, P[2] * inv, P[3] * inv};
}

// A random smooth body motion. special: 0 generic, 1 e0 = 0 exactly (180°), 2 e0 ≈ 1e-9.
BodyTraj RandomBody(std::mt19937& g, int special) {
  BodyTraj b;
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 3; ++i) {
    b.r[i].c[0] = u(g);
    for (int k = 1; k <= 5; ++k) b.r[i].c[k] = u(g) / k;
  }
  std::array<TJet, 4> P;
  Vec4 p0(u(g), u(g), u(g), u(g));
  if (special == 1) p0[0] = 0;
  if (special == 2) p0[0] = 1e-9;
  p0.normalize();
  for (int i = 0; i < 4; ++i) {
    P[i].c[0] = p0[i];
    for (int k = 1; k <= 5; ++k) P[i].c[k] = 0.8 * u(g) / k;
  }
  b.p = NormalizedQuat(P);
  FinishBody(&b);
  return b;
}

BodyTraj Ground() {
  BodyTraj b;
  b.ground = true;
  b.r = {TJet(0), TJet(0), TJet(0)};
  b.p = {TJet(1), TJet(0), TJet(0), TJet(0)};
  FinishBody(&b);
  return b;
}

// Body j moving on the rotation manifold of body i about local axis h'_i:
// A_j = A_i R(h'_i, θ(t)) A(q0); translation free.
BodyTraj OnRotationManifold(std::mt19937& g, const BodyTraj& bi, const Vec3& h_local, const TJet& theta, const Vec4& q0) {
  BodyTraj b = RandomBody(g, 0);
  TJet s, c;
  testing::SinCos(0.5 * theta, &s, &c);
  const Q4 qh = {c, h_local.x() * s, h_local.y() * s, h_local.z() * s};
  const Q4 q0j = {TJet(q0[0]), TJet(q0[1]), TJet(q0[2]), TJet(q0[3])};
  b.p = testing::QuatProduct(testing::QuatProduct(bi.p, qh), q0j);
  FinishBody(&b);
  return b;
}

BodyKinematics KinAt0(const BodyTraj& b) {
  BodyKinematics k;
  if (b.ground) return k;
  k.SetPose(Vec3(b.r[0].c[0], b.r[1].c[0], b.r[2].c[0]), Vec4(b.p[0].c[0], b.p[1].c[0], b.p[2].c[0], b.p[3].c[0]));
  for (int o = 1; o <= 4; ++o) k.r[o] = Vec3(b.r[0].D(o), b.r[1].D(o), b.r[2].D(o));
  for (int o = 0; o < 4; ++o) k.w[o] = Vec3(b.w[0].D(o), b.w[1].D(o), b.w[2].D(o));
  k.UpdateDerived(4);
  return k;
}

// Pose-only kinematics at time t (for κ by differences in time), with ω' for Jacobians
// that are evaluated off t = 0.
BodyKinematics KinAt(const BodyTraj& b, double t) {
  BodyKinematics k;
  if (b.ground) return k;
  Vec4 p(b.p[0].At(t), b.p[1].At(t), b.p[2].At(t), b.p[3].At(t));
  k.SetPose(Vec3(b.r[0].At(t), b.r[1].At(t), b.r[2].At(t)), p.normalized());
  return k;
}

struct Case {
  std::unique_ptr<Constraint> c;
  BodyTraj bi, bj;
  TJet f;                 // driver function (zero for joints)
  double angle_ref = 0;   // near θ(0)
  std::function<std::vector<TJet>(const BodyTraj&, const BodyTraj&, const TJet&)> phi;  // independent Φ(t)
};

struct Errors {
  double phi = 0, phi_extended = 0, jac = 0, jac_p = 0, rhs_w = 0, rhs_p = 0, kappa = 0;
  double phi_series = 0, pose_series = 0, phi_quad = 0;  // CalcPhiJet, JetPoseOf, CalcPhiQuad
  void Max(const Errors& o) {
    phi = std::max(phi, o.phi);
    phi_series = std::max(phi_series, o.phi_series); pose_series = std::max(pose_series, o.pose_series);
    phi_quad = std::max(phi_quad, o.phi_quad);
    phi_extended = std::max(phi_extended, o.phi_extended); jac = std::max(jac, o.jac); jac_p = std::max(jac_p, o.jac_p);
    rhs_w = std::max(rhs_w, o.rhs_w); rhs_p = std::max(rhs_p, o.rhs_p); kappa = std::max(kappa, o.kappa);
  }
};

Jet ToJet(const TJet& t) {
  Jet j;
  for (int k = 0; k <= kMaxOrder; ++k) j.c[k] = t.c[k];
  return j;
}

double RelErr(double a, double b, double scale) { return std::abs(a - b) / std::max(scale, 1e-300); }

ExtendedJet ToExtendedJet(const TJet& t) {
  ExtendedJet j;
  for (int k = 0; k <= kMaxOrder; ++k) j.c[k] = t.c[k];
  return j;
}

// The measured error bounds' forms of Φ (constraints.md §8, "Measured"): on Taylor series
// (CalcPhiJet, with the poses' series from their rates, JetPoseOf), every coefficient
// to 4th order against the independent Φ(t)'s; in quadruple precision (CalcPhiQuad,
// where the family has it) against its value. And the series of A against the
// trajectory's own A(t).
void CheckSeriesForms(const Constraint& c, const std::vector<const BodyTraj*>& sides, const JetInput& in,
                      const std::vector<TJet>& phi_t, Errors* e) {
  ExtendedJet phi_j[kMaxRows];
  c.CalcPhiJet(in, phi_j);
  for (int r = 0; r < c.size(); ++r) {
    double scale = 1;
    for (int k = 0; k <= kMaxOrder; ++k) scale = std::max(scale, std::abs(phi_t[r].c[k]));
    for (int k = 0; k <= kMaxOrder; ++k)
      e->phi_series = std::max(e->phi_series, RelErr(static_cast<double>(phi_j[r].c[k]), phi_t[r].c[k], scale));
  }
  for (int side = 0; side < c.num_sides(); ++side) {
    if (sides[side]->ground) continue;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int k = 0; k <= kMaxOrder; ++k)
          e->pose_series = std::max(e->pose_series, std::abs(static_cast<double>(in.Side(side).A(a, b).c[k]) - sides[side]->A[a][b].c[k]));
  }
}

// Φ in extended precision (the accuracy phase of the position solve), on series and in
// quadruple precision (the measured error bounds) against the independent Φ(t).
void CheckPrecisionForms(const Constraint& c, const Case& cs, const BodyKinematics& ki, const BodyKinematics& kj,
                         const std::vector<TJet>& phi_t, Errors* e) {
  const int m = c.size();
  const ExtendedPose xi = ExtendedPose::Of(ki), xj = ExtendedPose::Of(kj);
  Real phi_x[kMaxRows];
  c.CalcPhiExtended(ExtendedInput{xi, xj, static_cast<Real>(cs.f.c[0]), cs.angle_ref}, phi_x);
  for (int r = 0; r < m; ++r)
    e->phi_extended = std::max(e->phi_extended, RelErr(static_cast<double>(phi_x[r]), phi_t[r].c[0], 1 + std::abs(phi_t[r].c[0])));
  const JetPose si = JetPoseOf(ki, xi.A, kMaxOrder), sj = JetPoseOf(kj, xj.A, kMaxOrder);
  CheckSeriesForms(c, {&cs.bi, &cs.bj}, JetInput{si, sj, ToExtendedJet(cs.f), cs.angle_ref}, phi_t, e);
  const QuadPose qi{ki.r[0].cast<Quad>(), ki.A.cast<Quad>()}, qj{kj.r[0].cast<Quad>(), kj.A.cast<Quad>()};
  Quad phi_q[kMaxRows];
  if (c.CalcPhiQuad(QuadInput{qi, qj, static_cast<Quad>(cs.f.c[0]), cs.angle_ref}, phi_q))
    for (int r = 0; r < m; ++r)
      e->phi_quad = std::max(e->phi_quad, RelErr(static_cast<double>(phi_q[r]), phi_t[r].c[0], 1 + std::abs(phi_t[r].c[0])));
}

Errors CheckCase(const Case& cs) {
  Errors e;
  const Constraint& c = *cs.c;
  const int m = c.size();
  const BodyKinematics ki = KinAt0(cs.bi), kj = KinAt0(cs.bj);
  ConstraintInput in{ki, kj, ToJet(cs.f), cs.angle_ref};
  const std::vector<TJet> phi_t = cs.phi(cs.bi, cs.bj, cs.f);
  double phi[kMaxRows];
  c.CalcPhi(in, phi);
  for (int r = 0; r < m; ++r) e.phi = std::max(e.phi, RelErr(phi[r], phi_t[r].c[0], 1 + std::abs(phi_t[r].c[0])));
  CheckPrecisionForms(c, cs, ki, kj, phi_t, &e);

  // Jacobian blocks vs central differences on the manifold (body-frame rotation increments).
  JacobianBlocks J;
  c.CalcJacobian(in, &J);
  const double h = 1e-6;
  // Scale: the blocks, or |Φ| itself where the gradient is small (near-parallel DOT_1),
  // since differences of Φ are only accurate to eps·|Φ|/h.
  double jscale = std::max({J.r_i.norm(), J.r_j.norm(), J.pi_i.norm(), J.pi_j.norm(), 1e-12});
  for (int r = 0; r < m; ++r) jscale = std::max(jscale, std::abs(phi[r]));
  for (int side = 0; side < 2; ++side) {
    if ((side == 0 ? cs.bi : cs.bj).ground) continue;
    for (int col = 0; col < 6; ++col) {
      double fp[kMaxRows], fm[kMaxRows];
      for (int sgn : {1, -1}) {
        BodyKinematics kp = side == 0 ? ki : kj;
        Vec3 d = Vec3::Zero();
        d[col % 3] = sgn * h;
        if (col < 3) kp.r[0] += d;
        else kp.SetPose(kp.r[0], QuatMultiply(kp.p, QuatFromAxisAngle(Vec3::Unit(col % 3), sgn * h)));
        ConstraintInput ip{side == 0 ? kp : ki, side == 0 ? kj : kp, in.f, in.angle_ref};
        c.CalcPhi(ip, sgn > 0 ? fp : fm);
      }
      for (int r = 0; r < m; ++r) {
        const double fd = (fp[r] - fm[r]) / (2 * h);
        const RowBlock& B = col < 3 ? (side == 0 ? J.r_i : J.r_j) : (side == 0 ? J.pi_i : J.pi_j);
        e.jac = std::max(e.jac, RelErr(fd, B(r, col % 3), jscale));
      }
    }
  }
  // Φ_p vs differences of Φ(r, p/|p|).
  Eigen::Matrix<double, kMaxRows, 4> Pi, Pj;
  CalcPVersionJacobian(c, in, J, &Pi, &Pj);
  for (int side = 0; side < 2; ++side) {
    if ((side == 0 ? cs.bi : cs.bj).ground) continue;
    for (int col = 0; col < 4; ++col) {
      double fp[kMaxRows], fm[kMaxRows];
      for (int sgn : {1, -1}) {
        BodyKinematics kp = side == 0 ? ki : kj;
        Vec4 p = kp.p;
        p[col] += sgn * h;
        kp.SetPose(kp.r[0], p.normalized());
        ConstraintInput ip{side == 0 ? kp : ki, side == 0 ? kj : kp, in.f, in.angle_ref};
        c.CalcPhi(ip, sgn > 0 ? fp : fm);
      }
      for (int r = 0; r < m; ++r)
        e.jac_p = std::max(e.jac_p, RelErr((fp[r] - fm[r]) / (2 * h), (side == 0 ? Pi : Pj)(r, col), jscale));
    }
  }
  // Right-hand sides, both versions, orders 1..4.
  for (int k = 1; k <= 4; ++k) {
    double rw[kMaxRows], rp[kMaxRows];
    c.CalcRhs(in, k, rw);
    CalcPVersionRhs(c, in, k, rp);
    for (int r = 0; r < m; ++r) {
      double lhs_w = 0, lhs_p = 0, scale = std::abs(phi_t[r].D(k));
      for (int side = 0; side < 2; ++side) {
        const BodyTraj& b = side == 0 ? cs.bi : cs.bj;
        if (b.ground) continue;
        const RowBlock& Br = side == 0 ? J.r_i : J.r_j;
        const RowBlock& Bw = side == 0 ? J.pi_i : J.pi_j;
        const auto& Bp = side == 0 ? Pi : Pj;
        for (int a = 0; a < 3; ++a) {
          const double tr = Br(r, a) * b.r[a].D(k), tw = Bw(r, a) * b.w[a].D(k - 1);
          lhs_w += tr + tw;
          lhs_p += tr;
          scale = std::max({scale, std::abs(tr), std::abs(tw)});
        }
        for (int a = 0; a < 4; ++a) {
          const double tp = Bp(r, a) * b.p[a].D(k);
          lhs_p += tp;
          scale = std::max(scale, std::abs(tp));
        }
      }
      const double want_w = lhs_w - phi_t[r].D(k), want_p = lhs_p - phi_t[r].D(k);
      e.rhs_w = std::max(e.rhs_w, RelErr(rw[r], want_w, std::max(scale, std::abs(want_w))));
      e.rhs_p = std::max(e.rhs_p, RelErr(rp[r], want_p, std::max(scale, std::abs(want_p))));
    }
  }
  // κ vs 4th-order central differences in time of Φ_qᵀλ.
  std::mt19937 g(7);
  double lambda[kMaxRows];
  for (int r = 0; r < m; ++r) lambda[r] = std::uniform_real_distribution<double>(-1, 1)(g);
  KappaTerms kap;
  c.CalcKappa(in, lambda, &kap);
  const double dt = 1e-3;
  Eigen::Matrix<double, 12, 1> fd = Eigen::Matrix<double, 12, 1>::Zero();
  const double w5[4] = {1, -8, 8, -1}, t5[4] = {-2, -1, 1, 2};
  for (int s = 0; s < 4; ++s) {
    const BodyKinematics a = KinAt(cs.bi, t5[s] * dt), b = KinAt(cs.bj, t5[s] * dt);
    Jet f;
    f.c[0] = cs.f.At(t5[s] * dt);
    ConstraintInput is{a, b, f, in.angle_ref};
    JacobianBlocks Js;
    c.CalcJacobian(is, &Js);
    Eigen::Map<const Eigen::VectorXd> l(lambda, m);
    fd.segment<3>(0) += w5[s] * Js.r_i.topRows(m).transpose() * l;
    fd.segment<3>(3) += w5[s] * Js.pi_i.topRows(m).transpose() * l;
    fd.segment<3>(6) += w5[s] * Js.r_j.topRows(m).transpose() * l;
    fd.segment<3>(9) += w5[s] * Js.pi_j.topRows(m).transpose() * l;
  }
  fd /= 12 * dt;
  Eigen::Matrix<double, 12, 1> got;
  got << kap.F_i, kap.T_i, kap.F_j, kap.T_j;
  if (cs.bi.ground) { fd.head<6>().setZero(); got.head<6>().setZero(); }
  if (cs.bj.ground) { fd.tail<6>().setZero(); got.tail<6>().setZero(); }
  e.kappa = (fd - got).norm() / std::max({fd.norm(), got.norm(), jscale * 1e-3});
  return e;
}

// ---- the families -------------------------------------------------------------

using Maker = std::function<Case(std::mt19937&, int pose_kind)>;

V3 PointOf(const BodyTraj& b, const Vec3& s) { return testing::Add(b.r, testing::MulMV(b.A, testing::Const(s.data()))); }
V3 VecOf(const BodyTraj& b, const Vec3& a) { return testing::MulMV(b.A, testing::Const(a.data())); }

TJet RandomPoly(std::mt19937& g, double c0, double scale) {
  TJet f(c0);
  std::uniform_real_distribution<double> u(-scale, scale);
  for (int k = 1; k <= 5; ++k) f.c[k] = u(g);
  return f;
}

// Pose kinds cycle through generic, e0 = 0, e0 ≈ 1e-9 and a ground body i.
BodyTraj BodyI(std::mt19937& g, int kind) { return kind == 3 ? Ground() : RandomBody(g, kind % 3); }

Case MakeSpherical(std::mt19937& g, int kind) {
  Case cs;
  const Vec3 si = Rand3(g), sj = Rand3(g);
  cs.bi = BodyI(g, kind);
  cs.bj = RandomBody(g, (kind + 1) % 3);
  cs.c = std::make_unique<SphericalConstraint>(cs.bi.ground ? kGround : 0, 1, si, sj);
  cs.phi = [si, sj](const BodyTraj& a, const BodyTraj& b, const TJet&) {
    const V3 d = testing::Sub(PointOf(b, sj), PointOf(a, si));
    return std::vector<TJet>{d[0], d[1], d[2]};
  };
  return cs;
}

Case MakeDistance(std::mt19937& g, int kind, bool driven) {
  Case cs;
  const Vec3 si = Rand3(g), sj = Rand3(g);
  cs.bi = BodyI(g, kind);
  cs.bj = RandomBody(g, (kind + 1) % 3);
  if (kind % 5 == 4) {
    // Points near each other: body j's point placed 1e-3 from body i's at t = 0.
    const Vec3 pi(PointOf(cs.bi, si)[0].c[0], PointOf(cs.bi, si)[1].c[0], PointOf(cs.bi, si)[2].c[0]);
    const Vec3 pj(PointOf(cs.bj, sj)[0].c[0], PointOf(cs.bj, sj)[1].c[0], PointOf(cs.bj, sj)[2].c[0]);
    const Vec3 shift = pi - pj + 1e-3 * Rand3(g).normalized();
    for (int a = 0; a < 3; ++a) cs.bj.r[a].c[0] += shift[a];
  }
  const double L = 0.7;
  cs.f = RandomPoly(g, 1.3, 0.5);
  cs.c = std::make_unique<DistanceConstraint>(cs.bi.ground ? kGround : 0, 1, si, sj, driven ? 0.0 : L);
  cs.phi = [si, sj, L, driven](const BodyTraj& a, const BodyTraj& b, const TJet& f) {
    const V3 d = testing::Sub(PointOf(b, sj), PointOf(a, si));
    return std::vector<TJet>{testing::Dot(d, d) - (driven ? f * f : TJet(L * L))};
  };
  return cs;
}

Case MakeDot1(std::mt19937& g, int kind) {
  Case cs;
  const Vec3 ai = Rand3(g), aj = Rand3(g);
  cs.bi = BodyI(g, kind);
  cs.bj = RandomBody(g, (kind + 1) % 3);
  cs.c = std::make_unique<Dot1Constraint>(cs.bi.ground ? kGround : 0, 1, ai, aj);
  cs.phi = [ai, aj](const BodyTraj& a, const BodyTraj& b, const TJet&) {
    return std::vector<TJet>{testing::Dot(VecOf(a, ai), VecOf(b, aj))};
  };
  return cs;
}

Case MakeDot2(std::mt19937& g, int kind, bool driver) {
  Case cs;
  const Vec3 ai = Rand3(g) + Vec3(0, 0, 1.5), si = Rand3(g), sj = Rand3(g);
  cs.bi = BodyI(g, kind);
  cs.bj = RandomBody(g, (kind + 1) % 3);
  cs.f = RandomPoly(g, 0.2, 0.5);
  const BodyIndex i = cs.bi.ground ? kGround : 0;
  if (driver) cs.c = std::make_unique<Dot2DistanceDriver>(i, 1, ai, si, sj);
  else cs.c = std::make_unique<Dot2Constraint>(i, 1, ai, si, sj);
  const double L = driver ? ai.norm() : 1.0;
  cs.phi = [ai, si, sj, L, driver](const BodyTraj& a, const BodyTraj& b, const TJet& f) {
    const V3 d = testing::Sub(PointOf(b, sj), PointOf(a, si));
    TJet v = (1.0 / L) * testing::Dot(VecOf(a, ai), d);
    return std::vector<TJet>{driver ? v - f : v};
  };
  return cs;
}

// Random orthonormal frame (local to body i) and a random relative offset q0.
void RandomFrames(std::mt19937& g, JointFrame* fi, JointFrame* fj, Vec4* q0) {
  fi->h = Rand3(g).normalized();
  fi->f = AnyPerpendicular(fi->h);
  fi->g = fi->h.cross(fi->f);
  fi->origin = Rand3(g);
  *q0 = Vec4(Rand3(g).norm() + 0.1, Rand3(g).x(), Rand3(g).y(), Rand3(g).z()).normalized();
  const Mat3 Q = CalcA(*q0);
  fj->f = Q.transpose() * fi->f;
  fj->g = Q.transpose() * fi->g;
  fj->h = Q.transpose() * fi->h;
  fj->origin = Rand3(g);
}

Case MakeRotationDriver(std::mt19937& g, int kind) {
  Case cs;
  JointFrame fi, fj;
  Vec4 q0;
  RandomFrames(g, &fi, &fj, &q0);
  cs.bi = BodyI(g, kind);
  const TJet theta = RandomPoly(g, std::uniform_real_distribution<double>(-30, 30)(g), 2.0);
  cs.bj = OnRotationManifold(g, cs.bi, fi.h, theta, q0);
  cs.f = RandomPoly(g, 0.3, 1.0);
  cs.angle_ref = theta.c[0] + 0.4;
  cs.c = std::make_unique<RotationDriver>(cs.bi.ground ? kGround : 0, 1, fi, fj);
  cs.phi = [theta](const BodyTraj&, const BodyTraj&, const TJet& f) { return std::vector<TJet>{theta - f}; };
  return cs;
}

Case MakeScrew(std::mt19937& g, int kind) {
  Case cs;
  JointFrame fi, fj;
  Vec4 q0;
  RandomFrames(g, &fi, &fj, &q0);
  cs.bi = BodyI(g, kind);
  const TJet theta = RandomPoly(g, std::uniform_real_distribution<double>(-30, 30)(g), 2.0);
  cs.bj = OnRotationManifold(g, cs.bi, fi.h, theta, q0);
  cs.angle_ref = theta.c[0] - 0.4;
  const double pitch = 0.37;
  cs.c = std::make_unique<ScrewConstraint>(cs.bi.ground ? kGround : 0, 1, fi, fj, pitch);
  cs.phi = [fi, fj, theta, pitch](const BodyTraj& a, const BodyTraj& b, const TJet&) {
    const V3 d = testing::Sub(PointOf(b, fj.origin), PointOf(a, fi.origin));
    return std::vector<TJet>{testing::Dot(VecOf(a, fi.h), d) - (pitch / (2 * M_PI)) * theta};
  };
  return cs;
}

constexpr int kPoses = 1000;

Errors RunFamily(const Maker& make) {
  std::mt19937 g(20261122);
  Errors worst;
  for (int n = 0; n < kPoses; ++n) worst.Max(CheckCase(make(g, n % 5)));
  return worst;
}

void ExpectConforms(const Errors& e) {
  EXPECT_LT(e.phi, 1e-12);
  EXPECT_LT(e.phi_extended, 1e-12);
  EXPECT_LT(e.phi_series, 1e-12);
  EXPECT_LT(e.pose_series, 1e-12);
  EXPECT_LT(e.phi_quad, 1e-12);
  EXPECT_LT(e.jac, 1e-7);
  EXPECT_LT(e.jac_p, 1e-7);
  // The issue asks for 1e-6; near-parallel DOT_1 loses ~3 digits to cancellation
  // (1.04e-8 seen with clang, below 1e-8 with g++: the order of the sums).
  EXPECT_LT(e.rhs_w, 1e-7);
  EXPECT_LT(e.rhs_p, 1e-7);
  EXPECT_LT(e.kappa, 1e-6);
}

TEST(Conformance, Spherical) {
  const Errors e = RunFamily(MakeSpherical);
  std::printf("[measured] spherical: series %.1e, poses' series %.1e, quadruple %.1e\n", e.phi_series, e.pose_series, e.phi_quad);
  ExpectConforms(e);
}
TEST(Conformance, SphericalSpherical) { ExpectConforms(RunFamily([](auto& g, int k) { return MakeDistance(g, k, false); })); }
TEST(Conformance, RelativeDistanceDriver) { ExpectConforms(RunFamily([](auto& g, int k) { return MakeDistance(g, k, true); })); }
TEST(Conformance, Dot1) { ExpectConforms(RunFamily(MakeDot1)); }
TEST(Conformance, Dot2) { ExpectConforms(RunFamily([](auto& g, int k) { return MakeDot2(g, k, false); })); }
TEST(Conformance, Dot2DistanceDriver) { ExpectConforms(RunFamily([](auto& g, int k) { return MakeDot2(g, k, true); })); }
// Kind 3 makes body i ground: the fixed revolute rotation driver (§3.6).
TEST(Conformance, RotationDriver) { ExpectConforms(RunFamily(MakeRotationDriver)); }
TEST(Conformance, ScrewDistanceAngle) { ExpectConforms(RunFamily(MakeScrew)); }

// Which families have the quadruple-precision Φ (the pose error of the measured bounds,
// constraints.md §8): those that read no angle; the others answer false, and the
// caller takes the long-double Φ. Its values: phi_quad in every family's harness.
TEST(Conformance, QuadruplePrecisionWhereNoAngleIsRead) {
  std::mt19937 g(7);
  const QuadPose ground, body{Eigen::Matrix<Quad, 3, 1>(1, 2, 3), Eigen::Matrix<Quad, 3, 3>::Identity()};
  const QuadInput in{ground, body, 0, 0};
  Quad phi[kMaxRows];
  EXPECT_TRUE(MakeSpherical(g, 0).c->CalcPhiQuad(in, phi));
  EXPECT_TRUE(MakeDot1(g, 0).c->CalcPhiQuad(in, phi));
  EXPECT_TRUE(MakeDot2(g, 0, true).c->CalcPhiQuad(in, phi));
  EXPECT_FALSE(MakeRotationDriver(g, 0).c->CalcPhiQuad(in, phi));
  EXPECT_FALSE(MakeScrew(g, 0).c->CalcPhiQuad(in, phi));
}

// Near-parallel DOT_1 vectors: a_j within 1e-6 rad of a_i at t = 0.
TEST(Conformance, Dot1NearParallel) {
  Errors worst;
  std::mt19937 g(99);
  for (int n = 0; n < kPoses; ++n) {
    Case cs = MakeDot1(g, n % 3);
    const Vec3 ai = Rand3(g);
    const Mat3 Ai = CalcA(Vec4(cs.bi.p[0].c[0], cs.bi.p[1].c[0], cs.bi.p[2].c[0], cs.bi.p[3].c[0]));
    const Mat3 Aj = CalcA(Vec4(cs.bj.p[0].c[0], cs.bj.p[1].c[0], cs.bj.p[2].c[0], cs.bj.p[3].c[0]));
    const Vec3 aj = Aj.transpose() * (Ai * ai + 1e-6 * Rand3(g));
    cs.c = std::make_unique<Dot1Constraint>(0, 1, ai, aj);
    cs.phi = [ai, aj](const BodyTraj& a, const BodyTraj& b, const TJet&) {
      return std::vector<TJet>{testing::Dot(VecOf(a, ai), VecOf(b, aj))};
    };
    worst.Max(CheckCase(cs));
  }
  ExpectConforms(worst);
}

// On the manifold the FRRD's blocks reduce to the seed's: Φ_π' = û'ᵀ and the p-version
// η_p = f_ttt − θ̇³/4 for a body aligned with ground at θ = 0 (§3.6).
TEST(Conformance, FixedRevoluteDriverMatchesSeedForm) {
  std::mt19937 g(3);
  JointFrame fi, fj;
  Vec4 q0(1, 0, 0, 0);
  fi.h = Rand3(g).normalized();
  fi.f = AnyPerpendicular(fi.h);
  fi.g = fi.h.cross(fi.f);
  fj = fi;
  BodyTraj gi = Ground();
  TJet theta = RandomPoly(g, 0.7, 1.0);
  theta.c[2] = 0;  // θ̈ = 0 at t = 0, so η_p reduces to f_ttt − θ̇³/4 exactly
  BodyTraj bj = OnRotationManifold(g, gi, fi.h, theta, q0);
  const BodyKinematics kj = KinAt0(bj);
  TJet f = RandomPoly(g, 0.1, 1.0);
  RotationDriver d(kGround, 0, fi, fj);
  ConstraintInput in{GroundKinematics(), kj, ToJet(f), 0.7};
  JacobianBlocks J;
  d.CalcJacobian(in, &J);
  EXPECT_LT((J.pi_j.row(0).transpose() - fj.h).norm(), 1e-12);
  double eta_p;
  CalcPVersionRhs(d, in, 3, &eta_p);
  const double thd = theta.D(1);
  EXPECT_NEAR(eta_p, f.D(3) - thd * thd * thd / 4, 1e-12 * (1 + std::abs(eta_p)));
}

// A deliberately corrupted family (sign of the η term flipped) must fail the harness.
class CorruptedSpherical : public Constraint {
 public:
  explicit CorruptedSpherical(std::unique_ptr<Constraint> inner)
      : Constraint(inner->body_i(), inner->body_j(), inner->size()), inner_(std::move(inner)) {}
  void CalcPhi(const ConstraintInput& in, double* phi) const override { inner_->CalcPhi(in, phi); }
  void CalcPhiExtended(const ExtendedInput& in, Real* phi) const override { inner_->CalcPhiExtended(in, phi); }
  void CalcPhiJet(const JetInput& in, ExtendedJet* phi) const override { inner_->CalcPhiJet(in, phi); }
  void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const override { inner_->CalcJacobian(in, J); }
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override {
    inner_->CalcRhs(in, k, rhs);
    if (k == 3) rhs[1] = -rhs[1];
  }
  void CalcKappa(const ConstraintInput& in, const double* l, KappaTerms* kap) const override { inner_->CalcKappa(in, l, kap); }
  int LengthPower() const override { return 1; }
  const char* family() const override { return "broken"; }

 private:
  std::unique_ptr<Constraint> inner_;
};

TEST(Conformance, HarnessCatchesACorruptedSign) {
  const Errors e = RunFamily([](std::mt19937& g, int k) {
    Case cs = MakeSpherical(g, k);
    cs.c = std::make_unique<CorruptedSpherical>(std::move(cs.c));
    return cs;
  });
  EXPECT_GT(e.rhs_w, 1e-3);  // the harness notices
  EXPECT_LT(e.jac, 1e-7);    // and only that
}


// ---- couplers between joint coordinates (§3.11): up to six sides ----------------

// One joint coordinate of a coupler case: body `child` turns on the rotation manifold
// of `parent` (rotation) or moves freely (slide); -1 is ground.
struct TermLayout {
  int parent, child;
  bool rotation;
};

struct CouplerCase {
  std::unique_ptr<Constraint> c;
  std::vector<BodyTraj> bodies;           // index = BodyIndex
  std::vector<double> angle_refs;         // per tracked angle
  std::function<TJet(const std::vector<BodyTraj>&)> phi;  // independent Φ(t)
};

const BodyTraj& TrajOf(const std::vector<BodyTraj>& bodies, BodyIndex b) {
  static const BodyTraj ground = Ground();
  return b == kGround ? ground : bodies[b];
}

// The coupler's input from per-body kinematics (ground: GroundKinematics).
ConstraintInput CouplerInput(const Constraint& c, const std::vector<BodyKinematics>& kin, const std::vector<double>& refs) {
  auto k = [&](int side) -> const BodyKinematics& {
    return c.body(side) == kGround ? GroundKinematics() : kin[c.body(side)];
  };
  ConstraintInput in{k(0), k(1), Jet{}, refs.empty() ? 0.0 : refs[0]};
  for (int side = 2; side < c.num_sides(); ++side) in.more[side - 2] = &k(side);
  for (size_t a = 1; a < refs.size(); ++a) in.more_angle_refs[a - 1] = refs[a];
  return in;
}

double CouplerPhiAt(const Constraint& c, const std::vector<BodyKinematics>& kin, const std::vector<double>& refs) {
  double phi;
  c.CalcPhi(CouplerInput(c, kin, refs), &phi);
  return phi;
}

// The layouts: gears on ground, on a carrier, in a chain; racks; a planetary mesh
// relative to its carrier; mixed three-coordinate couplings.
const std::vector<std::vector<TermLayout>>& CouplerLayouts() {
  static const std::vector<std::vector<TermLayout>> kLayouts = {
      {{-1, 0, true}, {-1, 1, true}},
      {{0, 1, true}, {0, 2, true}},
      {{0, 1, true}, {1, 2, true}},
      {{-1, 0, true}, {1, 2, false}},
      {{1, 0, true}, {1, 2, false}},
      {{-1, 0, true}, {-1, 1, true}, {1, 2, true}},
      {{-1, 0, true}, {0, 1, true}, {2, 3, false}},
      {{0, 1, false}, {0, 2, true}, {-1, 3, false}},
  };
  return kLayouts;
}

// A coupling whose RHS is halved: what the harness must catch.
class HalvedRhsCoupling : public CouplingConstraint {
 public:
  using CouplingConstraint::CouplingConstraint;
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override {
    CouplingConstraint::CalcRhs(in, k, rhs);
    *rhs *= 0.5;
  }
};

CouplerCase MakeCoupler(std::mt19937& g, int n, bool broken = false) {
  const std::vector<TermLayout>& layout = CouplerLayouts()[n % CouplerLayouts().size()];
  CouplerCase cs;
  cs.bodies.resize(4);
  std::vector<bool> built(4, false);
  std::vector<CoordinateTerm> terms;
  std::vector<TJet> thetas(layout.size());
  std::vector<JointFrame> f1(layout.size()), f2(layout.size());
  std::uniform_real_distribution<double> u(-2, 2);
  for (int b = 0; b < 4; ++b) cs.bodies[b] = RandomBody(g, (n + b) % 3);
  for (size_t k = 0; k < layout.size(); ++k) {
    const TermLayout& L = layout[k];
    Vec4 q0;
    RandomFrames(g, &f1[k], &f2[k], &q0);
    if (L.rotation) {
      thetas[k] = RandomPoly(g, std::uniform_real_distribution<double>(-30, 30)(g), 2.0);
      cs.bodies[L.child] = OnRotationManifold(g, TrajOf(cs.bodies, L.parent), f1[k].h, thetas[k], q0);
      cs.angle_refs.push_back(thetas[k].c[0] + (k % 2 ? 0.4 : -0.4));
    }
    terms.push_back(CoordinateTerm{L.rotation, L.parent < 0 ? kGround : L.parent, L.child, f1[k], f2[k], u(g)});
  }
  const double c0 = u(g);
  if (broken) cs.c = std::make_unique<HalvedRhsCoupling>(terms, c0);
  else cs.c = std::make_unique<CouplingConstraint>(terms, c0);
  cs.phi = [layout, terms, thetas, c0](const std::vector<BodyTraj>& b) {
    TJet sum(-c0);
    for (size_t k = 0; k < terms.size(); ++k) {
      if (layout[k].rotation) {
        sum = sum + terms[k].coefficient * thetas[k];
        continue;
      }
      const BodyTraj &a = TrajOf(b, terms[k].body1), &c = TrajOf(b, terms[k].body2);
      const V3 d = testing::Sub(PointOf(c, terms[k].frame2.origin), PointOf(a, terms[k].frame1.origin));
      sum = sum + terms[k].coefficient * testing::Dot(VecOf(a, terms[k].frame1.h), d);
    }
    return sum;
  };
  return cs;
}

// Φ, Φ_q (both versions) and κ against differences, RHS_k against the jets, per side.
// A coupler's Φ on series (CheckSeriesForms), its sides' poses from their rates.
void CheckCouplerSeries(const Constraint& c, const CouplerCase& cs, const std::vector<BodyKinematics>& kin,
                        const ConstraintInput& in, const TJet& phi_t, Errors* e) {
  std::vector<JetPose> series;
  for (const BodyKinematics& k : kin) series.push_back(JetPoseOf(k, ExtendedPose::Of(k).A, kMaxOrder));
  static const JetPose kGroundSeries;
  static const BodyTraj kGroundTraj = [] { BodyTraj t; t.ground = true; return t; }();
  auto ss = [&](int side) -> const JetPose& { return c.body(side) == kGround ? kGroundSeries : series[c.body(side)]; };
  JetInput jin{ss(0), ss(1), ExtendedJet(0), in.angle_ref};
  std::vector<const BodyTraj*> sides;
  for (int side = 0; side < c.num_sides(); ++side) {
    if (side >= 2) jin.more[side - 2] = &ss(side);
    sides.push_back(c.body(side) == kGround ? &kGroundTraj : &cs.bodies[c.body(side)]);
  }
  jin.more_angle_refs = in.more_angle_refs;
  CheckSeriesForms(c, sides, jin, {phi_t}, e);
}

Errors CheckCouplerCase(const CouplerCase& cs) {
  Errors e;
  const Constraint& c = *cs.c;
  std::vector<BodyKinematics> kin;
  for (const BodyTraj& b : cs.bodies) kin.push_back(KinAt0(b));
  const ConstraintInput in = CouplerInput(c, kin, cs.angle_refs);
  const TJet phi_t = cs.phi(cs.bodies);
  double phi;
  c.CalcPhi(in, &phi);
  e.phi = RelErr(phi, phi_t.c[0], 1 + std::abs(phi_t.c[0]));
  std::vector<ExtendedPose> xp;
  for (const BodyKinematics& k : kin) xp.push_back(ExtendedPose::Of(k));
  static const ExtendedPose kGroundPose;
  auto xs = [&](int side) -> const ExtendedPose& { return c.body(side) == kGround ? kGroundPose : xp[c.body(side)]; };
  ExtendedInput xin{xs(0), xs(1), 0, in.angle_ref};
  for (int side = 2; side < c.num_sides(); ++side) xin.more[side - 2] = &xs(side);
  xin.more_angle_refs = in.more_angle_refs;
  Real phi_x;
  c.CalcPhiExtended(xin, &phi_x);
  e.phi_extended = RelErr(static_cast<double>(phi_x), phi_t.c[0], 1 + std::abs(phi_t.c[0]));
  CheckCouplerSeries(c, cs, kin, in, phi_t, &e);
  JacobianBlocks J;
  c.CalcJacobian(in, &J);
  const double h = 1e-6;
  double jscale = 1e-12;
  for (int side = 0; side < c.num_sides(); ++side) jscale = std::max({jscale, J.R(side).row(0).norm(), J.Pi(side).row(0).norm()});
  for (int side = 0; side < c.num_sides(); ++side) {
    const BodyIndex b = c.body(side);
    if (b == kGround) continue;
    const auto P = PVersionBlock(in, J, side);
    for (int col = 0; col < 10; ++col) {
      double f[2];
      for (int sgn : {1, -1}) {
        std::vector<BodyKinematics> kp = kin;
        if (col < 3) kp[b].r[0][col] += sgn * h;
        else if (col < 6) kp[b].SetPose(kp[b].r[0], QuatMultiply(kp[b].p, QuatFromAxisAngle(Vec3::Unit(col % 3), sgn * h)));
        else {
          Vec4 p = kp[b].p;
          p[col - 6] += sgn * h;
          kp[b].SetPose(kp[b].r[0], p.normalized());
        }
        f[sgn > 0 ? 0 : 1] = CouplerPhiAt(c, kp, cs.angle_refs);
      }
      const double fd = (f[0] - f[1]) / (2 * h);
      if (col < 6) e.jac = std::max(e.jac, RelErr(fd, col < 3 ? J.R(side)(0, col) : J.Pi(side)(0, col - 3), jscale));
      else e.jac_p = std::max(e.jac_p, RelErr(fd, P(0, col - 6), jscale));
    }
  }
  for (int k = 1; k <= 4; ++k) {
    double rw, rp;
    c.CalcRhs(in, k, &rw);
    CalcPVersionRhs(c, in, k, &rp);
    double lhs_w = 0, lhs_p = 0, scale = std::abs(phi_t.D(k));
    for (int side = 0; side < c.num_sides(); ++side) {
      if (c.body(side) == kGround) continue;
      const BodyTraj& b = cs.bodies[c.body(side)];
      const auto P = PVersionBlock(in, J, side);
      for (int a = 0; a < 3; ++a) {
        const double tr = J.R(side)(0, a) * b.r[a].D(k), tw = J.Pi(side)(0, a) * b.w[a].D(k - 1);
        lhs_w += tr + tw;
        lhs_p += tr;
        scale = std::max({scale, std::abs(tr), std::abs(tw)});
      }
      for (int a = 0; a < 4; ++a) lhs_p += P(0, a) * b.p[a].D(k), scale = std::max(scale, std::abs(P(0, a) * b.p[a].D(k)));
    }
    const double want_w = lhs_w - phi_t.D(k), want_p = lhs_p - phi_t.D(k);
    e.rhs_w = std::max(e.rhs_w, RelErr(rw, want_w, std::max(scale, std::abs(want_w))));
    e.rhs_p = std::max(e.rhs_p, RelErr(rp, want_p, std::max(scale, std::abs(want_p))));
  }
  // κ vs 4th-order central differences in time of Φ_qᵀλ, side by side.
  const double lambda = 0.7, dt = 1e-3;
  KappaTerms kap;
  c.CalcKappa(in, &lambda, &kap);
  const double w5[4] = {1, -8, 8, -1}, t5[4] = {-2, -1, 1, 2};
  Eigen::VectorXd fd = Eigen::VectorXd::Zero(6 * c.num_sides()), got = fd;
  for (int s = 0; s < 4; ++s) {
    std::vector<BodyKinematics> ks;
    for (const BodyTraj& b : cs.bodies) ks.push_back(KinAt(b, t5[s] * dt));
    JacobianBlocks Js;
    c.CalcJacobian(CouplerInput(c, ks, cs.angle_refs), &Js);
    for (int side = 0; side < c.num_sides(); ++side) {
      fd.segment<3>(6 * side) += w5[s] * lambda * Js.R(side).row(0).transpose();
      fd.segment<3>(6 * side + 3) += w5[s] * lambda * Js.Pi(side).row(0).transpose();
    }
  }
  fd /= 12 * dt;
  for (int side = 0; side < c.num_sides(); ++side) {
    if (c.body(side) == kGround) {
      fd.segment<6>(6 * side).setZero();
      continue;
    }
    got.segment<3>(6 * side) = kap.F(side);
    got.segment<3>(6 * side + 3) = kap.T(side);
  }
  e.kappa = (fd - got).norm() / std::max({fd.norm(), got.norm(), jscale * 1e-3});
  return e;
}

// Every layout, 1000 poses: the general coupling (gear, belt, rack, screw coupling
// are its two-coordinate instances, checked below against it).
TEST(Conformance, CouplerBetweenJointCoordinates) {
  std::mt19937 g(20261202);
  Errors worst;
  for (int n = 0; n < kPoses; ++n) worst.Max(CheckCouplerCase(MakeCoupler(g, n)));
  std::printf("[measured] couplers: phi %.1e ext %.1e jac %.1e jac_p %.1e rhs_w %.1e rhs_p %.1e kappa %.1e series %.1e %.1e\n",
              worst.phi, worst.phi_extended, worst.jac, worst.jac_p, worst.rhs_w, worst.rhs_p, worst.kappa, worst.phi_series,
              worst.pose_series);
  ExpectConforms(worst);
}

// The named couplers are the coupling with their coefficients: Φ, Φ_q and RHS equal.
TEST(Conformance, NamedCouplersAreTheirCoupling) {
  std::mt19937 g(8);
  for (int n = 0; n < 200; ++n) {
    JointFrame a1, a2, b1, b2;
    Vec4 q0;
    RandomFrames(g, &a1, &a2, &q0);
    RandomFrames(g, &b1, &b2, &q0);
    const CoordinateTerm rot{true, kGround, 0, a1, a2, 1}, rot2{true, kGround, 1, b1, b2, 1};
    const CoordinateTerm slide{false, kGround, 1, b1, b2, 1};
    const double r = std::uniform_real_distribution<double>(-3, 3)(g);
    std::vector<BodyKinematics> kin(2);
    kin[0] = KinAt0(RandomBody(g, 0));
    kin[1] = KinAt0(RandomBody(g, 1));
    const std::vector<double> refs = {0.3, -0.2};
    auto same = [&](const Constraint& named, const Constraint& general, const std::vector<double>& rf) {
      const ConstraintInput in = CouplerInput(named, kin, rf), ig = CouplerInput(general, kin, rf);
      EXPECT_NEAR(CouplerPhiAt(named, kin, rf), CouplerPhiAt(general, kin, rf), 1e-13);
      JacobianBlocks Jn, Jg;
      named.CalcJacobian(in, &Jn);
      general.CalcJacobian(ig, &Jg);
      for (int side = 0; side < named.num_sides(); ++side)
        EXPECT_LT((Jn.Pi(side) - Jg.Pi(side)).norm() + (Jn.R(side) - Jg.R(side)).norm(), 1e-13);
      for (int k = 1; k <= 4; ++k) {
        double a, b;
        named.CalcRhs(in, k, &a);
        general.CalcRhs(ig, k, &b);
        EXPECT_NEAR(a, b, 1e-13 * (1 + std::abs(a)));
      }
    };
    auto with = [](CoordinateTerm t, double c) { t.coefficient = c; return t; };
    same(GearConstraint(rot, rot2, r), CouplingConstraint({with(rot, -r), rot2}, 0), refs);
    same(BeltConstraint(rot, rot2, r), CouplingConstraint({with(rot, -r), rot2}, 0), refs);
    same(RackPinionConstraint(rot, slide, r), CouplingConstraint({with(rot, -r), slide}, 0), {0.3});
    same(ScrewCouplingConstraint(rot, slide, r), CouplingConstraint({with(rot, -r / (2 * M_PI)), slide}, 0), {0.3});
  }
}

// The harness sees a coupler whose right-hand sides lose half of the slide's bias.
TEST(Conformance, CouplerHarnessCatchesAWrongRhs) {
  std::mt19937 g(4);
  Errors worst;
  for (int n = 0; n < 50; ++n) worst.Max(CheckCouplerCase(MakeCoupler(g, 3, /*broken=*/true)));
  EXPECT_GT(worst.rhs_w, 1e-3);
  EXPECT_LT(worst.jac, 1e-7);
}

TEST(Conformance, EulerNormalizationRhs) {
  std::mt19937 g(5);
  for (int n = 0; n < kPoses; ++n) {
    const BodyTraj b = RandomBody(g, n % 3);
    Vec4 pd[5];
    for (int k = 0; k <= 4; ++k) pd[k] = Vec4(b.p[0].D(k), b.p[1].D(k), b.p[2].D(k), b.p[3].D(k));
    // pᵀp ≡ 1, so every derivative vanishes: 2pᵀp^(k) − RHS_k = 0.
    for (int k = 1; k <= 4; ++k) {
      const double lhs = EulerNormalization::Jacobian(pd[0]).dot(pd[k]);
      EXPECT_NEAR(lhs, EulerNormalization::Rhs(pd, k), 1e-11 * (1 + pd[k].norm()));
    }
  }
}

// p^(k) from ω'^(k) by the Leibniz recursion of §1.3 equals the jets' own p^(k).
TEST(Conformance, EulerDerivativesFromAngularVelocity) {
  std::mt19937 g(11);
  for (int n = 0; n < 200; ++n) {
    const BodyTraj b = RandomBody(g, n % 3);
    const BodyKinematics k = KinAt0(b);
    Vec4 pd[5];
    k.CalcEulerDerivatives(4, pd);
    for (int o = 0; o <= 4; ++o)
      EXPECT_LT((pd[o] - Vec4(b.p[0].D(o), b.p[1].D(o), b.p[2].D(o), b.p[3].D(o))).norm(), 1e-10 * (1 + pd[o].norm()));
  }
}

}  // namespace
}  // namespace mechkin
