// Progress of a long command on a terminal's stderr (`check` over a library, `sweep`):
// "\r 120/10000 files, 85.0 files/s, 1 min 56 s left", at most five updates a second;
// off (nothing written) unless enabled — the callers enable it only when stderr is a
// terminal and their results do not go to that terminal.
#pragma once

#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace mechkin {

class ProgressLine {
 public:
  /// `unit`: what is counted, plural ("files", "variants").
  ProgressLine(bool enabled, size_t total, std::string unit, std::ostream& err);
  void Update(size_t done);
  /// Clears the progress line (before a summary).
  void Finish();

 private:
  bool enabled_;
  size_t total_;
  std::string unit_;
  std::ostream& err_;
  std::chrono::steady_clock::time_point start_, shown_;
  bool drawn_ = false;
};

}  // namespace mechkin
