// Relative orientation of two bodies as the quantities engineers read (issue
// "Say what engineers measure"): rotation-sequence angles, Euler parameters and
// the rotation vector, each as a Jet so that every time derivative up to the
// run's order follows exactly (chain rule on the solved ω' series, §1.3).
//
// R = A1ᵀA2 takes body2's coordinates to body1's: R_ab = (A1 e_a)·(A2 e_b), each a
// product of body-fixed vectors whose derivatives are A D[k] e (body_kinematics.hpp).
// Sequences are intrinsic: "ZYX" is R = Rz(α) Ry(β) Rx(γ) (yaw, pitch, roll).
#pragma once

#include <array>
#include <string>

#include "constraints/body_kinematics.hpp"
#include "math/taylor.hpp"

namespace mechkin {

using RotationJet = std::array<std::array<Jet, 3>, 3>;

/// R = A1ᵀA2 with derivatives to `order`.
RotationJet RelativeRotation(const BodyKinematics& b1, const BodyKinematics& b2, int order);
/// Of frames fixed in the bodies (columns of F1, F2: their axes in body coordinates):
/// R = (A1F1)ᵀ(A2F2) — a spherical joint's frames.
RotationJet RelativeRotation(const BodyKinematics& b1, const Mat3& F1, const BodyKinematics& b2, const Mat3& F2,
                             int order);

/// The three angles of an intrinsic sequence ("XYZ" … "ZYX", "XYX" … "ZYZ").
/// Returns false at gimbal lock (the middle angle at ±90°, or 0/180° for a proper
/// Euler sequence, to 1e-7): the first and third angles are then not separately
/// defined; angles[1] is still valid.
bool SequenceAngles(const RotationJet& R, const std::string& sequence, std::array<Jet, 3>* angles);

/// Euler parameters of body2 relative to body1 (scalar first) with derivatives.
std::array<Jet, 4> RelativeEulerParameters(const BodyKinematics& b1, const BodyKinematics& b2, int order);
/// Of frames fixed in the bodies (unit quaternions q1, q2 of F1, F2).
std::array<Jet, 4> RelativeEulerParameters(const BodyKinematics& b1, const Vec4& q1, const BodyKinematics& b2,
                                           const Vec4& q2, int order);

/// Rotation vector θ·n of unit Euler parameters q (θ = 2 atan2(|v|, q0)), smooth through θ = 0.
std::array<Jet, 3> RotationVector(const std::array<Jet, 4>& q);

}  // namespace mechkin
