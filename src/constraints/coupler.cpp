// §3.11 couplers between joint coordinates: Φ = Σ_k c_k q_k − c_0, the sum of the
// coordinates' own Φ, Φ_q, RHS_k and κ (GRRD §3.9 and D2DD §3.8 with f = 0), each
// scaled by c_k and placed on its joint's two sides.
#include <stdexcept>

#include "constraints/couplers.hpp"

namespace mechkin {

namespace {

int SideOf(BodyIndex b, BodyIndex* sides, int* n) {
  for (int s = 0; s < *n; ++s)
    if (sides[s] == b) return s;
  sides[*n] = b;
  return (*n)++;
}

}  // namespace

CouplerConstraint::CouplerConstraint(const std::vector<CoordinateTerm>& terms, double constant)
    : Constraint(kGround, kGround, 1), constant_(constant) {
  if (terms.size() < 2 || terms.size() > static_cast<size_t>(kMaxAngles))
    throw std::invalid_argument("a coupler reads 2 or 3 joint coordinates");
  BodyIndex sides[kMaxSides];
  int n = 0;
  for (const CoordinateTerm& ct : terms) {
    Term& t = terms_[num_terms_++];
    t.c = ct.coefficient;
    t.side_a = SideOf(ct.body1, sides, &n);
    t.side_b = SideOf(ct.body2, sides, &n);
    if (ct.rotation) {
      t.rotation = std::make_unique<RotationDriver>(ct.body1, ct.body2, ct.frame1, ct.frame2);
      t.angle = num_angles_++;
    } else {
      t.slide = std::make_unique<Dot2DistanceDriver>(ct.body1, ct.body2, ct.frame1.h, ct.frame1.origin, ct.frame2.origin);
      has_slide_ = true;
    }
  }
  if (n == 1) sides[n++] = sides[0] == kGround ? 0 : kGround;  // cannot happen for a joint; keeps two sides
  SetSides(sides, n);
}

ConstraintInput CouplerConstraint::TermInput(const ConstraintInput& in, const Term& t) const {
  return ConstraintInput{in.Side(t.side_a), in.Side(t.side_b), Jet{}, t.angle >= 0 ? in.AngleRef(t.angle) : 0.0};
}

// Φ_q = Σ c_k ∂q_k/∂q: GRRD's exact angle gradient, D2DD's blocks (§3.8, §3.9).
void CouplerConstraint::CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const {
  for (int s = 0; s < num_sides(); ++s) J->R(s).setZero(), J->Pi(s).setZero();
  for (int k = 0; k < num_terms_; ++k) {
    const Term& t = terms_[k];
    JacobianBlocks tb;
    TermFamily(t).CalcJacobian(TermInput(in, t), &tb);
    J->R(t.side_a).row(0) += t.c * tb.r_i.row(0);
    J->Pi(t.side_a).row(0) += t.c * tb.pi_i.row(0);
    J->R(t.side_b).row(0) += t.c * tb.r_j.row(0);
    J->Pi(t.side_b).row(0) += t.c * tb.pi_j.row(0);
  }
}

// RHS_k = Σ c_k RHS_k(q_k): 0 for a rotation on its joint's manifold (§3.9), D2DD's
// −bias/L for a slide (§3.8), for every order k.
void CouplerConstraint::CalcRhs(const ConstraintInput& in, int k, double* rhs) const {
  double sum = 0;
  for (int n = 0; n < num_terms_; ++n) {
    const Term& t = terms_[n];
    double r = 0;
    TermFamily(t).CalcRhs(TermInput(in, t), k, &r);
    sum += t.c * r;
  }
  *rhs = sum;
}

// κ(λ) = Σ κ_k(c_k λ): the rotations' vanish on the manifold (§3.9), the slides' are D2DD's.
void CouplerConstraint::CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const {
  *kappa = KappaTerms{};
  for (int n = 0; n < num_terms_; ++n) {
    const Term& t = terms_[n];
    const double l = t.c * *lambda;
    KappaTerms tk;
    TermFamily(t).CalcKappa(TermInput(in, t), &l, &tk);
    kappa->F(t.side_a) += tk.F_i, kappa->T(t.side_a) += tk.T_i;
    kappa->F(t.side_b) += tk.F_j, kappa->T(t.side_b) += tk.T_j;
  }
}

double CouplerConstraint::CoordinateDerivative(const ConstraintInput& in, int k, int m) const {
  const Term& t = terms_[k];
  const ConstraintInput ti = TermInput(in, t);
  JacobianBlocks tb;
  TermFamily(t).CalcJacobian(ti, &tb);
  double rhs = 0;
  TermFamily(t).CalcRhs(ti, m, &rhs);
  return tb.r_i.row(0).dot(ti.i.r[m]) + tb.pi_i.row(0).dot(ti.i.w[m - 1]) + tb.r_j.row(0).dot(ti.j.r[m]) +
         tb.pi_j.row(0).dot(ti.j.w[m - 1]) - rhs;
}

void CouplerConstraint::CalcAngles(const ConstraintInput& in, double* angles) const {
  for (int n = 0; n < num_terms_; ++n) {
    const Term& t = terms_[n];
    if (t.rotation) angles[t.angle] = t.rotation->Angle(in.Side(t.side_a), in.Side(t.side_b), in.AngleRef(t.angle));
  }
}

double CouplerConstraint::CalcAngle(const ConstraintInput& in) const {
  double angles[kMaxAngles] = {0, 0, 0};
  CalcAngles(in, angles);
  return angles[0];
}

}  // namespace mechkin
