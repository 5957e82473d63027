#include "analysis/row_selection.hpp"

#include "kinematics/position.hpp"
#include "kinematics/sparse_rank.hpp"
#include "mobility/mobility.hpp"

namespace mechkin {

// Greedy independence threshold on the scaled rows (relative norm of the new direction).
constexpr double kRowIndependence = 1e-7;

RowSelection SelectRows(const ConstraintSystem& sys, const SystemState& s) {
  RowSelection sel;
  if (6 * sys.num_bodies() <= 1200) {
    sel.active = IndependentRows(ScaledJacobian(sys, s), kRowIndependence, &sel.set_aside);
  } else {
    // Large models: the same greedy file-order rule by the sparse rank-revealing QR.
    const SparseRowRank rr(ScaledSparseJacobian(sys, s, AllRows(sys)), kRowIndependence);
    if (rr.ok()) {
      sel.active = rr.independent();
      sel.set_aside = rr.dependent();
    } else {
      sel.active = AllRows(sys);
    }
  }
  for (int row : sel.set_aside) {
    if (row >= sys.num_joint_rows()) sel.conflicting_drivers.push_back(sys.SourceName(row));
    else sel.set_aside_names.push_back(sys.DescribeRow(row));
  }
  sel.set_aside_scales = RowScales(sys, sel.set_aside);
  return sel;
}

std::string DrivingRefusal(const ConstraintSystem& sys, const RowSelection& sel) {
  if (!sel.conflicting_drivers.empty()) {
    std::string m = "over-driven: driver(s) ";
    for (size_t k = 0; k < sel.conflicting_drivers.size(); ++k) m += (k ? ", `" : "`") + sel.conflicting_drivers[k] + "`";
    return m + " conflict with the joints or other drivers. Remove or change them (mechkin check names the freedoms).";
  }
  const int n = sys.num_bodies();
  if (static_cast<int>(sel.active.size()) == 6 * n) return "";
  const MobilityReport mob = CalcMobility(sys.model());
  std::string m = "under-driven: " + std::to_string(6 * n - static_cast<int>(sel.active.size())) +
                  " freedom(s) are not driven";
  for (const auto& f : mob.remaining_freedoms) m += "\n    " + f;
  for (const auto& f : mob.idle) m += "\n    idle: " + f.description;
  return m + "\n  Add drivers, or remove the idle freedoms (see mechkin check).";
}

}  // namespace mechkin
