// §3.2 SPH_SPH (fixed distance) and §3.7 3DRDD (driven distance):
//   Φ = d_ijᵀ d_ij − L²   or   d_ijᵀ d_ij − f(t)²,   d_ij = r^P_j − r^P_i.
#include "constraints/families.hpp"

namespace mechkin {

// Φ_r = [−2dᵀ, 2dᵀ], Φ_π' = [2dᵀA_i s̃'_i, −2dᵀA_j s̃'_j]   (§3.2 table; §3.7: same for 3DRDD)
void DistanceConstraint::CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const {
  const Vec3 d = RelativePointDerivative(in, s_i_, s_j_, 0);
  J->r_i.row(0) = -2 * d.transpose();
  J->r_j.row(0) = 2 * d.transpose();
  J->pi_i.row(0) = 2 * d.transpose() * in.i.A * Tilde(s_i_);
  J->pi_j.row(0) = -2 * d.transpose() * in.j.A * Tilde(s_j_);
}

// RHS_k = −[Σ_{m=1}^{k−1} binom(k,m) d^(m)·d^(k−m) + 2 d·bias(d^(k))] (+ (f²)^(k) for 3DRDD).
// k=2: γ = −2ḋᵀḋ + 2dᵀγ^SPH; k=3: η = −6ḋᵀd̈ + 2dᵀη^SPH; k=4: σ = −6d̈ᵀd̈ − 8ḋᵀd⃛ + 2dᵀσ^SPH
// (§3.2); 3DRDD adds 2ff_t, 2f_t² + 2ff_tt, 6f_tf_tt + 2ff_ttt, 6f_tt² + 8f_tf_ttt + 2ff_tttt (§3.7).
void DistanceConstraint::CalcRhs(const ConstraintInput& in, int k, double* rhs) const {
  Vec3 d[kMaxOrder];
  for (int m = 0; m < k; ++m) d[m] = RelativePointDerivative(in, s_i_, s_j_, m);
  const Vec3 bias = in.j.PointBias(s_j_, k) - in.i.PointBias(s_i_, k);
  double s = 2 * d[0].dot(bias);
  for (int m = 1; m < k; ++m) s += kBinomial[k][m] * d[m].dot(d[k - m]);
  *rhs = -s;
  if (driven()) *rhs += (in.f * in.f).Derivative(k);
}

// κ_F_i = −2λḋ, κ_F_j = 2λḋ, κ_T_i = 2λ[(A_iω̃'_i s̃'_i)ᵀd + (A_i s̃'_i)ᵀḋ],
// κ_T_j = −2λ[(A_jω̃'_j s̃'_j)ᵀd + (A_j s̃'_j)ᵀḋ]   (§3.2, compact form)
void DistanceConstraint::CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const {
  const double l = *lambda;
  const Vec3 d = RelativePointDerivative(in, s_i_, s_j_, 0), dd = RelativePointDerivative(in, s_i_, s_j_, 1);
  kappa->F_i = -2 * l * dd;
  kappa->F_j = 2 * l * dd;
  kappa->T_i = 2 * l * ((in.i.A * Tilde(in.i.w[0]) * Tilde(s_i_)).transpose() * d + (in.i.A * Tilde(s_i_)).transpose() * dd);
  kappa->T_j = -2 * l * ((in.j.A * Tilde(in.j.w[0]) * Tilde(s_j_)).transpose() * d + (in.j.A * Tilde(s_j_)).transpose() * dd);
}

}  // namespace mechkin
