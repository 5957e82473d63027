// `check --clearance` and `expect: {"min_clearance"}` (issue 28, docs/format.md
// "Clearance"): the analysis span swept, each pair's smallest clearance and where
// (time, driver values, closest points), and the tightest pair.
#pragma once

#include <string>
#include <vector>

#include "analysis/contact_watch.hpp"
#include "analysis/kinematic_analysis.hpp"

namespace mechkin {

struct ClearanceMinimum {
  ClearancePair pair;
  double clearance = 0;  // m: the smallest over the rows (0 at a contact located between rows)
  double t = 0;          // s, where
  std::vector<double> driver_values;  // SI, there
  Vec3 point1 = Vec3::Zero(), point2 = Vec3::Zero();  // closest points there (global, m)
};

struct ClearanceSweep {
  std::vector<ClearanceMinimum> pairs;  // the clearance outputs' pairs, or every unjointed shaped pair
  int tightest = -1;                    // index into pairs (−1: none)
  int rows = 0;
  bool complete = false;
  std::string note;                     // why the sweep ended early
};

/// Sweeps model.analysis (positions only, first contacts located). Never throws for
/// a mechanism that cannot move: the sweep says where it stopped.
ClearanceSweep SweepClearance(const Model& model, const AnalysisOptions& options);
/// "`coupler` and `ground`: 1.25 mm at t = 0.3 s (driver `crank` = 108 deg)".
std::string ClearanceWhere(const Model& model, const ClearanceMinimum& m);

}  // namespace mechkin
