// The constraint families of constraints.md §3. Each class implements one
// family; its source file cites the formulas it implements. Right-hand sides
// are written order-generically with the Leibniz rule: for Φ = x·y,
//   d^kΦ/dt^k = Σ_m binom(k,m) x^(m)·y^(k−m),
// and RHS_k is minus every term except the unknown highest derivative, i.e. the
// k = 0 and m = k terms contribute only their "bias" part (B[k] of
// BodyKinematics). For k = 2, 3, 4 this reproduces the printed γ, η, σ of §3.
#pragma once

#include <algorithm>
#include <cmath>

#include "constraints/constraint.hpp"

namespace mechkin {

/// Leibniz coefficients binom(k, m), k ≤ 4.
constexpr double kBinomial[5][5] = {{1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}, {1, 4, 6, 4, 1}};

/// §3.1 SPH: r^P_j − r^P_i = 0 (3 equations).
class SphericalConstraint : public Constraint {
 public:
  SphericalConstraint(BodyIndex i, BodyIndex j, const Vec3& s_i, const Vec3& s_j)
      : Constraint(i, j, 3), s_i_(s_i), s_j_(s_j), tilde_s_i_(Tilde(s_i)), tilde_s_j_(Tilde(s_j)) {}
  void CalcPhi(const ConstraintInput& in, double* phi) const override { Phi(in.i, in.j, in.f.c[0], in.angle_ref, phi); }
  void CalcPhiExtended(const ExtendedInput& in, Real* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  void CalcPhiJet(const JetInput& in, ExtendedJet* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  bool CalcPhiQuad(const QuadInput& in, Quad* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); return true; }
  void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const override;
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override;
  void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const override;
  const char* family() const override { return "SPH"; }
  int LengthPower() const override { return 1; }

  /// Φ = r^P_j − r^P_i (§3.1) on any pose type (BodyKinematics or ExtendedPose):
  /// S = double or Real. Every family's Phi below has this signature (f, angle ref).
  template <class Pose, typename S>
  void Phi(const Pose& i, const Pose& j, S, double, S* phi) const {
    const Eigen::Matrix<S, 3, 1> d = j.Point(s_j_) - i.Point(s_i_);
    for (int k = 0; k < 3; ++k) phi[k] = d[k];
  }

 private:
  Vec3 s_i_, s_j_;
  // s̃'_i, s̃'_j built once: a Tilde made in the Jacobian is written to the stack entry by
  // entry and read back in pairs, and each such load waits for two pending stores.
  Mat3 tilde_s_i_, tilde_s_j_;
};

/// §3.2 SPH_SPH: dᵀd − L² = 0; with a driver function, §3.7 3DRDD: dᵀd − f(t)² = 0.
class DistanceConstraint : public Constraint {
 public:
  /// length > 0: fixed link (SPH_SPH); length == 0: driven by f(t) (3DRDD).
  DistanceConstraint(BodyIndex i, BodyIndex j, const Vec3& s_i, const Vec3& s_j, double length)
      : Constraint(i, j, 1), s_i_(s_i), s_j_(s_j), length_(length) {}
  void CalcPhi(const ConstraintInput& in, double* phi) const override { Phi(in.i, in.j, in.f.c[0], in.angle_ref, phi); }
  void CalcPhiExtended(const ExtendedInput& in, Real* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  void CalcPhiJet(const JetInput& in, ExtendedJet* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  bool CalcPhiQuad(const QuadInput& in, Quad* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); return true; }
  void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const override;
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override;
  void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const override;
  const char* family() const override { return length_ > 0 ? "SPH_SPH" : "3DRDD"; }
  int LengthPower() const override { return 2; }
  bool driven() const { return !(length_ > 0); }
  double Misfit(const ConstraintInput& in, int, double phi) const override {
    const double L = driven() ? in.f.c[0] : length_;
    return std::sqrt(std::max(phi + L * L, 0.0)) - L;  // |d| − L
  }

  /// Φ = dᵀd − L² (§3.2), or − f² (§3.7).
  template <class Pose, typename S>
  void Phi(const Pose& i, const Pose& j, S f, double, S* phi) const {
    const S L = driven() ? f : S(length_);
    *phi = (j.Point(s_j_) - i.Point(s_i_)).squaredNorm() - L * L;
  }

 private:
  Vec3 s_i_, s_j_;
  double length_;
};

/// §3.3 DOT_1: a_iᵀ a_j = 0 for body-fixed vectors a'_i, a'_j.
class Dot1Constraint : public Constraint {
 public:
  Dot1Constraint(BodyIndex i, BodyIndex j, const Vec3& a_i, const Vec3& a_j)
      : Constraint(i, j, 1), a_i_(a_i), a_j_(a_j), tilde_a_i_(Tilde(a_i)), tilde_a_j_(Tilde(a_j)) {}
  void CalcPhi(const ConstraintInput& in, double* phi) const override { Phi(in.i, in.j, in.f.c[0], in.angle_ref, phi); }
  void CalcPhiExtended(const ExtendedInput& in, Real* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  void CalcPhiJet(const JetInput& in, ExtendedJet* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  bool CalcPhiQuad(const QuadInput& in, Quad* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); return true; }
  void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const override;
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override;
  void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const override;
  const char* family() const override { return "DOT_1"; }
  int LengthPower() const override { return 0; }

  /// Φ = a_iᵀa_j (§3.3).
  template <class Pose, typename S>
  void Phi(const Pose& i, const Pose& j, S, double, S* phi) const {
    *phi = i.Vector(a_i_).dot(j.Vector(a_j_));
  }

 private:
  Vec3 a_i_, a_j_;
  Mat3 tilde_a_i_, tilde_a_j_;  // ã'_i, ã'_j for the Jacobian (built once: see SphericalConstraint)
};

/// §3.4 DOT_2: a_iᵀ d_ij = 0, d_ij = r^P_j − r^P_i. Also the shared core of D2DD (§3.8)
/// and SDA (§3.10), which divide it by L = |a'_i|.
class Dot2Constraint : public Constraint {
 public:
  Dot2Constraint(BodyIndex i, BodyIndex j, const Vec3& a_i, const Vec3& s_i, const Vec3& s_j)
      : Constraint(i, j, 1), a_i_(a_i), s_i_(s_i), s_j_(s_j), tilde_a_i_(Tilde(a_i)), tilde_s_i_(Tilde(s_i)),
        tilde_s_j_(Tilde(s_j)) {}
  void CalcPhi(const ConstraintInput& in, double* phi) const override { Phi(in.i, in.j, in.f.c[0], in.angle_ref, phi); }
  void CalcPhiExtended(const ExtendedInput& in, Real* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  void CalcPhiJet(const JetInput& in, ExtendedJet* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  bool CalcPhiQuad(const QuadInput& in, Quad* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); return true; }
  void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const override;
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override;
  void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const override;
  const char* family() const override { return "DOT_2"; }
  int LengthPower() const override { return 1; }
  double length() const { return a_i_.norm(); }

  /// Φ = a_iᵀd_ij (§3.4).
  template <class Pose, typename S>
  void Phi(const Pose& i, const Pose& j, S, double, S* phi) const {
    *phi = i.Vector(a_i_).dot(j.Point(s_j_) - i.Point(s_i_));
  }

 private:
  Vec3 a_i_, s_i_, s_j_;
  Mat3 tilde_a_i_, tilde_s_i_, tilde_s_j_;  // for the Jacobian (built once: see SphericalConstraint)
};

/// §3.8 D2DD: a_iᵀ d_ij / L − f(t) = 0 (translation driver; a_i = h_i, L = 1).
class Dot2DistanceDriver : public Constraint {
 public:
  Dot2DistanceDriver(BodyIndex i, BodyIndex j, const Vec3& a_i, const Vec3& s_i, const Vec3& s_j)
      : Constraint(i, j, 1), dot2_(i, j, a_i, s_i, s_j) {}
  void CalcPhi(const ConstraintInput& in, double* phi) const override { Phi(in.i, in.j, in.f.c[0], in.angle_ref, phi); }
  void CalcPhiExtended(const ExtendedInput& in, Real* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  void CalcPhiJet(const JetInput& in, ExtendedJet* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  bool CalcPhiQuad(const QuadInput& in, Quad* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); return true; }
  void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const override;
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override;
  void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const override;
  const char* family() const override { return "D2DD"; }
  int LengthPower() const override { return 1; }

  /// Φ = a_iᵀd_ij / L − f (§3.8).
  template <class Pose, typename S>
  void Phi(const Pose& i, const Pose& j, S f, double ref, S* phi) const {
    dot2_.Phi(i, j, f, ref, phi);
    *phi = *phi / S(dot2_.length()) - f;
  }

 private:
  Dot2Constraint dot2_;
};

/// §3.9 GRRD: θ_ij − f(t) = 0, θ = atan2(g_iᵀf_j, f_iᵀf_j) unwrapped. With body i =
/// ground it is the fixed revolute rotation driver (§3.6, seed note: any design
/// orientation). The Jacobian is the exact gradient, valid off the joint manifold.
class RotationDriver : public Constraint {
 public:
  RotationDriver(BodyIndex i, BodyIndex j, const JointFrame& frame_i, const JointFrame& frame_j)
      : Constraint(i, j, 1), fi_(frame_i.f), gi_(frame_i.g), fj_(frame_j.f), hi_(frame_i.h), hj_(frame_j.h) {}
  void CalcPhi(const ConstraintInput& in, double* phi) const override { Phi(in.i, in.j, in.f.c[0], in.angle_ref, phi); }
  void CalcPhiExtended(const ExtendedInput& in, Real* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  void CalcPhiJet(const JetInput& in, ExtendedJet* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const override;
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override;
  void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const override;
  double CalcAngle(const ConstraintInput& in) const override;
  bool HasAngle() const override { return true; }
  const char* family() const override { return "GRRD"; }
  int LengthPower() const override { return 0; }
  /// Exact gradient of θ (§3.9): rows for π'_i and π'_j.
  void CalcAngleGradient(const ConstraintInput& in, Vec3* d_pi_i, Vec3* d_pi_j) const;

  /// θ_ij on any pose type, continued over whole turns from `ref`.
  template <class Pose>
  auto Angle(const Pose& i, const Pose& j, double ref) const {
    const auto fj = j.Vector(fj_);
    return UnwrapAngle(i.Vector(gi_).dot(fj), i.Vector(fi_).dot(fj), ref);
  }
  /// Φ = θ_ij − f (§3.9).
  template <class Pose, typename S>
  void Phi(const Pose& i, const Pose& j, S f, double ref, S* phi) const {
    *phi = Angle(i, j, ref) - f;
  }

 protected:
  Vec3 fi_, gi_, fj_, hi_, hj_;
};

/// §3.9 GRRD off the joint manifold: the same Φ = θ_ij − f(t) and gradient, for two
/// bodies that no revolute keeps aligned (an `angle` driver between body vectors).
/// RHS_k = f^(k) − θ^(k)|bias: θ's k-th derivative on Taylor jets of the frame vectors
/// with their order-k terms replaced by the bias A B[k] a' (the part without the
/// unknowns ω'^(k−1)); κ = λ d/dt(Φ_π')ᵀ from the gradient on first-order jets.
class AngleDriver : public RotationDriver {
 public:
  using RotationDriver::RotationDriver;
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override;
  void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const override;
};

/// §3.10 SDA, general two-body form: h_iᵀ d_ij − λ_s θ_ij = 0, λ_s = pitch / 2π.
class ScrewConstraint : public Constraint {
 public:
  ScrewConstraint(BodyIndex i, BodyIndex j, const JointFrame& frame_i, const JointFrame& frame_j, double pitch)
      : Constraint(i, j, 1),
        dot2_(i, j, frame_i.h, frame_i.origin, frame_j.origin),
        angle_(i, j, frame_i, frame_j),
        lambda_s_(pitch / (2 * M_PI)) {}
  void CalcPhi(const ConstraintInput& in, double* phi) const override { Phi(in.i, in.j, in.f.c[0], in.angle_ref, phi); }
  void CalcPhiExtended(const ExtendedInput& in, Real* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  void CalcPhiJet(const JetInput& in, ExtendedJet* phi) const override { Phi(in.i, in.j, in.f, in.angle_ref, phi); }
  void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const override;
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override;
  void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const override;
  double CalcAngle(const ConstraintInput& in) const override { return angle_.CalcAngle(in); }
  bool HasAngle() const override { return true; }
  const char* family() const override { return "SDA"; }
  int LengthPower() const override { return 1; }

  /// Φ = h_iᵀd_ij − λ_s θ_ij (§3.10).
  template <class Pose, typename S>
  void Phi(const Pose& i, const Pose& j, S f, double ref, S* phi) const {
    dot2_.Phi(i, j, f, ref, phi);
    *phi -= S(lambda_s_) * angle_.Angle(i, j, ref);
  }

 private:
  Dot2Constraint dot2_;
  RotationDriver angle_;
  double lambda_s_;
};

/// §3.5 EUL: pᵀp − 1 = 0, one per body, p version only. Not a two-body family:
/// plain functions.
struct EulerNormalization {
  static double Phi(const Vec4& p) { return p.squaredNorm() - 1; }
  /// Φ_p = 2pᵀ.
  static Vec4 Jacobian(const Vec4& p) { return 2 * p; }
  /// RHS_k from p^(0..k−1): 0, −2ṗᵀṗ, −6ṗᵀp̈, −6p̈ᵀp̈ − 8ṗᵀp⃛ (§1.6, §3.5).
  static double Rhs(const Vec4* pd, int k);
};

}  // namespace mechkin
