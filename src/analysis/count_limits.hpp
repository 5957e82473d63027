// The counts the front ends accept beside a run request (range steps, Monte-Carlo
// and sweep samples), each with its single range and message, so the CLI option and
// the Python argument refuse a value in the same words (issue 24).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace mechkin {

struct CountLimit {
  const char* what;  // as the message names it
  long long low, high;
};

inline constexpr CountLimit kRangeSteps{"the range's steps per direction", 4, 10000000};
inline constexpr CountLimit kMonteCarloSamples{"the Monte-Carlo sample count", 0, 100000000};
inline constexpr CountLimit kSweepSamples{"the sweep's sample count", 1, 100000000};

/// "" when `value` is a whole number within the limit; otherwise the message
/// ("the Monte-Carlo sample count must be a whole number from 0 to 100000000, not 2e+08").
inline std::string CountProblem(const CountLimit& limit, double value) {
  if (std::isfinite(value) && value == std::floor(value) && value >= limit.low && value <= limit.high) return "";
  char shown[32];
  std::snprintf(shown, sizeof shown, "%.6g", value);
  return std::string(limit.what) + " must be a whole number from " + std::to_string(limit.low) + " to " +
         std::to_string(limit.high) + ", not " + shown;
}

}  // namespace mechkin
