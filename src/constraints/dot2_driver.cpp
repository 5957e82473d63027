// §3.8 D2DD: Φ = a_iᵀ d_ij / L − f(t), L = |a'_i|; Φ_q = Φ_q^DOT_2 / L,
// RHS_k = RHS_k^DOT_2 / L + f^(k), κ = κ^DOT_2 / L.
#include "constraints/families.hpp"

namespace mechkin {

void Dot2DistanceDriver::CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const {
  dot2_.CalcJacobian(in, J);
  const double L = dot2_.length();
  J->r_i /= L; J->r_j /= L; J->pi_i /= L; J->pi_j /= L;
}

void Dot2DistanceDriver::CalcRhs(const ConstraintInput& in, int k, double* rhs) const {
  dot2_.CalcRhs(in, k, rhs);
  *rhs = *rhs / dot2_.length() + in.f.Derivative(k);
}

void Dot2DistanceDriver::CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const {
  const double l = *lambda / dot2_.length();
  dot2_.CalcKappa(in, &l, kappa);
}

}  // namespace mechkin
