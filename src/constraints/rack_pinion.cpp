// §3.11 rack and pinion: s₂ − ρ θ₁ = 0 (m), c = (−ρ, 1), c_0 = 0: the rack travels
// the pitch radius times the pinion's turn, counted over whole turns.
#include "constraints/couplers.hpp"

namespace mechkin {

RackPinionConstraint::RackPinionConstraint(const CoordinateTerm& pinion, const CoordinateTerm& rack, double pitch_radius)
    : CouplerConstraint({ScaledTerm(pinion, true, -pitch_radius), ScaledTerm(rack, false, 1)}, 0) {}

}  // namespace mechkin
