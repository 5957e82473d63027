#include "cli/commands/progress.hpp"

#include <cmath>
#include <iomanip>
#include <utility>

namespace mechkin {

ProgressLine::ProgressLine(bool enabled, size_t total, std::string unit, std::ostream& err)
    : enabled_(enabled), total_(total), unit_(std::move(unit)), err_(err),
      start_(std::chrono::steady_clock::now()), shown_(start_) {}

void ProgressLine::Update(size_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - shown_ < std::chrono::milliseconds(200) && done < total_) return;
  shown_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  const double rate = seconds > 0 ? done / seconds : 0;
  err_ << "\r\033[K" << done << "/" << total_ << " " << unit_ << ", " << std::fixed << std::setprecision(1) << rate
       << " " << unit_ << "/s";
  if (rate > 0 && done < total_) {
    const long left = std::lround((total_ - done) / rate);
    err_ << ", ";
    if (left >= 60) err_ << left / 60 << " min ";
    err_ << left % 60 << " s left";
  }
  err_.unsetf(std::ios::floatfield);
  err_ << std::setprecision(6) << std::flush;
  drawn_ = true;
}

void ProgressLine::Finish() {
  if (drawn_) err_ << "\r\033[K" << std::flush;
  drawn_ = false;
}

}  // namespace mechkin
