// §3.11 belt or chain drive: θ₂ − r θ₁ = 0 like a gear (c = (−r, 1), c_0 = 0), the
// sense of r from the belt's arrangement: r = d₁/d₂ open, −d₁/d₂ crossed.
#include "constraints/couplers.hpp"

namespace mechkin {

BeltConstraint::BeltConstraint(const CoordinateTerm& joint1, const CoordinateTerm& joint2, double ratio)
    : CouplerConstraint({ScaledTerm(joint1, -ratio), ScaledTerm(joint2, 1)}, 0) {}

}  // namespace mechkin
