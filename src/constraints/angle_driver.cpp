// §3.9 GRRD off the joint manifold (families.hpp, AngleDriver): θ = atan2(g_iᵀf_j, f_iᵀf_j).
#include <array>

#include "constraints/families.hpp"

namespace mechkin {

namespace {

using VecJet3 = std::array<Jet, 3>;

constexpr double kInvFact[] = {1, 1, 0.5, 1.0 / 6, 1.0 / 24};

// Global series of the body-fixed vector a' to order k; the order-k term is the
// bias A B[k] a' when `bias_top` (θ^(k) without its part in the order-k unknowns).
VecJet3 Series(const BodyKinematics& b, const Vec3& a, int k, bool bias_top) {
  VecJet3 j;
  for (int m = 0; m <= k; ++m) {
    const Vec3 v = (bias_top && m == k) ? b.VectorBias(a, m) : b.VectorDerivative(a, m);
    for (int c = 0; c < 3; ++c) j[c].c[m] = v[c] * kInvFact[m];
  }
  return j;
}

Jet Dot(const VecJet3& a, const VecJet3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

VecJet3 Cross(const Vec3& a, const VecJet3& b) {  // a constant
  const Jet x = Jet::Constant(a.x()), y = Jet::Constant(a.y()), z = Jet::Constant(a.z());
  return {y * b[2] - z * b[1], z * b[0] - x * b[2], x * b[1] - y * b[0]};
}

}  // namespace

void AngleDriver::CalcRhs(const ConstraintInput& in, int k, double* rhs) const {
  const VecJet3 fi = Series(in.i, fi_, k, true), gi = Series(in.i, gi_, k, true), fj = Series(in.j, fj_, k, true);
  const Jet theta = Atan2(Dot(gi, fj), Dot(fi, fj));
  *rhs = in.f.Derivative(k) - theta.Derivative(k);
}

// With x = A_iᵀf_j and y = A_jᵀ(s f_i − c g_i) (body-frame components, on jets):
//   Φ_π'_i = [c (g'_i × x) − s (f'_i × x)] / ρ²,   Φ_π'_j = −(f'_j × y) / ρ²,
// the gradient of RotationDriver::CalcAngleGradient; κ_T = λ times their rates.
void AngleDriver::CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const {
  const VecJet3 fi = Series(in.i, fi_, 1, false), gi = Series(in.i, gi_, 1, false), fj = Series(in.j, fj_, 1, false);
  const Jet s = Dot(gi, fj), c = Dot(fi, fj), rho2 = s * s + c * c;
  VecJet3 x, y;
  for (int a = 0; a < 3; ++a) {
    x[a] = Dot(Series(in.i, Vec3::Unit(a), 1, false), fj);
    const VecJet3 ej = Series(in.j, Vec3::Unit(a), 1, false);
    y[a] = s * Dot(ej, fi) - c * Dot(ej, gi);
  }
  const VecJet3 gx = Cross(gi_, x), fx = Cross(fi_, x), fy = Cross(fj_, y);
  *kappa = KappaTerms{};
  for (int a = 0; a < 3; ++a) {
    kappa->T_i[a] = *lambda * ((c * gx[a] - s * fx[a]) / rho2).Derivative(1);
    kappa->T_j[a] = *lambda * (-(fy[a] / rho2)).Derivative(1);
  }
}

}  // namespace mechkin
