// §3.4 DOT_2: Φ = a_iᵀ d_ij, d_ij = r^P_j − r^P_i.
#include "constraints/families.hpp"

namespace mechkin {

// Φ_r = [−a_iᵀ, a_iᵀ], Φ_π'_i = a'_iᵀ s̃'_i − dᵀA_i ã'_i, Φ_π'_j = −a_iᵀA_j s̃'_j   (§3.4 table)
void Dot2Constraint::CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const {
  const Vec3 ai = in.i.A * a_i_;
  const Vec3 d = RelativePointDerivative(in, s_i_, s_j_, 0);
  J->r_i.row(0) = -ai.transpose();
  J->r_j.row(0) = ai.transpose();
  J->pi_i.row(0) = a_i_.transpose() * tilde_s_i_ - d.transpose() * in.i.A * tilde_a_i_;
  J->pi_j.row(0) = -ai.transpose() * in.j.A * tilde_s_j_;
}

// RHS_k = −[Σ_{m=1}^{k−1} binom(k,m) a_i^(m)·d^(k−m) + bias(a_i^(k))·d + a_i·bias(d^(k))];
// k = 2: γ = −2ḋᵀA_iω̃a'_i − dᵀA_iω̃ω̃a'_i + a'_iᵀA_iᵀγ^SPH, and likewise η, σ of §3.4.
void Dot2Constraint::CalcRhs(const ConstraintInput& in, int k, double* rhs) const {
  const Vec3 ai = in.i.A * a_i_;
  const Vec3 bias_d = in.j.PointBias(s_j_, k) - in.i.PointBias(s_i_, k);
  double s = in.i.VectorBias(a_i_, k).dot(RelativePointDerivative(in, s_i_, s_j_, 0)) + ai.dot(bias_d);
  for (int m = 1; m < k; ++m) s += kBinomial[k][m] * in.i.VectorDerivative(a_i_, m).dot(RelativePointDerivative(in, s_i_, s_j_, k - m));
  *rhs = -s;
}

// κ_F_i = −λA_iω̃'_i a'_i, κ_F_j = −κ_F_i, κ_T_i = −λ[(A_iω̃'_i ã'_i)ᵀd + (A_i ã'_i)ᵀḋ],
// κ_T_j = −λ[(A_j s̃'_j)ᵀA_iω̃'_i a'_i + (A_jω̃'_j s̃'_j)ᵀA_i a'_i]   (§3.4)
void Dot2Constraint::CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const {
  const double l = *lambda;
  const Vec3 d = RelativePointDerivative(in, s_i_, s_j_, 0), dd = RelativePointDerivative(in, s_i_, s_j_, 1);
  const Vec3 ai_dot = in.i.A * Tilde(in.i.w[0]) * a_i_;
  kappa->F_i = -l * ai_dot;
  kappa->F_j = l * ai_dot;
  kappa->T_i = -l * ((in.i.A * Tilde(in.i.w[0]) * Tilde(a_i_)).transpose() * d + (in.i.A * Tilde(a_i_)).transpose() * dd);
  kappa->T_j = -l * ((in.j.A * Tilde(s_j_)).transpose() * ai_dot +
                     (in.j.A * Tilde(in.j.w[0]) * Tilde(s_j_)).transpose() * (in.i.A * a_i_));
}

}  // namespace mechkin
