// First contacts along the run (issue 28, docs/format.md "Clearance"): for each
// clearance output's pair, a step whose row finds the shapes touching, or one whose
// rows are both clear but between which the bodies may have passed through each
// other, is searched on the exact motion (tight position solves at trial times, as
// joint limits are located) and the first contact bisected to 1e-9 s (§13).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/clearance.hpp"
#include "kinematics/workspace.hpp"

namespace mechkin {

struct AnalysisReport;  // analysis/kinematic_analysis.hpp

struct ContactHit {
  double t = 0;                 // the first contact (s); at the start: the first row's time
  int output = -1;              // the clearance output of the pair
  BodyIndex body1 = kGround, body2 = kGround;
  Vec3 point = Vec3::Zero();    // global (m): between the closest points at t
  double clearance = 0;         // at the start: the (negative) clearance there; else 0
  bool at_start = false;        // already touching on the first row (not located)
  std::vector<double> driver_values;  // SI, at t
};

class ContactWatch {
 public:
  /// Watches the clearance outputs whose bodies `needed_bodies` solves (empty: all).
  ContactWatch(const Model& model, const std::vector<int>& needed_bodies);
  bool empty() const { return eval_->size() == 0; }
  /// The first row: the pairs already in contact there.
  std::vector<ContactHit> Start(const SystemState& s);
  /// The contacts that begin between the accepted pose `prev` and the solved `s`,
  /// located, earliest first; the watch then follows `s`.
  std::vector<ContactHit> Check(KinematicsWorkspace& ws, const SystemState& prev, const SystemState& s,
                                int predictor_order);

 private:
  struct Probe {
    SystemState state;
    double distance;
  };
  bool MayTouchBetween(int pair, const SystemState& a, double da, const SystemState& b, double db) const;
  std::optional<std::pair<Probe, Probe>> Search(KinematicsWorkspace& ws, const SystemState& prev, int pair,
                                                const Probe& a, const Probe& b, int* budget) const;
  ContactHit Locate(KinematicsWorkspace& ws, const SystemState& prev, int pair, Probe a, Probe b) const;
  Probe Solve(KinematicsWorkspace& ws, const SystemState& prev, double t, int pair) const;

  const Model& model_;
  std::unique_ptr<ClearanceEvaluator> eval_;
  std::vector<double> distance_;  // per pair at the last accepted pose
  int predictor_order_ = 1;
};

/// "bodies `slider` and `ground` come into contact at t = … s (driver `x` = … mm) at [..] mm …".
std::string ContactMessage(const Model& model, const ContactHit& hit, int rows_done, bool stops);
/// The run's contact watch of a row: notes the contacts (and goes on) or, with
/// `stop`, stops at the first (rep->stop = Contact). True when the run stops.
bool WatchContacts(ContactWatch* watch, KinematicsWorkspace& ws, const SystemState& prev, const SystemState& s,
                   int step, int predictor_order, bool stop, AnalysisReport* rep);

}  // namespace mechkin
