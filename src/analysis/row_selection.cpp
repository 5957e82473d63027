#include "analysis/row_selection.hpp"

#include <Eigen/QR>

#include "kinematics/position.hpp"
#include "kinematics/sparse_rank.hpp"
#include "mobility/mobility.hpp"

namespace mechkin {

// Greedy independence threshold on the scaled rows (relative norm of the new direction).
constexpr double kRowIndependence = 1e-7;

namespace {

void NameSetAside(const ConstraintSystem& sys, RowSelection* sel) {
  for (int row : sel->set_aside) {
    if (row >= sys.num_joint_rows()) sel->conflicting_drivers.push_back(sys.SourceName(row));
    else sel->set_aside_names.push_back(sys.DescribeRow(row));
  }
  sel->set_aside_scales = RowScales(sys, sel->set_aside);
}

}  // namespace


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
  NameSetAside(sys, &sel);
  return sel;
}

RowSelection SelectWellConditionedRows(const ConstraintSystem& sys, const SystemState& s) {
  RowSelection sel;
  const Eigen::MatrixXd J = ScaledJacobian(sys, s);
  const int n = static_cast<int>(J.cols()), joints = sys.num_joint_rows(), drivers = sys.num_rows() - joints;
  // Drivers are the prescription: project the joint rows onto the complement of their span.
  const Eigen::MatrixXd D = J.bottomRows(drivers);
  Eigen::MatrixXd Jj = J.topRows(joints);
  if (drivers > 0) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> dq(D.transpose());
    const Eigen::MatrixXd Q1 = dq.householderQ() * Eigen::MatrixXd::Identity(n, drivers);
    Jj -= (Jj * Q1) * Q1.transpose();
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Jj.transpose());
  qr.setThreshold(kRowIndependence);
  const int need = n - drivers;
  if (qr.rank() < need) return sel;  // the full system is singular here: nothing better to choose
  std::vector<char> chosen(sys.num_rows(), 0);
  for (int k = 0; k < need; ++k) chosen[qr.colsPermutation().indices()[k]] = 1;
  for (int r = joints; r < sys.num_rows(); ++r) chosen[r] = 1;
  for (int r = 0; r < sys.num_rows(); ++r) (chosen[r] ? sel.active : sel.set_aside).push_back(r);
  NameSetAside(sys, &sel);
  return sel;
}

std::string DrivingRefusal(const ConstraintSystem& sys, const RowSelection& sel) {
  const int n = sys.num_bodies();
  if (sel.conflicting_drivers.empty() && static_cast<int>(sel.active.size()) == 6 * n) return "";
  // Before blaming the drivers: the joints may lock the mechanism, or the design
  // pose may be a singular position of the driven mechanism.
  const MobilityReport mob = CalcMobility(sys.model());
  if (mob.locked) return mob.verdict + ". The drivers cannot move it (mechkin check).";
  if (mob.singular_lost > 0) {
    std::string m = "the design pose is a singular position of the driven mechanism: the drivers control " +
                    std::to_string(mob.singular_lost) + " fewer direction(s) there than at nearby poses";
    for (const auto& d : mob.singular_directions) m += "\n    " + d;
    return m + "\n  The run starts at the design pose: move it off the singular position (e.g. change a joint "
               "angle or a leg length slightly).";
  }
  // The status check reports (JudgeDriving); idle spins are freedoms left.
  if (!sel.conflicting_drivers.empty() || mob.driving_status == DrivingStatus::Over) {
    const auto& conflicting = sel.conflicting_drivers.empty() ? mob.conflicting_drivers : sel.conflicting_drivers;
    std::string m = "over-driven: driver(s) ";
    for (size_t k = 0; k < conflicting.size(); ++k) m += (k ? ", `" : "`") + conflicting[k] + "`";
    return m + " conflict with the joints or other drivers. Remove or change them (mechkin check names the freedoms).";
  }
  std::string m = "under-driven: " + std::to_string(6 * n - static_cast<int>(sel.active.size())) +
                  " freedom(s) are not driven";
  for (const auto& f : mob.remaining_freedoms)
    if (f.rfind("idle, not driven: ", 0) != 0) m += "\n    " + f;
  for (const auto& f : mob.idle) m += "\n    idle: " + f.description;
  return m + "\n  Add drivers, or remove the idle freedoms (see mechkin check).";
}

}  // namespace mechkin
