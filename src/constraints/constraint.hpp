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

#include <array>
#include <memory>
#include <string>

#include "constraints/body_kinematics.hpp"
#include "math/extended_jet.hpp"
#include "math/quad.hpp"
#include "model/model.hpp"

namespace mechkin {

constexpr int kMaxRows = 3;  // largest family (spherical)
using RowBlock = Eigen::Matrix<double, kMaxRows, 3>;
/// Bodies ("sides") one family may couple: two for the joint families, up to six for
/// a coupler between three joint coordinates (§3.11). Sides 0 and 1 are i and j.
constexpr int kMaxSides = 6;
/// Angles one family tracks over whole turns (a coupler: one per rotation coordinate).
constexpr int kMaxAngles = 3;

/// Jacobian blocks of one family; only the first size() rows are meaningful.
/// Sides 2.. (multi-body families only) are left unset by the two-body families.
struct JacobianBlocks {
  RowBlock r_i = RowBlock::Zero(), pi_i = RowBlock::Zero();
  RowBlock r_j = RowBlock::Zero(), pi_j = RowBlock::Zero();
  RowBlock r_more[kMaxSides - 2], pi_more[kMaxSides - 2];

  const RowBlock& R(int side) const { return side == 0 ? r_i : side == 1 ? r_j : r_more[side - 2]; }
  const RowBlock& Pi(int side) const { return side == 0 ? pi_i : side == 1 ? pi_j : pi_more[side - 2]; }
  RowBlock& R(int side) { return side == 0 ? r_i : side == 1 ? r_j : r_more[side - 2]; }
  RowBlock& Pi(int side) { return side == 0 ? pi_i : side == 1 ? pi_j : pi_more[side - 2]; }
};

/// Reaction-rate terms of §1.8 for every side.
struct KappaTerms {
  Vec3 F_i = Vec3::Zero(), T_i = Vec3::Zero(), F_j = Vec3::Zero(), T_j = Vec3::Zero();
  Vec3 F_more[kMaxSides - 2] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  Vec3 T_more[kMaxSides - 2] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};

  Vec3& F(int side) { return side == 0 ? F_i : side == 1 ? F_j : F_more[side - 2]; }
  Vec3& T(int side) { return side == 0 ? T_i : side == 1 ? T_j : T_more[side - 2]; }
  const Vec3& F(int side) const { return side == 0 ? F_i : side == 1 ? F_j : F_more[side - 2]; }
  const Vec3& T(int side) const { return side == 0 ? T_i : side == 1 ? T_j : T_more[side - 2]; }
};

/// What a family reads at one instant.
struct ConstraintInput {
  // Not an aggregate: value-initializing `more` on every call cost the step loop 8 %
  // (a 96-byte `rep stos` per entry, spatial slider-crank 3.7 → 4.4 µs per step).
  ConstraintInput(const BodyKinematics& side_i, const BodyKinematics& side_j, const Jet& value = Jet{},
                  double reference = 0)
      : i(side_i), j(side_j), f(value), angle_ref(reference) {}

  const BodyKinematics& i;
  const BodyKinematics& j;
  Jet f;                 // driver function value and derivatives (SI); zero for joints
  double angle_ref = 0;  // unwrapping reference for multi-turn angles (rad)
  // Multi-body families (couplers, §3.11): the kinematics of sides 2.., and the
  // references of their second and third tracked angle. Set only for the sides and
  // angles a coupler has (whoever builds its input: MakeInput); unset otherwise.
  std::array<const BodyKinematics*, kMaxSides - 2> more;
  std::array<double, kMaxAngles - 1> more_angle_refs;

  const BodyKinematics& Side(int side) const { return side == 0 ? i : side == 1 ? j : *more[side - 2]; }
  double AngleRef(int a) const { return a == 0 ? angle_ref : more_angle_refs[a - 1]; }
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
  std::array<const ExtendedPose*, kMaxSides - 2> more{};
  std::array<double, kMaxAngles - 1> more_angle_refs{};

  const ExtendedPose& Side(int side) const { return side == 0 ? i : side == 1 ? j : *more[side - 2]; }
  double AngleRef(int a) const { return a == 0 ? angle_ref : more_angle_refs[a - 1]; }
};

/// A body pose in quadruple precision (math/quad.hpp): what Φ reads, for the pose
/// error of the measured error bounds (constraints.md §8, "Measured", step 1).
struct QuadPose {
  Eigen::Matrix<Quad, 3, 1> r = Eigen::Matrix<Quad, 3, 1>::Zero();
  Eigen::Matrix<Quad, 3, 3> A = Eigen::Matrix<Quad, 3, 3>::Identity();

  Eigen::Matrix<Quad, 3, 1> Point(const Vec3& s) const { return r + A * s.cast<Quad>(); }
  Eigen::Matrix<Quad, 3, 1> Vector(const Vec3& a) const { return A * a.cast<Quad>(); }
};

/// What a family's Φ reads in quadruple precision (as ExtendedInput).
struct QuadInput {
  const QuadPose& i;
  const QuadPose& j;
  Quad f = 0;             // driver function value (SI); zero for joints
  double angle_ref = 0;   // as in ConstraintInput
  std::array<const QuadPose*, kMaxSides - 2> more{};
  std::array<double, kMaxAngles - 1> more_angle_refs{};

  const QuadPose& Side(int side) const { return side == 0 ? i : side == 1 ? j : *more[side - 2]; }
  double AngleRef(int a) const { return a == 0 ? angle_ref : more_angle_refs[a - 1]; }
};

/// A body's pose as Taylor series in time (extended precision) along the computed
/// derivatives: Φ on it gives d^kΦ/dt^k = Φ_q q^(k) − RHS_k for every order at once
/// (constraints.md §8, "Measured", step 3).
struct JetPose {
  using Vec3J = Eigen::Matrix<ExtendedJet, 3, 1>;
  using Mat3J = Eigen::Matrix<ExtendedJet, 3, 3>;
  Vec3J r = Vec3J::Constant(ExtendedJet(0));
  Mat3J A = Mat3J::Identity();

  Vec3J Point(const Vec3& s) const { return r + A * s.cast<ExtendedJet>(); }
  Vec3J Vector(const Vec3& a) const { return A * a.cast<ExtendedJet>(); }
};

/// The pose of `body` as series to `order` (≤ kMaxOrder) at orientation A (its
/// normalized one in long double): r(τ) = Σ r^(k) τ^k/k!, and A(τ) from A' = A ω̃'(τ)
/// term by term, a_{k+1} = Σ_{j≤k} a_j ω̃'_{k−j} / (k+1) with ω'_m = ω'^(m)/m! (§1.4).
JetPose JetPoseOf(const BodyKinematics& body, const Mat3R& A, int order);

/// What a family's Φ reads on Taylor series (as ExtendedInput).
struct JetInput {
  const JetPose& i;
  const JetPose& j;
  ExtendedJet f;          // driver function value and derivatives (SI); zero for joints
  double angle_ref = 0;   // as in ConstraintInput
  std::array<const JetPose*, kMaxSides - 2> more{};
  std::array<double, kMaxAngles - 1> more_angle_refs{};

  const JetPose& Side(int side) const { return side == 0 ? i : side == 1 ? j : *more[side - 2]; }
  double AngleRef(int a) const { return a == 0 ? angle_ref : more_angle_refs[a - 1]; }
};

class Constraint {
 public:
  Constraint(BodyIndex body_i, BodyIndex body_j, int size) : size_(size) {
    sides_[0] = body_i;
    sides_[1] = body_j;
  }
  virtual ~Constraint() = default;

  int size() const { return size_; }
  BodyIndex body_i() const { return sides_[0]; }
  BodyIndex body_j() const { return sides_[1]; }
  /// Bodies the family couples: 2, or up to kMaxSides for a multi-body family.
  int num_sides() const { return num_sides_; }
  BodyIndex body(int side) const { return sides_[side]; }

  virtual void CalcPhi(const ConstraintInput& in, double* phi) const = 0;
  /// The same Φ in extended precision (the families share one template for both).
  virtual void CalcPhiExtended(const ExtendedInput& in, Real* phi) const = 0;
  /// The same Φ on Taylor series in time (the families' one template again).
  virtual void CalcPhiJet(const JetInput& in, ExtendedJet* phi) const = 0;
  /// The same Φ in quadruple precision; false for the families that read angles
  /// (atan2 has no quadruple-precision form here): the caller uses CalcPhiExtended's.
  virtual bool CalcPhiQuad(const QuadInput&, Quad*) const { return false; }
  virtual void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const = 0;
  /// RHS_k, ω' version, k = 1..4. Kinematics of orders < k must be set in `in`.
  virtual void CalcRhs(const ConstraintInput& in, int k, double* rhs) const = 0;
  /// κ for multipliers λ (size() of them); velocities must be set in `in`.
  virtual void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const = 0;
  /// Multi-turn angle this family tracks (rotation drivers, screws); 0 otherwise.
  virtual double CalcAngle(const ConstraintInput&) const { return 0; }
  virtual bool HasAngle() const { return false; }
  /// Angles tracked over whole turns (HasAngle: 1; a coupler up to kMaxAngles), and
  /// all of them at once (the first is CalcAngle's).
  virtual int NumAngles() const { return HasAngle() ? 1 : 0; }
  virtual void CalcAngles(const ConstraintInput& in, double* angles) const { angles[0] = CalcAngle(in); }
  /// Φ of this family has units length^LengthPower(): SPH, DOT_2, D2DD, SDA 1; SPH_SPH,
  /// 3DRDD 2; DOT_1, GRRD 0. Residuals are divided by L^power (L the characteristic
  /// length) so that every tolerance is relative to the mechanism's size.
  virtual int LengthPower() const = 0;
  /// How far equation `row` is from closing, in metres (LengthPower ≥ 1) or radians
  /// (power 0): Φ itself, except for squared distances, where it is |d| − L.
  virtual double Misfit(const ConstraintInput&, int /*row*/, double phi) const { return phi; }
  /// Short name of the family ("SPH", "DOT_1", ...), and of equation `row`.
  virtual const char* family() const = 0;

 protected:
  /// A multi-body family's sides (n ≤ kMaxSides, distinct bodies; ground allowed).
  void SetSides(const BodyIndex* bodies, int n) {
    for (int k = 0; k < n; ++k) sides_[k] = bodies[k];
    num_sides_ = n;
  }

 private:
  BodyIndex sides_[kMaxSides] = {kGround, kGround, kGround, kGround, kGround, kGround};
  int num_sides_ = 2;
  int size_;
};

/// Φ_p blocks (size()×4) of body i and j: Φ_p = 2 Φ_π' G (§1.5).
void CalcPVersionJacobian(const Constraint& c, const ConstraintInput& in, const JacobianBlocks& J,
                          Eigen::Matrix<double, kMaxRows, 4>* p_i, Eigen::Matrix<double, kMaxRows, 4>* p_j);
/// Φ_p block (size()×4) of one side.
Eigen::Matrix<double, kMaxRows, 4> PVersionBlock(const ConstraintInput& in, const JacobianBlocks& J, int side);
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
