#include "mobility/mobility.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <functional>
#include <map>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <unordered_map>

#include "constraints/system.hpp"
#include "joints/registry.hpp"
#include "kinematics/position.hpp"
#include "kinematics/sparse_rank.hpp"

namespace mechkin {

namespace {

constexpr int kMaxDenseColumns = 1200;  // 200 bodies; larger models take the sparse QR
constexpr int kMaxNamedRedundant = 200;  // redundant rows whose `fixed_by` is worked out
constexpr int kMaxNamedFreedoms = 16;    // undriven freedoms named by the bodies they move

struct RankInfo {
  int rank = 0;
  double sigma_min_kept = 0, sigma_max_dropped = 0;
  Eigen::MatrixXd null_basis;  // columns span the kernel (scaled coordinates)
};

RankInfo CalcRank(const Eigen::MatrixXd& J) {
  RankInfo info;
  const int n = static_cast<int>(J.cols());
  if (J.rows() == 0) {
    info.null_basis = Eigen::MatrixXd::Identity(n, n);
    return info;
  }
  // BDCSVD: divide and conquer, fast for the few-hundred-column Jacobians of larger
  // mechanisms; it falls back to Jacobi sweeps for small blocks.
  Eigen::BDCSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  const double smax = sv.size() ? sv[0] : 0;
  for (int k = 0; k < sv.size(); ++k) {
    if (sv[k] > kRankThreshold * smax) {
      ++info.rank;
      info.sigma_min_kept = sv[k];
    } else
      info.sigma_max_dropped = std::max(info.sigma_max_dropped, sv[k]);
  }
  info.null_basis = svd.matrixV().rightCols(n - info.rank);
  return info;
}

std::string VecStr(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.3g, %.3g, %.3g]", std::abs(v.x()) < 5e-13 ? 0.0 : v.x(),
                std::abs(v.y()) < 5e-13 ? 0.0 : v.y(), std::abs(v.z()) < 5e-13 ? 0.0 : v.z());
  return buf;
}

// Rank-only mobility of a model (for checking suggestions): {mobility, redundant}, or
// {-1, -1} when the joints do not assemble.
std::pair<int, int> QuickMobility(const Model& model) {
  const ConstraintSystem joints(model, false);
  SystemState state(joints);
  SolveOptions opt;
  if (!AssembleMinNorm(joints, AllRows(joints), opt, &state).success) return {-1, -1};
  const RankInfo info = CalcRank(ScaledJacobian(joints, state));
  return {6 * model.num_bodies() - info.rank, joints.num_rows() - info.rank};
}

// Joint types that keep a joint's frame and remove fewer equations (its descriptor's
// relaxations, looked up once a suggestion is wanted).
std::vector<const JointDescriptor*> LooserTypes(const JointDescriptor* t) {
  std::vector<const JointDescriptor*> out;
  for (const std::string& name : t->relaxations)
    if (const JointDescriptor* d = FindJointType(name)) out.push_back(d);
  return out;
}

void Loosen(Joint* j, const JointDescriptor* t) {
  // Cross axes: body2's h becomes the second cross axis, ⟂ the first (the frames' f).
  if (t->frames == JointFrameRule::CrossAxes) j->frame2.h = j->frame2.f;
  j->type = t;
}

// Finds one or two joint replacements that remove every redundant equation while
// keeping the mobility, and verifies each by recomputing the rank.
std::string SuggestRemoval(const Model& model, const MobilityReport& rep) {
  std::set<int> candidates;
  for (const auto& e : rep.redundant_equations)
    for (size_t j = 0; j < model.joints.size(); ++j) {
      const std::string& name = model.joints[j].name;
      if (e.description.find("`" + name + "`") != std::string::npos ||
          std::find(e.fixed_by.begin(), e.fixed_by.end(), name) != e.fixed_by.end())
        candidates.insert(static_cast<int>(j));
    }
  auto describe = [&](int j, const JointDescriptor* t) {
    return "joint `" + model.joints[j].name + "` (" + model.joints[j].type->name + ") by a " + t->name + " joint";
  };
  const int r = rep.redundant;
  for (int j : candidates)
    for (const JointDescriptor* t : LooserTypes(model.joints[j].type)) {
      if (model.joints[j].type->Rows() - t->Rows() != r) continue;
      Model m = model;
      Loosen(&m.joints[j], t);
      if (QuickMobility(m) == std::pair<int, int>{rep.mobility, 0})
        return "replace " + describe(j, t) + ": redundant 0, mobility still " + std::to_string(rep.mobility) +
               " (verified)";
    }
  for (int j1 : candidates)
    for (int j2 : candidates) {
      if (j2 <= j1) continue;
      for (const JointDescriptor* t1 : LooserTypes(model.joints[j1].type))
        for (const JointDescriptor* t2 : LooserTypes(model.joints[j2].type)) {
          const int removed = model.joints[j1].type->Rows() - t1->Rows() + model.joints[j2].type->Rows() - t2->Rows();
          if (removed != r) continue;
          Model m = model;
          Loosen(&m.joints[j1], t1);
          Loosen(&m.joints[j2], t2);
          if (QuickMobility(m) == std::pair<int, int>{rep.mobility, 0})
            return "replace " + describe(j1, t1) + " and " + describe(j2, t2) + ": redundant 0, mobility still " +
                   std::to_string(rep.mobility) + " (verified)";
        }
    }
  return "";
}

// A different pose along the free motion when the design pose is an unlucky
// (singular) one: the largest rank seen is the generic one.
void SeekGenericRank(const Model& model, const ConstraintSystem& joints, const SolveOptions& opt,
                     SystemState* state_ptr, RankInfo* info_ptr) {
  SystemState& state = *state_ptr;
  RankInfo& info = *info_ptr;
  const int n = model.num_bodies();
  // Guard against an unlucky (singular) design pose: move along the free motion
  // and take the largest rank seen.
  if (info.null_basis.cols() == 0) return;
  {
    std::mt19937 rng(12345);
    std::normal_distribution<double> nd;
    const double L = model.characteristic_length;
    const int trials = 6 * n <= 300 ? 2 : 1;  // each trial is a dense re-assembly
    for (int trial = 0; trial < trials; ++trial) {
      SystemState moved = state;
      Eigen::VectorXd c(info.null_basis.cols());
      for (int k = 0; k < c.size(); ++k) c[k] = nd(rng);
      Eigen::VectorXd dq = info.null_basis * c.normalized() * 0.05;
      for (int b = 0; b < n; ++b) dq.segment<3>(6 * b) *= L;
      ApplyStep(dq, &moved);
      if (!AssembleMinNorm(joints, AllRows(joints), opt, &moved).success) continue;
      RankInfo other = CalcRank(ScaledJacobian(joints, moved));
      if (other.rank > info.rank) {
        info = other;
        state = moved;
      }
    }
  }
}

// The couplers in the combinations that make driver rows dependent (§3.11, §6.4).
void NameConflictingCouplers(const ConstraintSystem& full, const SparseRowRank& fr, MobilityReport* rep) {
  std::set<std::string> names;
  for (int row : fr.dependent()) {
    if (row < full.num_joint_rows()) continue;
    const Eigen::VectorXd coef = fr.DependentCombination(row);
    const double cmax = coef.cwiseAbs().maxCoeff();
    for (int k = 0; k < coef.size(); ++k)
      if (cmax > 0 && std::abs(coef[k]) > 1e-6 * cmax && full.entries()[full.Locate(k).first].from_coupler)
        names.insert(full.SourceName(k));
  }
  rep->conflicting_couplers.assign(names.begin(), names.end());
}

// Rank of joints + drivers together at the same pose: freedoms left, conflicting drivers.
Eigen::MatrixXd DrivingRank(const Model& model, const ConstraintSystem& full, const SystemState& state, int joint_rank,
                            MobilityReport* rep_ptr) {
  MobilityReport& rep = *rep_ptr;
  const int n = model.num_bodies();
  SystemState fstate(full);
  fstate.bodies = state.bodies;
  fstate.angle_ref.assign(full.num_angle_slots(), 0.0);
  const Eigen::MatrixXd Jf = ScaledJacobian(full, fstate);
  const RankInfo finfo = CalcRank(Jf);
  rep.dof_after_drivers = 6 * n - finfo.rank;
  std::vector<int> fdep;
  if (finfo.rank < full.num_rows()) IndependentRows(Jf, 1e-7, &fdep);
  std::set<std::string> conflicting;
  for (int row : fdep)
    if (row >= full.num_joint_rows()) conflicting.insert(full.SourceName(row));
  rep.conflicting_drivers.assign(conflicting.begin(), conflicting.end());
  rep.driver_rank_deficit = static_cast<int>(model.drivers.size()) - (finfo.rank - joint_rank);
  if (!conflicting.empty() && !model.couplers.empty()) NameConflictingCouplers(full, SparseRowRank(Jf.sparseView()), &rep);
  return Jf;
}

// The rows a rigid motion of `group` must not violate: the joints and drivers
// touching the group, and the output points on the group's bodies. T (6·|g| × 6,
// block k for body g[k]) maps the group twist to the group's part of q̇; the rest
// of q̇ is zero. outputs_on[b]: the indices of the outputs with a point on body b.
Eigen::MatrixXd GroupConstraints(const Model& model, const std::vector<int>& g, const SystemState& state,
                                 const Eigen::SparseMatrix<double>& Jf,
                                 const std::vector<std::vector<size_t>>& outputs_on, Eigen::MatrixXd* T_out) {
  const double L = model.characteristic_length;
  Eigen::MatrixXd& T = *T_out;
  // T maps a group twist (ω global, v at the global origin; scaled by L) to q̇ (scaled).
  T = Eigen::MatrixXd::Zero(6 * static_cast<int>(g.size()), 6);
  for (size_t k = 0; k < g.size(); ++k) {
    const Vec3 r = state.bodies[g[k]].r[0];
    const Mat3& A = state.bodies[g[k]].A;
    T.block(6 * k, 0, 3, 3) = -Tilde(r) / L;  // ṙ = v + ω × r
    T.block(6 * k, 3, 3, 3) = Mat3::Identity();
    T.block(6 * k + 3, 0, 3, 3) = A.transpose();
  }
  // Only rows with an entry in the group's columns can be violated; Jf is
  // column-major, so S = Jf(:, group) · T is gathered column by column.
  std::vector<Eigen::RowVectorXd> rows;
  std::unordered_map<int, size_t> slot;  // row of Jf → index in rows
  for (size_t k = 0; k < g.size(); ++k)
    for (int c = 0; c < 6; ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(Jf, 6 * g[k] + c); it; ++it) {
        auto [pos, added] = slot.emplace(static_cast<int>(it.row()), rows.size());
        if (added) rows.push_back(Eigen::RowVectorXd::Zero(6));
        rows[pos->second] += it.value() * T.row(6 * static_cast<int>(k) + c);
      }
  // Output points on the group's bodies must not move (in the file's output order).
  std::vector<size_t> touching;
  for (int b : g) touching.insert(touching.end(), outputs_on[b].begin(), outputs_on[b].end());
  std::sort(touching.begin(), touching.end());
  touching.erase(std::unique(touching.begin(), touching.end()), touching.end());
  for (size_t oi : touching) {
    const Output& o = model.outputs[oi];
    for (BodyIndex ob : {o.body1, o.body2})
      if (ob != kGround && std::find(g.begin(), g.end(), ob) != g.end()) {
        const Vec3 s = ob == o.body1 ? o.point1 : o.point2;
        const Vec3 P = state.bodies[ob].r[0] + state.bodies[ob].A * s;
        Eigen::MatrixXd Vp(3, 6);
        Vp.leftCols(3) = -Tilde(P) / L;
        Vp.rightCols(3) = Mat3::Identity();
        for (int k = 0; k < 3; ++k) rows.push_back(Vp.row(k));
      }
  }
  Eigen::MatrixXd S(rows.size(), 6);
  for (size_t k = 0; k < rows.size(); ++k) S.row(k) = rows[k];
  return S;
}

using Block6 = Eigen::Matrix<double, 6, 1>;
// A direction of q̇ that moves only a few bodies: (body, its 6 entries), by body.
using SparseMotion = std::vector<std::pair<int, Block6>>;

double Norm(const SparseMotion& a) {
  double sum = 0;
  for (const auto& block : a) sum += block.second.squaredNorm();
  return std::sqrt(sum);
}

double Dot(const SparseMotion& a, const SparseMotion& b) {
  double sum = 0;
  for (size_t i = 0, k = 0; i < a.size() && k < b.size();) {
    if (a[i].first < b[k].first) ++i;
    else if (b[k].first < a[i].first) ++k;
    else sum += a[i++].second.dot(b[k++].second);
  }
  return sum;
}

// The idle motions accepted so far (as found, each on its group's bodies) and the
// Cholesky factor R of their Gram matrix G = MᵀM = RᵀR. A candidate m's part
// outside their span has the squared norm |m|² − |y|² with Rᵀy = Mᵀm, and Mᵀm
// is nonzero only for the accepted motions sharing a body with m: with R kept
// sparse (motions that share no body give G's zeros), the solve visits only the
// entries reachable from those, not a dense orthonormal basis filling in along
// a chain of jointed pairs.
class IdleBasis {
 public:
  explicit IdleBasis(int bodies) : moving_(bodies) {}

  // Joins `motion` to the accepted ones when its part outside their span is more
  // than 1e-6 of it.
  bool AddIfIndependent(const SparseMotion& motion) {
    std::map<size_t, double> y;  // Rᵀy = Mᵀm, solved in index order
    std::set<size_t> pending;
    std::map<size_t, double> b;
    for (const auto& block : motion)
      for (size_t k : moving_[block.first]) pending.insert(k);
    for (size_t k : pending) b[k] = Dot(motions_[k], motion);
    while (!pending.empty()) {
      const size_t j = *pending.begin();
      pending.erase(pending.begin());
      double v = b.count(j) ? b[j] : 0.0;
      for (const auto& [i, r] : columns_[j])
        if (const auto it = y.find(i); it != y.end()) v -= r * it->second;
      v /= diagonal_[j];
      y[j] = v;
      for (size_t later : rows_[j]) pending.insert(later);
    }
    double projected = 0;
    for (const auto& entry : y) projected += entry.second * entry.second;
    const double whole = Norm(motion);
    const double left = whole * whole - projected;
    const double residual = left > 0 ? std::sqrt(left) : 0.0;
    if (residual <= 1e-6 * whole) return false;
    const size_t index = motions_.size();
    std::vector<std::pair<size_t, double>> column;
    for (const auto& [i, v] : y)
      if (v != 0) {
        column.emplace_back(i, v);
        rows_[i].push_back(index);
      }
    for (const auto& block : motion) moving_[block.first].push_back(index);
    motions_.push_back(motion);
    columns_.push_back(std::move(column));
    diagonal_.push_back(residual);
    rows_.emplace_back();
    return true;
  }

 private:
  std::vector<SparseMotion> motions_;
  std::vector<std::vector<size_t>> moving_;                    // body → indices into motions_
  std::vector<std::vector<std::pair<size_t, double>>> columns_;  // R above the diagonal, by column
  std::vector<std::vector<size_t>> rows_;                      // R's nonzero columns, by row
  std::vector<double> diagonal_;
};

IdleFreedom DescribeIdle(const Model& model, const std::vector<int>& g, const Vec3& w) {
  IdleFreedom f;
  f.axis = w.norm() > 0 ? Vec3(w.normalized()) : Vec3::Zero();
  for (int b : g) f.body += (f.body.empty() ? "" : "+") + model.bodies[b].name;
  f.description =
      (g.size() == 1 ? "body `" + f.body + "`" : "bodies `" + f.body + "` together") +
      (w.norm() > 0
           ? (g.size() == 1 ? " spins about its own axis " : " spin about their common axis ") + VecStr(f.axis)
           : " slide") +
      " without moving anything else; model " +
      (g.size() == 1 ? "the link as a `distance` joint instead of a body" : "the leg with fewer bodies or lock the spin") +
      " if nothing but its length matters";
  return f;
}

// Idle freedoms: a body, or two bodies joined by a joint, moving together as one
// rigid group while everything else is still, no driver coordinate and no output
// point moves. Each group's work touches only its bodies' columns and the basis
// motions sharing a body with it, so the pass is linear in the bodies and joints.
void FindIdleFreedoms(const Model& model, const SystemState& state, const Eigen::SparseMatrix<double>& Jf,
                      MobilityReport* rep_ptr) {
  MobilityReport& rep = *rep_ptr;
  const int n = model.num_bodies();
  std::vector<std::vector<int>> groups;
  for (int b = 0; b < n; ++b) groups.push_back({b});
  for (const auto& jt : model.joints)
    if (jt.body1 != kGround && jt.body2 != kGround)
      groups.push_back({std::min(jt.body1, jt.body2), std::max(jt.body1, jt.body2)});
  std::sort(groups.begin(), groups.end());
  groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
  std::vector<std::vector<size_t>> outputs_on(n);
  for (size_t oi = 0; oi < model.outputs.size(); ++oi) {
    const Output& o = model.outputs[oi];
    if (o.kind == OutputKind::JointCoordinate) continue;
    for (BodyIndex ob : {o.body1, o.body2})
      if (ob != kGround) outputs_on[ob].push_back(oi);
  }
  IdleBasis idle(n);
  for (const auto& g : groups) {
    Eigen::MatrixXd T;
    const Eigen::MatrixXd S = GroupConstraints(model, g, state, Jf, outputs_on, &T);
    const RankInfo gi = CalcRank(S);
    for (int c = 0; c < gi.null_basis.cols(); ++c) {
      const Eigen::VectorXd local = T * gi.null_basis.col(c);
      SparseMotion motion;
      for (size_t k = 0; k < g.size(); ++k) motion.emplace_back(g[k], local.segment<6>(6 * k));
      // New direction only if independent of the idle motions found so far.
      if (!idle.AddIfIndependent(motion)) continue;
      rep.idle.push_back(DescribeIdle(model, g, gi.null_basis.col(c).head<3>()));
    }
  }
}

// full / under (naming the freedoms left by the bodies they move most) / over.
void ClassifyDriving(const Model& model, const std::function<Eigen::MatrixXd()>& null_basis_of_full,
                     MobilityReport* rep_ptr) {
  MobilityReport& rep = *rep_ptr;
  const int n = model.num_bodies();
  const int idle = static_cast<int>(rep.idle.size());
  rep.driving_status = JudgeDriving(static_cast<int>(rep.conflicting_drivers.size()), rep.dof_after_drivers);
  if (rep.driving_status == DrivingStatus::Under) {
    // Name the remaining freedoms by the bodies they move most (the null basis
    // only when some freedom is not idle: a large model of idle spins skips it).
    const Eigen::MatrixXd null_basis = rep.dof_after_drivers > idle ? null_basis_of_full() : Eigen::MatrixXd();
    for (int c = 0;
         c < null_basis.cols() && static_cast<int>(rep.remaining_freedoms.size()) < rep.dof_after_drivers - idle;
         ++c) {
      const Eigen::VectorXd v = null_basis.col(c);
      std::vector<std::pair<double, int>> mv;
      for (int b = 0; b < n; ++b) mv.emplace_back(v.segment<6>(6 * b).norm(), b);
      std::sort(mv.rbegin(), mv.rend());
      std::string s = "a freedom moving ";
      int listed = 0;
      for (const auto& [mag, b] : mv)
        if (mag > 1e-6 && listed < 4) s += (listed++ ? ", `" : "`") + model.bodies[b].name + "`";
      rep.remaining_freedoms.push_back(s + " is not driven");
    }
    // The idle spins are freedoms too: a run would have to fix them.
    for (const auto& f : rep.idle) rep.remaining_freedoms.push_back("idle, not driven: " + f.description);
  }
}


// The freedoms of the bodies left dangling in `model`: trees hanging off the rest
// by one joint each (peeled leaf by leaf) and bodies with no joint. A tree's joint
// equations are independent, so it adds 6 − (equations removed) per joint to the
// mobility whatever the rest does. `*all_dangling` is set when nothing else is left.
int DanglingFreedoms(const Model& model, bool* all_dangling) {
  const int n = model.num_bodies();
  std::vector<std::vector<size_t>> joints_of(n);
  for (size_t j = 0; j < model.joints.size(); ++j)
    for (BodyIndex b : {model.joints[j].body1, model.joints[j].body2})
      if (b != kGround) joints_of[b].push_back(j);
  std::vector<int> degree(n);
  std::vector<char> joint_gone(model.joints.size(), 0), body_gone(n, 0);
  std::vector<int> leaves;
  for (int b = 0; b < n; ++b)
    if ((degree[b] = static_cast<int>(joints_of[b].size())) <= 1) leaves.push_back(b);
  int freedoms = 0, left = n;
  while (!leaves.empty()) {
    const int b = leaves.back();
    leaves.pop_back();
    if (body_gone[b] || degree[b] > 1) continue;
    body_gone[b] = 1, --left;
    if (degree[b] == 0) freedoms += 6;
    for (size_t j : joints_of[b]) {
      if (joint_gone[j]) continue;
      joint_gone[j] = 1;
      freedoms += 6 - model.joints[j].type->Rows();
      const BodyIndex other = model.joints[j].body1 == b ? model.joints[j].body2 : model.joints[j].body1;
      if (other != kGround && --degree[other] <= 1) leaves.push_back(other);
    }
  }
  *all_dangling = left == 0;
  return freedoms;
}

// Mobility 0 from the joints: name the joints whose removal alone frees the
// mechanism (dense path; up to 60 joints, one rank each). Removing a joint always
// lets what hangs on it dangle (the crank of a Watt II whose second loop is locked);
// that does not count: a joint is named when, without it, the loops that remain
// move (mobility beyond the dangling trees' freedoms) or no loop remains.
void FindLockingJoints(const Model& model, MobilityReport* rep) {
  if (model.joints.size() > 60) return;
  for (size_t j = 0; j < model.joints.size(); ++j) {
    Model without = model;
    without.joints.erase(without.joints.begin() + static_cast<long>(j));
    const int mobility = QuickMobility(without).first;
    bool no_loop_left = false;
    const int dangling = DanglingFreedoms(without, &no_loop_left);
    if (mobility > 0 && (no_loop_left || mobility > dangling)) rep->locking_joints.push_back(model.joints[j].name);
  }
}

// Directions of a null basis in words: the bodies each moves most.
std::vector<std::string> DescribeMotions(const Model& model, const Eigen::MatrixXd& basis, int count) {
  std::vector<std::string> out;
  for (int c = 0; c < basis.cols() && static_cast<int>(out.size()) < count; ++c) {
    std::vector<std::pair<double, int>> mv;
    for (int b = 0; b < model.num_bodies(); ++b) mv.emplace_back(basis.col(c).segment<6>(6 * b).norm(), b);
    std::sort(mv.rbegin(), mv.rend());
    std::string s = "a small motion of ";
    int listed = 0;
    for (const auto& [mag, b] : mv)
      if (mag > 1e-6 && listed < 4) s += (listed++ ? ", `" : "`") + model.bodies[b].name + "`";
    const int b0 = mv.front().second;
    Vec3 w = basis.col(c).segment<3>(6 * b0 + 3);
    for (int k = 0; k < 3; ++k)
      if (std::abs(w[k]) < 1e-9 * w.norm()) w[k] = 0;  // round-off, not a direction
    if (w.norm() > 0.5 * basis.col(c).segment<6>(6 * b0).norm())
      s += " (turning about " + VecStr(w.normalized()) + " in its body axes)";
    out.push_back(s + " is not controlled by the drivers here");
  }
  return out;
}

// A design pose that is itself singular: the joints and drivers together lose rank
// there but not at nearby poses along the joints' free motion (three random tries,
// the best kept). Returns the nearby pose in *generic (joints assembled), or false.
bool FindRegularDrivenPose(const Model& model, const ConstraintSystem& joints, const ConstraintSystem& full,
                           const SystemState& design, const RankInfo& joint_info, int design_full_rank,
                           SystemState* generic) {
  if (joint_info.null_basis.cols() == 0) return false;
  std::mt19937 rng(4242);
  std::normal_distribution<double> nd;
  const double L = model.characteristic_length;
  int best = design_full_rank;
  for (int trial = 0; trial < 3; ++trial) {
    SystemState moved = design;
    Eigen::VectorXd c(joint_info.null_basis.cols());
    for (int k = 0; k < c.size(); ++k) c[k] = nd(rng);
    Eigen::VectorXd dq = joint_info.null_basis * c.normalized() * 0.05;
    for (int b = 0; b < model.num_bodies(); ++b) dq.segment<3>(6 * b) *= L;
    ApplyStep(dq, &moved);
    SolveOptions opt;
    opt.max_iterations = 100;
    if (!AssembleMinNorm(joints, AllRows(joints), opt, &moved).success) continue;
    SystemState fstate(full);
    fstate.bodies = moved.bodies;
    fstate.angle_ref.assign(full.num_angle_slots(), 0.0);
    const int rank = CalcRank(ScaledJacobian(full, fstate)).rank;
    if (rank > best) {
      best = rank;
      *generic = moved;
    }
  }
  return best > design_full_rank;
}

// Redundant rows from the sparse QR, each with the joints whose rows combine to it
// (named for the first kMaxNamedRedundant; the count is always exact).
void NameRedundantEquationsSparse(const ConstraintSystem& joints, const SparseRowRank& jr, MobilityReport* rep) {
  for (int row : jr.dependent()) {
    RedundantEquation eq;
    eq.row = row;
    eq.description = joints.DescribeRow(row);
    if (static_cast<int>(rep->redundant_equations.size()) < kMaxNamedRedundant) {
      const Eigen::VectorXd coef = jr.DependentCombination(row);
      const double cmax = coef.cwiseAbs().maxCoeff();
      std::set<std::string> names;
      for (int k = 0; k < coef.size(); ++k)
        if (cmax > 0 && std::abs(coef[k]) > 1e-6 * cmax && joints.SourceName(k) != joints.SourceName(row)) {
          names.insert(joints.SourceName(k));
          eq.couplers_in_fixed_by |= joints.entries()[joints.Locate(k).first].from_coupler;
        }
      names.erase(joints.SourceName(row));
      eq.fixed_by.assign(names.begin(), names.end());
    }
    rep->redundant_equations.push_back(eq);
  }
}

void SetOverconstrainedVerdict(MobilityReport* rep) {
  rep->verdict_kind = MobilityVerdict::Overconstrained;
  rep->verdict = "overconstrained: " + std::to_string(rep->redundant) + " redundant equation" +
                 (rep->redundant == 1 ? "" : "s") + " — the Grübler count undercounts the mobility";
}

// The assembly's outcome in the report; false when the joints do not assemble.
bool RecordAssembly(const SolveSummary& assembled, int equations, MobilityReport* rep) {
  rep->assembly_residual = assembled.residual;
  rep->equations = equations;
  if (!assembled.success) {
    rep->assembly_message = "the joints cannot be assembled near the design pose (scaled residual " +
                            std::to_string(assembled.residual) + "): " + assembled.message;
    return false;
  }
  rep->assembled = true;
  rep->assembly_message = "assembled";
  return true;
}

// Among the locking joints with an axis (revolute, cylindrical, screw): the one
// whose axis is off the direction all the others share (a mistyped axis, as in a
// planar loop with one axis turned), in words; empty when there is no such one.
std::string OddAxisOut(const Model& model, const std::vector<std::string>& locking) {
  std::vector<std::pair<std::string, Vec3>> axes;
  for (const auto& jt : model.joints) {
    const bool has_axis = jt.type->turns;
    if (!has_axis || std::find(locking.begin(), locking.end(), jt.name) == locking.end()) continue;
    const Mat3 A = jt.body1 == kGround ? Mat3::Identity() : CalcA(model.bodies[jt.body1].euler);
    axes.emplace_back(jt.name, (A * jt.frame1.h).normalized());
  }
  if (axes.size() < 3) return "";
  auto parallel = [](const Vec3& a, const Vec3& b) { return a.cross(b).norm() < 1e-9; };
  for (size_t odd = 0; odd < axes.size(); ++odd) {
    const Vec3& common = axes[odd == 0 ? 1 : 0].second;
    bool others_share = true;
    for (size_t k = 0; k < axes.size() && others_share; ++k)
      if (k != odd) others_share = parallel(axes[k].second, common);
    if (!others_share || parallel(axes[odd].second, common)) continue;
    char angle[32];
    std::snprintf(angle, sizeof angle, "%.4g", std::acos(std::min(1.0, std::abs(axes[odd].second.dot(common)))) * 180 / M_PI);
    std::string s = "; the axis of `" + axes[odd].first + "` is " + angle + "° off the axis ";
    for (size_t k = 0, listed = 0; k < axes.size(); ++k)
      if (k != odd) s += (listed++ ? ", `" : "`") + axes[k].first + "`";
    return s + " share: is it mistyped?";
  }
  return "";
}

// Mobility 0 from the joints: the verdict names the joints that lock it.
void SetLockedVerdict(const Model& model, MobilityReport* rep) {
  rep->locked = true;
  FindLockingJoints(model, rep);
  rep->verdict = "locked by the joints: they allow no motion (mobility 0) before any driver";
  if (!rep->locking_joints.empty()) {
    const bool one = rep->locking_joints.size() == 1;
    rep->verdict += one ? "; removing " : "; removing any one of ";
    for (size_t k = 0; k < rep->locking_joints.size(); ++k)
      rep->verdict += (k ? ", `" : "`") + rep->locking_joints[k] + "`";
    rep->verdict += one ? " would free it — check its axis and position"
                        : " would free it — check their axes and positions" + OddAxisOut(model, rep->locking_joints);
  }
  if (rep->redundant > 0) rep->verdict_kind = MobilityVerdict::Overconstrained;
}

}  // namespace

// Models too large for the dense SVD (more than 200 bodies): the same analysis with
// the sparse rank-revealing QR (kinematics/sparse_rank.hpp). The margin reported is
// the QR's (smallest kept pivot |R_kk|, largest column left over), not singular
// values; the search for a more generic pose, the joint-change suggestions, the
// singular-design-pose diagnosis and naming the locking joints are left to the dense
// path (the "locked by the joints" verdict itself is the same).
MobilityReport CalcMobilitySparse(const Model& model) {
  MobilityReport rep;
  rep.rank_method = "sparse-qr";
  const int n = model.num_bodies();
  const ConstraintSystem joints(model, false);
  const ConstraintSystem full(model, true);
  SystemState state(joints);
  SolveOptions opt;
  opt.max_iterations = 100;
  const SolveSummary assembled = AssembleMinNormSparse(joints, opt, &state);
  if (!RecordAssembly(assembled, joints.num_rows(), &rep)) return rep;
  const SparseRowRank jr(ScaledSparseJacobian(joints, state, AllRows(joints)));
  rep.rank = jr.rank();
  rep.sigma_min_kept = jr.smallest_pivot();
  rep.sigma_max_dropped = jr.largest_dead();
  rep.mobility = 6 * n - jr.rank();
  rep.redundant = joints.num_rows() - jr.rank();
  NameRedundantEquationsSparse(joints, jr, &rep);

  SystemState fstate(full);
  fstate.bodies = state.bodies;
  fstate.angle_ref.assign(full.num_angle_slots(), 0.0);
  const Eigen::SparseMatrix<double> Jf = ScaledSparseJacobian(full, fstate, AllRows(full));
  const SparseRowRank fr(Jf);
  rep.dof_after_drivers = 6 * n - fr.rank();
  std::set<std::string> conflicting;
  for (int row : fr.dependent())
    if (row >= full.num_joint_rows()) conflicting.insert(full.SourceName(row));
  rep.conflicting_drivers.assign(conflicting.begin(), conflicting.end());
  rep.driver_rank_deficit = static_cast<int>(model.drivers.size()) - (fr.rank() - jr.rank());
  if (!conflicting.empty() && !model.couplers.empty()) NameConflictingCouplers(full, fr, &rep);
  FindIdleFreedoms(model, state, Jf, &rep);
  ClassifyDriving(model, [&] { return fr.NullSpace(kMaxNamedFreedoms); }, &rep);
  if (rep.redundant > 0) SetOverconstrainedVerdict(&rep);
  if (rep.mobility == 0 && n > 0) SetLockedVerdict(model, &rep);  // names no joints past 60
  return rep;
}

MobilityReport CalcMobility(const Model& model) {
  if (6 * model.num_bodies() > kMaxDenseColumns) return CalcMobilitySparse(model);
  MobilityReport rep;
  const int n = model.num_bodies();
  const ConstraintSystem joints(model, false);
  const ConstraintSystem full(model, true);
  SystemState state(joints);
  SolveOptions opt;
  opt.max_iterations = 100;
  const SolveSummary assembled = AssembleMinNorm(joints, AllRows(joints), opt, &state);
  if (!RecordAssembly(assembled, joints.num_rows(), &rep)) return rep;
  RankInfo info = CalcRank(ScaledJacobian(joints, state));
  SeekGenericRank(model, joints, opt, &state, &info);
  rep.rank = info.rank;
  rep.sigma_min_kept = info.sigma_min_kept;
  rep.sigma_max_dropped = info.sigma_max_dropped;
  rep.mobility = 6 * n - info.rank;
  rep.redundant = joints.num_rows() - info.rank;
  // The redundant rows by the same greedy file-order rule as the large-model path:
  // one sparse QR names every row and its combination (a dense pass is O(m²n)).
  if (rep.redundant > 0) NameRedundantEquationsSparse(joints, SparseRowRank(ScaledJacobian(joints, state).sparseView()), &rep);
  Eigen::MatrixXd Jf = DrivingRank(model, full, state, info.rank, &rep);
  if (rep.dof_after_drivers > std::max(0, rep.mobility - static_cast<int>(model.drivers.size())) ||
      !rep.conflicting_drivers.empty()) {
    // More freedoms left (or drivers in conflict) than the counts imply: is it the pose?
    SystemState generic(joints);
    if (FindRegularDrivenPose(model, joints, full, state, info, 6 * n - rep.dof_after_drivers, &generic)) {
      const int design_rank = 6 * n - rep.dof_after_drivers;
      const RankInfo design_full = CalcRank(Jf);
      rep.conflicting_drivers.clear();
      rep.conflicting_couplers.clear();
      rep.remaining_freedoms.clear();
      Jf = DrivingRank(model, full, generic, info.rank, &rep);
      rep.singular_lost = 6 * n - rep.dof_after_drivers - design_rank;
      rep.singular_directions = DescribeMotions(model, design_full.null_basis, rep.singular_lost);
      state = generic;
    }
  }
  FindIdleFreedoms(model, state, Jf.sparseView(), &rep);
  ClassifyDriving(model, [&] { return CalcRank(Jf).null_basis; }, &rep);
  if (rep.mobility == 0 && n > 0) {
    // The joints alone lock it: say so before any talk of conflicting drivers.
    SetLockedVerdict(model, &rep);
  } else if (rep.redundant > 0) {
    const std::string suggestion = SuggestRemoval(model, rep);
    if (!suggestion.empty()) rep.suggestions.push_back(suggestion);
    SetOverconstrainedVerdict(&rep);
  }
  return rep;
}

DrivingStatus JudgeDriving(int conflicting_drivers, int freedoms_left) {
  if (conflicting_drivers > 0) return DrivingStatus::Over;
  return freedoms_left > 0 ? DrivingStatus::Under : DrivingStatus::Full;
}

const char* DrivingStatusName(DrivingStatus status) {
  switch (status) {
    case DrivingStatus::Full:
      return "full";
    case DrivingStatus::Under:
      return "under";
    case DrivingStatus::Over:
      return "over";
  }
  return "full";
}

}  // namespace mechkin
