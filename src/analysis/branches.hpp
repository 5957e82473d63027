// How many assembly branches a mechanism has at its drivers' design values
// (issue "Say what engineers measure": `check --branches`): the assembly is
// restarted from randomly displaced poses (seeded) and the distinct solutions
// are counted. A solution with a joint mounted backwards (a revolute, prismatic,
// cylindrical or screw joint whose two axes come out opposite) is the same
// joint assembled the other way round, not a branch of this mechanism, and is
// not counted.
#pragma once

#include <functional>
#include <vector>

#include "model/model.hpp"

namespace mechkin {

struct BranchCount {
  int branches = 0;   // distinct poses found (the design's included)
  int restarts = 0;   // starts tried
  int converged = 0;  // starts that assembled (before deduplication and the axis filter)
  std::vector<double> distances;  // per branch: its largest body move from the design pose (/ size, or rad)
};

/// `restarts` random starts (bodies moved up to the mechanism's size and turned
/// up to 180°), seeded. Dense models only (up to 200 bodies); else branches = 0.
/// `stop` (when set) is asked before each restart: true ends the count there
/// (restarts then says how many were tried).
BranchCount CountBranches(const Model& model, int restarts, unsigned long seed = 1,
                          const std::function<bool()>& stop = {});

}  // namespace mechkin
