// Assembly from dimensions (docs/format.md "Assembly from dimensions"): the loop
// closures of a model that compile placed by its markers (model.assembly set:
// every tree joint closed or sketched, the loops open).
//
// From the starting pose (the tree placement, or the sketch) the joints and the
// drivers at their design values (0 for a joint driver: its markers coincide) are
// solved by damped minimum-norm Gauss–Newton — dense up to 200 bodies, else a
// sparse min-norm step (J Jᵀ + μI, linear in a chain) — then the `analysis.branch`
// hints or flips choose the branch. The model's design pose becomes the closed one
// and model.assembly reports, per loop, the closure error before and after, the
// iterations and how far each body moved from its guess.
#pragma once

#include "model/model.hpp"
#include "spec/diagnostic.hpp"

namespace mechkin {

/// Closes the loops of `model` (a no-op when model.assembly is unset or already
/// assembled). On failure returns false with the diagnostic: the JSON pointer of the
/// joint that closes the loop, the loop and its shortfall, and a fix.
bool AssembleModel(Model* model, Diagnostic* error);

/// The loop's bodies in order, "crank–coupler–rocker" (ground left out).
std::string LoopName(const Model& model, const AssemblyLoop& loop);

}  // namespace mechkin
