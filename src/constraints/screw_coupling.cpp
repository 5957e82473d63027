// §3.11 screw coupling: s₂ − (p/2π) θ₁ = 0 (m), c = (−p/2π, 1), c_0 = 0: a leadscrew
// turning in one joint drives a nut sliding in another (a screw joint couples the
// two coordinates of one joint, §3.10; this couples two joints).
#include <cmath>

#include "constraints/couplers.hpp"

namespace mechkin {

ScrewCouplingConstraint::ScrewCouplingConstraint(const CoordinateTerm& screw, const CoordinateTerm& nut, double pitch)
    : CouplerConstraint({ScaledTerm(screw, true, -pitch / (2 * M_PI)), ScaledTerm(nut, false, 1)}, 0) {}

}  // namespace mechkin
