// For the joint files: a joint's rows from the recurring groups of constraints.md §5.
#pragma once

#include <vector>

#include "joints/descriptor.hpp"

namespace mechkin {

/// The groups one after the other (a joint's rows in order).
std::vector<JointEquation> Joined(const std::vector<std::vector<JointEquation>>& groups);

}  // namespace mechkin
