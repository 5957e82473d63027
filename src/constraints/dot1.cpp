// §3.3 DOT_1: Φ = a_iᵀ a_j = a'_iᵀ A_iᵀ A_j a'_j.
#include "constraints/families.hpp"

namespace mechkin {

// Φ_π' = [−a_jᵀA_i ã'_i, −a_iᵀA_j ã'_j], Φ_r = 0   (§3.3 table)
void Dot1Constraint::CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const {
  const Vec3 ai = in.i.A * a_i_, aj = in.j.A * a_j_;
  J->r_i.row(0).setZero();
  J->r_j.row(0).setZero();
  J->pi_i.row(0) = -aj.transpose() * in.i.A * tilde_a_i_;
  J->pi_j.row(0) = -ai.transpose() * in.j.A * tilde_a_j_;
}

// RHS_k = −[Σ_{m=1}^{k−1} binom(k,m) a_i^(m)·a_j^(k−m) + bias(a_i^(k))·a_j + a_i·bias(a_j^(k))];
// k = 2, 3, 4 give the γ, η, σ of §3.3 (e.g. η's −3a'_jᵀ(ω̃ω̃ − ω̇̃)A_jᵀA_iω̃a'_i terms are the
// m = 1, 2 Leibniz terms).
void Dot1Constraint::CalcRhs(const ConstraintInput& in, int k, double* rhs) const {
  double s = in.i.VectorBias(a_i_, k).dot(in.j.A * a_j_) + (in.i.A * a_i_).dot(in.j.VectorBias(a_j_, k));
  for (int m = 1; m < k; ++m) s += kBinomial[k][m] * in.i.VectorDerivative(a_i_, m).dot(in.j.VectorDerivative(a_j_, k - m));
  *rhs = -s;
}

// κ_T_i = −λ[(A_i ã'_i)ᵀA_jω̃'_j a'_j + (A_iω̃'_i ã'_i)ᵀA_j a'_j], κ_T_j symmetric, κ_F = 0   (§3.3)
void Dot1Constraint::CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const {
  const double l = *lambda;
  kappa->F_i.setZero();
  kappa->F_j.setZero();
  kappa->T_i = -l * ((in.i.A * Tilde(a_i_)).transpose() * in.j.A * Tilde(in.j.w[0]) * a_j_ +
                     (in.i.A * Tilde(in.i.w[0]) * Tilde(a_i_)).transpose() * in.j.A * a_j_);
  kappa->T_j = -l * ((in.j.A * Tilde(a_j_)).transpose() * in.i.A * Tilde(in.i.w[0]) * a_i_ +
                     (in.j.A * Tilde(in.j.w[0]) * Tilde(a_j_)).transpose() * in.i.A * a_i_);
}

}  // namespace mechkin
