// Range of motion of each driver (issue "Say what engineers measure"): from the
// design pose, each driver is moved alone (the others held at their design
// values) in both directions along the branch connected to the design, and the
// run's own limit location (a fold located to 1e-9 of the step, or a singular
// position where branches meet) ends the interval; a rotation that comes round
// a whole turn is a "full turn".
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "analysis/kinematic_analysis.hpp"

namespace mechkin {

struct RangeEnd {
  // "limit" (the branch folds: stroke end, toggle), "branch point" (a singular
  // position where branches cross), "joint limit" (a joint's "limits" reached),
  // "full turn", "open" (no end within the search span), "failed" (the solve
  // failed for another reason: see message)
  std::string kind;
  double value = std::numeric_limits<double>::quiet_NaN();  // the driver's value there (file units)
  std::string message;
};

struct DriverRange {
  std::string driver, unit;
  double design_value = 0;    // the driver's value at the design pose (file units)
  RangeEnd lower, upper;      // in the driver's values (joint drivers: 0 at the design)
  double max_condition = 0, value_at_max_condition = 0;  // along the interval
};

struct RangeOptions {
  std::string driver;     // empty: every driver
  int steps = 360;        // per direction: per turn for rotations, over the search span otherwise
  double span = 0;        // search span of non-rotation drivers (file units); 0: 4 × the mechanism's size
  double tolerance = 1e-10;
  InterruptPoll interrupted;  // polled between steps: true ends the report with the drivers done
};

struct RangeReport {
  bool ok = false;
  std::string message;
  std::vector<DriverRange> drivers;
  bool interrupted = false;  // stopped by RangeOptions::interrupted: `drivers` are those done before
};

RangeReport CalcRange(const Model& model, const RangeOptions& options);

}  // namespace mechkin
