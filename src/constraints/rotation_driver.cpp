// §3.9 GRRD (and §3.6 FRRD as GRRD with body i = ground): Φ = θ_ij − f(t),
// θ = atan2(g_iᵀ f_j, f_iᵀ f_j), continued over whole turns.
#include <cmath>

#include "constraints/families.hpp"

namespace mechkin {

double RotationDriver::CalcAngle(const ConstraintInput& in) const { return Angle(in.i, in.j, in.angle_ref); }

// Exact gradient (§3.9): with c = f_iᵀf_j, s = g_iᵀf_j, ρ² = c² + s²,
//   Φ_π'_i = f_jᵀA_i(s f̃'_i − c g̃'_i)/ρ²,  Φ_π'_j = (s f_i − c g_i)ᵀA_j f̃'_j/ρ².
// On the joint manifold these are −h'_iᵀ and h'_jᵀ.
void RotationDriver::CalcAngleGradient(const ConstraintInput& in, Vec3* d_pi_i, Vec3* d_pi_j) const {
  const Vec3 fi = in.i.A * fi_, gi = in.i.A * gi_, fj = in.j.A * fj_;
  const double c = fi.dot(fj), s = gi.dot(fj);
  double rho2 = c * c + s * s;
  if (rho2 < 1e-300) rho2 = 1e-300;  // f_j ∥ h_i: angle undefined; keep finite
  *d_pi_i = (fj.transpose() * in.i.A * (s * Tilde(fi_) - c * Tilde(gi_))).transpose() / rho2;
  *d_pi_j = ((s * fi - c * gi).transpose() * in.j.A * Tilde(fj_)).transpose() / rho2;
}

void RotationDriver::CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const {
  Vec3 gi, gj;
  CalcAngleGradient(in, &gi, &gj);
  J->r_i.row(0).setZero();
  J->r_j.row(0).setZero();
  J->pi_i.row(0) = gi.transpose();
  J->pi_j.row(0) = gj.transpose();
}

// ω' version, on the joint manifold: ν = f_t, γ = f_tt, η = f_ttt, σ = f_tttt (§3.9);
// the p version (η_p = f_ttt − (h'_jᵀv_j − h'_iᵀv_i)) follows from CalcPVersionRhs.
void RotationDriver::CalcRhs(const ConstraintInput& in, int k, double* rhs) const {
  *rhs = in.f.Derivative(k);
}

// κ = 0 on the joint manifold: the blocks −h'_iᵀ, h'_jᵀ are constant in body coordinates.
void RotationDriver::CalcKappa(const ConstraintInput&, const double*, KappaTerms* kappa) const {
  *kappa = KappaTerms{};
}

}  // namespace mechkin
