// §3.10 SDA, general form: Φ = h_iᵀ d_ij − λ_s θ_ij (L = 1), λ_s = pitch per radian.
#include "constraints/families.hpp"

namespace mechkin {

// Φ_π'_i = Φ_π'_i^DOT_2 − λ_s ∂θ/∂π'_i (= … + λ_s h'_iᵀ on the manifold), likewise for j   (§3.10)
void ScrewConstraint::CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const {
  dot2_.CalcJacobian(in, J);
  Vec3 gi, gj;
  angle_.CalcAngleGradient(in, &gi, &gj);
  J->pi_i.row(0) -= lambda_s_ * gi.transpose();
  J->pi_j.row(0) -= lambda_s_ * gj.transpose();
}

// ν = 0, γ, η, σ = those of DOT_2 (θ's own right-hand sides vanish on the manifold);
// η_p, σ_p gain λ_s(h'_jᵀv_j − h'_iᵀv_i) through CalcPVersionRhs   (§3.10)
void ScrewConstraint::CalcRhs(const ConstraintInput& in, int k, double* rhs) const {
  dot2_.CalcRhs(in, k, rhs);
}

void ScrewConstraint::CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const {
  dot2_.CalcKappa(in, lambda, kappa);
}

}  // namespace mechkin
