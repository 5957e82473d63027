// Rank-based mobility at the assembled design configuration (constraints.md §6):
//   M = 6n − rank[Φ_r Φ_π'] (joints only), redundant = m − rank,
// with the rank from an SVD of the dimensionless Jacobian (rows divided by
// L^power, translation columns multiplied by L) and the threshold
//   σ_k kept  ⇔  σ_k > 1e-8 · σ_max.
// The margin (smallest kept and largest discarded singular value) is reported
// so a user can judge how robust the answer is. The rank is also evaluated at
// two further poses reached along the free motion; the largest rank seen (the
// generic one) is used.
#pragma once

#include <string>
#include <vector>

#include "model/model.hpp"

namespace mechkin {

constexpr double kRankThreshold = 1e-8;

enum class DrivingStatus { Full, Under, Over };
/// "full", "under", "over" (the words of the file's `expect.driven`).
const char* DrivingStatusName(DrivingStatus status);
/// The one rule for `check`'s `driven` and `run`'s refusal (constraints.md §6.4):
/// over when a driver conflicts, else under when any freedom is left after the
/// drivers — idle freedoms included, since a run solves 6n independent equations
/// and cannot leave a spin undetermined — else full.
DrivingStatus JudgeDriving(int conflicting_drivers, int freedoms_left);
enum class MobilityVerdict { Regular, Overconstrained };

struct RedundantEquation {
  int row;
  std::string description;          // "joint `J4` (revolute): rotation about its frame's f axis"
  std::vector<std::string> fixed_by;  // joints (and couplers, §3.11) whose equations already fix it
  bool couplers_in_fixed_by = false;
};

struct IdleFreedom {
  std::string body;
  Vec3 axis;  // global direction of the idle spin (unit)
  std::string description;
};

struct MobilityReport {
  bool assembled = false;
  std::string assembly_message;
  double assembly_residual = 0;
  int equations = 0;
  int rank = 0;
  int mobility = 0;
  int redundant = 0;
  double sigma_min_kept = 0, sigma_max_dropped = 0;
  /// How the rank was found: "svd" (dense, ≤ 200 bodies; the margin is in singular
  /// values) or "sparse-qr" (SuiteSparseQR; the margin is the smallest kept pivot
  /// |R_kk| and the largest column norm left over).
  std::string rank_method = "svd";
  std::vector<RedundantEquation> redundant_equations;
  std::vector<IdleFreedom> idle;
  // Driving
  int driver_rank_deficit = 0;
  int dof_after_drivers = 0;
  DrivingStatus driving_status = DrivingStatus::Full;
  std::vector<std::string> conflicting_drivers;
  /// Couplers (§3.11) whose equation, with the joints', contradicts a conflicting
  /// driver: the rows a conflicting driver's row is a combination of.
  std::vector<std::string> conflicting_couplers;
  std::vector<std::string> remaining_freedoms;
  MobilityVerdict verdict_kind = MobilityVerdict::Regular;
  std::string verdict;  // the verdict in words (empty when regular)
  std::vector<std::string> suggestions;
  /// Mobility 0 from the joints alone: the joints lock the mechanism before any
  /// driver (then "conflicting drivers" is a consequence, not the cause). The
  /// joints whose removal alone frees it are named.
  bool locked = false;
  std::vector<std::string> locking_joints;
  /// The design pose is a singular position of the driven mechanism: the drivers
  /// control `singular_lost` fewer directions there than at nearby poses of the
  /// joints' free motion. The driving analysis above is then that of a nearby
  /// regular pose; `singular_directions` describes the directions lost.
  int singular_lost = 0;
  std::vector<std::string> singular_directions;
};

/// The mobility analysis; models with more than 200 bodies take the sparse path.
MobilityReport CalcMobility(const Model& model);
/// The sparse path for any model (used by CalcMobility above 200 bodies; exposed so
/// tests can compare both paths on the same model).
MobilityReport CalcMobilitySparse(const Model& model);

}  // namespace mechkin
