// §3.11 gear: θ₂ − r θ₁ = 0, i.e. the coupler with c = (−r, 1), c_0 = 0; both
// coordinates are joint rotations counted over whole turns (bevel and worm pairs
// are gears between joints with non-parallel axes: the equation is the same).
#include "constraints/couplers.hpp"

namespace mechkin {

GearConstraint::GearConstraint(const CoordinateTerm& joint1, const CoordinateTerm& joint2, double ratio)
    : CouplerConstraint({ScaledTerm(joint1, -ratio), ScaledTerm(joint2, 1)}, 0) {}

}  // namespace mechkin
