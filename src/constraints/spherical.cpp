// §3.1 Spherical (SPH): Φ = r_j + A_j s'_j − r_i − A_i s'_i.
#include "constraints/families.hpp"

namespace mechkin {

// Φ_r = [−I, I], Φ_π' = [A_i s̃'_i, −A_j s̃'_j]   (§3.1 table)
void SphericalConstraint::CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const {
  J->r_i = -Mat3::Identity();
  J->r_j = Mat3::Identity();
  J->pi_i = in.i.A * tilde_s_i_;
  J->pi_j = -in.j.A * tilde_s_j_;
}

// RHS_k = A_i B_k s'_i − A_j B_k s'_j: γ = A_iω̃ω̃s'_i − A_jω̃ω̃s'_j, η = A_iH's'_i − A_jH's'_j,
// σ = A_iW's'_i − A_jW's'_j   (§3.1)
void SphericalConstraint::CalcRhs(const ConstraintInput& in, int k, double* rhs) const {
  Eigen::Map<Vec3> out(rhs);
  out = in.i.PointBias(s_i_, k) - in.j.PointBias(s_j_, k);
}

// κ_T_i = (A_i ω̃'_i s̃'_i)ᵀλ, κ_T_j = −(A_j ω̃'_j s̃'_j)ᵀλ, κ_F = 0   (§3.1)
void SphericalConstraint::CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const {
  const Eigen::Map<const Vec3> l(lambda);
  kappa->F_i.setZero();
  kappa->F_j.setZero();
  kappa->T_i = (in.i.A * Tilde(in.i.w[0]) * Tilde(s_i_)).transpose() * l;
  kappa->T_j = -(in.j.A * Tilde(in.j.w[0]) * Tilde(s_j_)).transpose() * l;
}

}  // namespace mechkin
