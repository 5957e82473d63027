// Grübler–Kutzbach count (constraints.md §6):
//   M = 6 n − 5 n_J1 − 4 n_J2 − 3 n_J3 − 1 n_SS,
// i.e. 6 per moving body minus the equations each joint removes. Drivers are
// not counted.
#pragma once

#include "model/model.hpp"

namespace mechkin {

int CalcGrublerCount(const Model& model);

}  // namespace mechkin
