// The contract every constraint family implements (constraints.md §1.6, §3).
//
// A family couples body i and body j (either may be ground) with `size()`
// scalar equations Φ = 0 and provides, at one instant:
//   * Φ;
//   * the Jacobian blocks Φ_r and Φ_π' of both bodies (ω' version, §1.5);
//   * the right-hand sides RHS_k of Φ_q q^(k) = RHS_k for k = 1..4 (ν, γ, η, σ,
//     ω' version), i.e. d^kΦ/dt^k = Φ_q q^(k) − RHS_k;
//   * κ: the rate of the reaction terms at fixed λ (§1.8).
// The p version follows for every family from §1.5 and §1.7:
//   Φ_p = 2 Φ_π' G,  ν, γ shared,  η_p = η − Σ_k Φ_π'k v_k,  σ_p = σ − Σ_k Φ_π'k v3_k,
// implemented once in CalcPVersion* below.
#pragma once

#include <memory>
#include <string>

#include "constraints/body_kinematics.hpp"
#include "model/model.hpp"

namespace mechkin {

constexpr int kMaxRows = 3;  // largest family (spherical)
using RowBlock = Eigen::Matrix<double, kMaxRows, 3>;

/// Jacobian blocks of one family; only the first size() rows are meaningful.
struct JacobianBlocks {
  RowBlock r_i = RowBlock::Zero(), pi_i = RowBlock::Zero();
  RowBlock r_j = RowBlock::Zero(), pi_j = RowBlock::Zero();
};

/// Reaction-rate terms of §1.8 for both bodies.
struct KappaTerms {
  Vec3 F_i = Vec3::Zero(), T_i = Vec3::Zero(), F_j = Vec3::Zero(), T_j = Vec3::Zero();
};

/// What a family reads at one instant.
struct ConstraintInput {
  const BodyKinematics& i;
  const BodyKinematics& j;
  Jet f;                 // driver function value and derivatives (SI); zero for joints
  double angle_ref = 0;  // unwrapping reference for multi-turn angles (rad)
};

/// Extended precision (x87 long double: 64-bit significand, 11 bits more than double)
/// for the accuracy phase of the position solve: near a dead centre the answer's
/// derivatives amplify the position error by κ per order, and a residual evaluated in
/// double cannot place the pose closer than round-off of the coordinates allows.
using Real = long double;
using Vec3R = Eigen::Matrix<Real, 3, 1>;
using Vec4R = Eigen::Matrix<Real, 4, 1>;
using Mat3R = Eigen::Matrix<Real, 3, 3>;

/// A body pose in extended precision: what Φ reads (r, A), nothing of the rates.
struct ExtendedPose {
  Vec3R r = Vec3R::Zero();
  Vec4R p = Vec4R(1, 0, 0, 0);
  Mat3R A = Mat3R::Identity();

  static ExtendedPose Of(const BodyKinematics& b) { return {b.r[0].cast<Real>(), b.p.cast<Real>(), b.A.cast<Real>()}; }
  Vec3R Point(const Vec3& s) const { return r + A * s.cast<Real>(); }
  Vec3R Vector(const Vec3& a) const { return A * a.cast<Real>(); }
};

/// What a family's Φ reads in extended precision.
struct ExtendedInput {
  const ExtendedPose& i;
  const ExtendedPose& j;
  Real f = 0;             // driver function value (SI); zero for joints
  double angle_ref = 0;   // as in ConstraintInput
};

class Constraint {
 public:
  Constraint(BodyIndex body_i, BodyIndex body_j, int size) : body_i_(body_i), body_j_(body_j), size_(size) {}
  virtual ~Constraint() = default;

  int size() const { return size_; }
  BodyIndex body_i() const { return body_i_; }
  BodyIndex body_j() const { return body_j_; }

  virtual void CalcPhi(const ConstraintInput& in, double* phi) const = 0;
  /// The same Φ in extended precision (the families share one template for both).
  virtual void CalcPhiExtended(const ExtendedInput& in, Real* phi) const = 0;
  virtual void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const = 0;
  /// RHS_k, ω' version, k = 1..4. Kinematics of orders < k must be set in `in`.
  virtual void CalcRhs(const ConstraintInput& in, int k, double* rhs) const = 0;
  /// κ for multipliers λ (size() of them); velocities must be set in `in`.
  virtual void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const = 0;
  /// Multi-turn angle this family tracks (rotation drivers, screws); 0 otherwise.
  virtual double CalcAngle(const ConstraintInput&) const { return 0; }
  virtual bool HasAngle() const { return false; }
  /// Φ of this family has units length^LengthPower(): SPH, DOT_2, D2DD, SDA 1; SPH_SPH,
  /// 3DRDD 2; DOT_1, GRRD 0. Residuals are divided by L^power (L the characteristic
  /// length) so that every tolerance is relative to the mechanism's size.
  virtual int LengthPower() const = 0;
  /// How far equation `row` is from closing, in metres (LengthPower ≥ 1) or radians
  /// (power 0): Φ itself, except for squared distances, where it is |d| − L.
  virtual double Misfit(const ConstraintInput&, int /*row*/, double phi) const { return phi; }
  /// Short name of the family ("SPH", "DOT_1", ...), and of equation `row`.
  virtual const char* family() const = 0;

 private:
  BodyIndex body_i_, body_j_;
  int size_;
};

/// Φ_p blocks (size()×4) of body i and j: Φ_p = 2 Φ_π' G (§1.5).
void CalcPVersionJacobian(const Constraint& c, const ConstraintInput& in, const JacobianBlocks& J,
                          Eigen::Matrix<double, kMaxRows, 4>* p_i, Eigen::Matrix<double, kMaxRows, 4>* p_j);
/// RHS_k, p version: equal to the ω' version for k ≤ 2; for k = 3, 4 the
/// correction −Σ Φ_π'k v_k (v3_k) of §1.7.
void CalcPVersionRhs(const Constraint& c, const ConstraintInput& in, int k, double* rhs);

/// m-th derivative of d_ij = r^P_j − r^P_i for body points s'_i, s'_j (m = 0: d itself).
inline Vec3 RelativePointDerivative(const ConstraintInput& in, const Vec3& s_i, const Vec3& s_j, int m) {
  return in.j.PointDerivative(s_j, m) - in.i.PointDerivative(s_i, m);
}

/// Continuous angle: atan2(s, c) shifted by whole turns to lie within π of `ref`.
template <typename S>
S UnwrapAngle(S s, S c, double ref) {
  using std::atan2, std::round;
  const S two_pi = 2 * S(3.141592653589793238462643383279502884L);
  const S raw = atan2(s, c);
  const S turns = round((S(ref) - raw) / two_pi);
  return raw + two_pi * turns;
}

}  // namespace mechkin
