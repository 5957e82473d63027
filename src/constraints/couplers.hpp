// Couplers between joint coordinates (constraints.md §3.11): one equation
//   Φ = Σ_k c_k q_k − c_0 = 0
// over two or three joint coordinates q_k, each the rotation θ of a revolute,
// cylindrical or screw joint (GRRD's angle of §3.9, continued over whole turns) or
// the slide s of a prismatic, cylindrical or screw joint (D2DD's h_iᵀd_ij of §3.8),
// both 0 at the design pose (or where the joint's markers coincide). The joints'
// bodies are the family's sides (up to six). Gear, belt, rack-and-pinion and
// screw coupling are the two-coordinate forms (one file each); `coupling` is the
// general one.
#pragma once

#include <memory>
#include <vector>

#include "constraints/families.hpp"

namespace mechkin {

/// One joint coordinate of a coupler: its joint's bodies and frames, and c_k.
struct CoordinateTerm {
  bool rotation = true;           // θ (rad); false: the slide s (m)
  BodyIndex body1 = kGround, body2 = kGround;
  JointFrame frame1, frame2;      // the joint's frames (coincide at the coordinate's zero)
  double coefficient = 1;         // c_k (SI: per rad or per m)
};

/// The coordinate t with coefficient c in a coupler's sum (each coupler's file says why
/// c has its value); the second form also says whether the coordinate is a turn θ or a
/// slide s (rack and pinion, screw coupling: one of each).
inline CoordinateTerm ScaledTerm(CoordinateTerm t, double c) {
  t.coefficient = c;
  return t;
}
inline CoordinateTerm ScaledTerm(CoordinateTerm t, bool rotation, double c) {
  t.rotation = rotation;
  return ScaledTerm(t, c);
}

/// §3.11 the linear coupler Σ c_k q_k − c_0. Φ_q, RHS_k and κ are the sums of the
/// coordinates' own (GRRD's with f = 0 on the joint manifold: RHS_k = 0, κ = 0;
/// D2DD's with f = 0) scaled by c_k, each on its joint's two sides.
class CouplerConstraint : public Constraint {
 public:
  CouplerConstraint(const std::vector<CoordinateTerm>& terms, double constant);
  void CalcPhi(const ConstraintInput& in, double* phi) const override { PhiOf(in, phi); }
  void CalcPhiExtended(const ExtendedInput& in, Real* phi) const override { PhiOf(in, phi); }
  void CalcPhiJet(const JetInput& in, ExtendedJet* phi) const override { PhiOf(in, phi); }
  void CalcJacobian(const ConstraintInput& in, JacobianBlocks* J) const override;
  void CalcRhs(const ConstraintInput& in, int k, double* rhs) const override;
  void CalcKappa(const ConstraintInput& in, const double* lambda, KappaTerms* kappa) const override;
  double CalcAngle(const ConstraintInput& in) const override;
  bool HasAngle() const override { return num_angles_ > 0; }
  int NumAngles() const override { return num_angles_; }
  void CalcAngles(const ConstraintInput& in, double* angles) const override;
  const char* family() const override { return "COUPLER"; }
  /// Φ in metres when a slide takes part (§3.11: the compile step scales c_k so), else radians.
  int LengthPower() const override { return has_slide_ ? 1 : 0; }
  int num_terms() const { return num_terms_; }
  /// c_k of coordinate k, whether it is a rotation, and its m-th time derivative
  /// q_k^(m) = ∂q_k/∂q q^(m) − RHS_m(q_k) (m ≥ 1; the kinematics of orders ≤ m set).
  double coefficient(int k) const { return terms_[k].c; }
  bool is_rotation(int k) const { return static_cast<bool>(terms_[k].rotation); }
  double CoordinateDerivative(const ConstraintInput& in, int k, int m) const;

  /// Φ = Σ c_k q_k − c_0 on either input type (double or extended precision).
  template <class Input, typename S>
  void PhiOf(const Input& in, S* phi) const {
    S sum = S(-constant_);
    for (int k = 0; k < num_terms_; ++k) {
      const Term& t = terms_[k];
      const auto& a = in.Side(t.side_a);
      const auto& b = in.Side(t.side_b);
      S q;
      if (t.rotation) q = t.rotation->Angle(a, b, t.angle >= 0 ? in.AngleRef(t.angle) : 0.0);
      else t.slide->Phi(a, b, S(0), 0.0, &q);
      sum += S(t.c) * q;
    }
    *phi = sum;
  }

 private:
  struct Term {
    double c = 0;
    int side_a = 0, side_b = 1;  // sides of the joint's body1 and body2
    int angle = -1;              // index among the tracked angles (rotations)
    std::unique_ptr<RotationDriver> rotation;
    std::unique_ptr<Dot2DistanceDriver> slide;
  };
  /// The coordinate's own two-body input (f = 0) read from the coupler's sides.
  ConstraintInput TermInput(const ConstraintInput& in, const Term& t) const;
  const Constraint& TermFamily(const Term& t) const {
    return t.rotation ? static_cast<const Constraint&>(*t.rotation) : *t.slide;
  }

  Term terms_[kMaxAngles];
  int num_terms_ = 0, num_angles_ = 0;
  bool has_slide_ = false;
  double constant_ = 0;
};

/// §3.11 gear (and bevel or worm pair): θ₂ − r θ₁ = 0 (r < 0 for an external mesh).
class GearConstraint : public CouplerConstraint {
 public:
  GearConstraint(const CoordinateTerm& joint1, const CoordinateTerm& joint2, double ratio);
  const char* family() const override { return "GEAR"; }
};

/// §3.11 belt or chain: θ₂ − r θ₁ = 0, r = ± d₁/d₂ (negative for a crossed belt).
class BeltConstraint : public CouplerConstraint {
 public:
  BeltConstraint(const CoordinateTerm& joint1, const CoordinateTerm& joint2, double ratio);
  const char* family() const override { return "BELT"; }
};

/// §3.11 rack and pinion: s₂ − ρ θ₁ = 0, ρ the pinion's pitch radius (m).
class RackPinionConstraint : public CouplerConstraint {
 public:
  RackPinionConstraint(const CoordinateTerm& pinion, const CoordinateTerm& rack, double pitch_radius);
  const char* family() const override { return "RACK_PINION"; }
};

/// §3.11 screw coupling (leadscrew and nut on two joints): s₂ − (p/2π) θ₁ = 0.
class ScrewCouplingConstraint : public CouplerConstraint {
 public:
  ScrewCouplingConstraint(const CoordinateTerm& screw, const CoordinateTerm& nut, double pitch);
  const char* family() const override { return "SCREW_COUPLING"; }
};

/// §3.11 general coupling: Σ c_k q_k − c_0 = 0 over 2–3 coordinates (differentials,
/// mimic joints, a planetary mesh written relative to its carrier).
class CouplingConstraint : public CouplerConstraint {
 public:
  using CouplerConstraint::CouplerConstraint;
  const char* family() const override { return "COUPLING"; }
};

}  // namespace mechkin
