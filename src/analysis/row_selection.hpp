// Which equations a run solves: with redundant equations (overconstrained
// mechanisms) an independent subset of 6n rows is kept and the others are set
// aside, greedily in file order with joints first (so later joints carry the
// redundant equations). Their residual is still checked every step.
#pragma once

#include <string>
#include <vector>

#include "constraints/system.hpp"

namespace mechkin {

struct RowSelection {
  std::vector<int> active;                    // independent rows, solved
  std::vector<int> set_aside;                 // redundant rows, checked only
  std::vector<std::string> set_aside_names;   // joint vocabulary, for the report
  std::vector<std::string> conflicting_drivers;
  Eigen::VectorXd set_aside_scales;           // 1/L^power of the set-aside rows
};

/// Selects the rows at the assembled pose `s`.
RowSelection SelectRows(const ConstraintSystem& sys, const SystemState& s);
/// The best-conditioned independent set at pose `s` (for redundancy that follows
/// the motion): every driver row, then the joint rows a column-pivoted QR picks
/// first in the complement of the drivers' span (scaled Jacobian). Empty `active`
/// when the joints and drivers together no longer have rank 6n there.
RowSelection SelectWellConditionedRows(const ConstraintSystem& sys, const SystemState& s);
/// Empty when the selection drives the mechanism fully; otherwise why the run
/// must refuse (over-driven: the conflicting drivers; under-driven: the freedoms).
std::string DrivingRefusal(const ConstraintSystem& sys, const RowSelection& selection);

}  // namespace mechkin
