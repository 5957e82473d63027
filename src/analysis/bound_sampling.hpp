// Sampled measured bounds for the rows the default does not measure whole
// (constraints.md §8, "Sampled"; issue "Loudly wrong exactly where it matters", item 2).
//
// The bounds from κ (error_bounds.hpp) assume a derivative's error grows by one κ over
// the pose's. On some mechanisms it grows by κ per order (the piston's regular rows,
// κ ≈ 5: the jerk's error was up to 30× its bound from κ), on others not at all (the
// bundled four-bar, whose jerk 2κ^k(e_0 + 8u) would overstate 1e4×). Only measuring
// tells which (row_error_estimate.hpp), and a measurement costs about two steps. So
// the default measures a sample of the rows:
//   - from row kFirstSample on: before it the running scale of each order, which a
//     measured relative bound is relative to, may be a small part of the motion's (a
//     motion from rest), and the bound that much too large;
//   - every kDenseInterval rows, or at twice the last interval (up to kSparseInterval)
//     after a sample whose measured bounds of every derivative order stay below
//     kQuietRatio of the smallest bound from κ since the sample before. The smallest,
//     not the sampled row's own: the one-step κ is noisy (4.6 to 9 on adjacent rows of
//     the piston, its bound from κ 8× apart at the jerk), and the rows where the bound
//     from κ falls short are the low ones;
//   - rows measured whole (near a singular position) count as samples, but never
//     lengthen the interval.
// What a row reports lies between two a priori bounds — the one from κ (errors that do
// not grow with the order) and the ceiling 2κ^k(e_0 + 8u) with the row's sharper κ
// (errors that grow by κ per order) — and the samples choose where: a sampled row its measured bound, a row between
// samples the larger of the last two samples' measured bounds (the error they measure is
// that of a smooth motion: the piston's jerk error grows smoothly, tenfold over a third
// of its stroke, while the bound from κ jumps with the row's κ). Never below the bound
// from κ; never above the ceiling.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mechkin {

class BoundSampler {
 public:
  static constexpr int kMaxOrder = 4;
  enum class Row { Sampled, MeasuredWhole };

  /// True on the rows (counted from 0, one call per row: a re-solved row restores the
  /// sampler as it was before the row's first call) due for a sample. A due row that
  /// takes none moves the next one on by the interval.
  bool Due() {
    const bool due = row_ == next_;
    if (due) next_ = row_ + interval_;
    ++row_;
    return due;
  }

  /// Learns from a measured row (after Due): `from_kappa` its bounds from κ, `measured`
  /// its measured ones, orders 0..order. A row measured whole (near a singular position)
  /// never lengthens the interval: its bounds from κ are those of that position, and the
  /// regular rows after it need a sample of their own soon.
  void Learn(const double* from_kappa, const double* measured, int order, Row row) {
    double worst = 0;
    for (int k = 0; k <= order; ++k) {
      const double least = std::min(from_kappa[k], least_from_kappa_[k]);
      least_from_kappa_[k] = std::numeric_limits<double>::infinity();
      // A NaN measurement, or a bound from κ of 0, counts as loud (not quiet).
      const double ratio = least > 0 ? measured[k] / least : std::numeric_limits<double>::quiet_NaN();
      if (k > 0) worst = std::isnan(ratio) ? std::numeric_limits<double>::infinity() : std::max(worst, ratio);
      carried_[k] = std::max(last_[k], measured[k]);
      last_[k] = measured[k];
    }
    const bool quiet = worst < kQuietRatio && row == Row::Sampled;
    interval_ = quiet ? std::min(2 * interval_, kSparseInterval) : kDenseInterval;
    next_ = std::max(kFirstSample, row_ - 1 + interval_);
  }

  /// A sampled row's report: its measured bounds between the bound from κ and the
  /// ceiling (`condition` the row's κ).
  static void ClampSampled(double condition, const double* from_kappa, double* measured, int order) {
    for (int k = 0; k <= order; ++k) measured[k] = ClampBetween(condition, from_kappa, k, measured[k]);
  }

  /// A row between samples: its bounds from κ raised to the carried measured ones,
  /// up to the ceiling.
  void RaiseUnsampled(double condition, double* bound, int order) {
    for (int k = order; k >= 0; --k) {  // from the top: the ceiling reads bound[0] from κ
      least_from_kappa_[k] = std::min(least_from_kappa_[k], bound[k]);
      bound[k] = ClampBetween(condition, bound, k, carried_[k]);
    }
  }

 private:
  static constexpr int kFirstSample = 16;
  static constexpr int kDenseInterval = 8;
  static constexpr int kSparseInterval = 256;
  // The measured bound carries safety factors of its own (2 on the pose, 4 on each
  // derivative, row_error_estimate.cpp): below half the bound from κ, that bound holds.
  static constexpr double kQuietRatio = 0.5;
  static constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2;

  // `value` brought between the bound from κ of order k and the ceiling 2κ^k(e_0 + 8u).
  static double ClampBetween(double condition, const double* from_kappa, int k, double value) {
    double ceiling = 2 * (from_kappa[0] + 8 * kUnitRoundoff);
    for (int j = 0; j < k; ++j) ceiling *= condition;
    return std::max(from_kappa[k], std::min(value, ceiling));
  }
  static std::array<double, kMaxOrder + 1> Infinities() {
    std::array<double, kMaxOrder + 1> a;
    a.fill(std::numeric_limits<double>::infinity());
    return a;
  }

  int row_ = 0;
  int next_ = kFirstSample;
  int interval_ = kDenseInterval;
  std::array<double, kMaxOrder + 1> last_{};                           // the last measured bounds
  std::array<double, kMaxOrder + 1> carried_{};                        // the larger of the last two measured bounds
  std::array<double, kMaxOrder + 1> least_from_kappa_ = Infinities();  // since the last sample
};

}  // namespace mechkin
