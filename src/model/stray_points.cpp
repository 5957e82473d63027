#include "model/stray_points.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mechkin {

namespace {

// The joint points grouped by body: point i is side i % 2 of joint i / 2; the
// points of one body are order[begin[i]] .. order[end[i] - 1], ascending.
struct BodyGroups {
  std::vector<std::size_t> order, begin, end;
};

BodyGroups GroupByBody(const std::vector<JointEnds>& joints) {
  const std::size_t n = 2 * joints.size();
  std::vector<std::pair<int, std::size_t>> keyed(n);
  for (std::size_t i = 0; i < n; ++i) keyed[i] = {joints[i / 2].body[i % 2], i};
  std::sort(keyed.begin(), keyed.end());
  BodyGroups g;
  g.order.resize(n);
  g.begin.resize(n);
  g.end.resize(n);
  for (std::size_t first = 0; first < n;) {
    std::size_t last = first;
    while (last < n && keyed[last].first == keyed[first].first) ++last;
    for (std::size_t k = first; k < last; ++k) {
      g.order[k] = keyed[k].second;
      g.begin[keyed[k].second] = first;
      g.end[keyed[k].second] = last;
    }
    first = last;
  }
  return g;
}

const Vec3& PointOf(const std::vector<JointEnds>& joints, std::size_t i) { return joints[i / 2].point[i % 2]; }

// The link length between points a and b, computed as (p_lower - p_higher).norm()
// whatever the argument order, so that every occurrence of a pair is the same double.
double LinkLength(const std::vector<JointEnds>& joints, std::size_t a, std::size_t b) {
  if (a > b) std::swap(a, b);
  return (PointOf(joints, a) - PointOf(joints, b)).norm();
}

// All link lengths, sorted only where a median can fall: ranks [lo, hi] are in
// order, everything before lo is ≤ sorted[lo] and everything after hi ≥ sorted[hi].
struct LengthWindow {
  std::vector<double> lengths;
  std::size_t lo = 0, hi = 0;
  std::size_t ties_after_hi = 0;  // lengths after hi equal to lengths[hi]

  void Arrange(std::size_t first, std::size_t last) {
    lo = first, hi = std::min(last, lengths.size() - 1);
    std::nth_element(lengths.begin(), lengths.begin() + lo, lengths.end());
    std::nth_element(lengths.begin() + lo, lengths.begin() + hi, lengths.end());
    std::sort(lengths.begin() + lo, lengths.begin() + hi + 1);
    ties_after_hi = std::count(lengths.begin() + hi + 1, lengths.end(), lengths[hi]);
  }
  // How many lengths are ≤ v, for v in [lengths[lo], lengths[hi]].
  std::size_t CountUpTo(double v) const {
    const auto window = std::upper_bound(lengths.begin() + lo, lengths.begin() + hi + 1, v) - (lengths.begin() + lo);
    return lo + static_cast<std::size_t>(window) + (v == lengths[hi] ? ties_after_hi : 0);
  }
};

// The element at index t of the sorted multiset all \ mine (mine ⊂ all), t and
// t + |mine| within the window. The answer lies at a rank in [t, t + |mine|] of all;
// the count of remaining lengths up to all[i] grows with i, so a binary search finds
// the first rank where it exceeds t. Of mine only the count below the window and the
// few lengths inside it matter, so mine is scanned once, not sorted.
double SelectExcluding(const LengthWindow& all, const std::vector<double>& mine, std::size_t t,
                       std::vector<double>* inside) {
  const double low = all.lengths[all.lo], high = all.lengths[all.hi];
  std::size_t below = 0;
  inside->clear();
  for (double x : mine) {
    if (x < low) ++below;
    else if (x <= high) inside->push_back(x);
  }
  std::sort(inside->begin(), inside->end());
  auto remaining_up_to = [&](std::size_t i) {
    const double v = all.lengths[i];
    const auto mine_up_to = below + static_cast<std::size_t>(std::upper_bound(inside->begin(), inside->end(), v) - inside->begin());
    return all.CountUpTo(v) - mine_up_to;
  };
  std::size_t lo = t, hi = std::min(all.hi, t + mine.size());
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (remaining_up_to(mid) >= t + 1)
      hi = mid;
    else
      lo = mid + 1;
  }
  return all.lengths[lo];
}

// The lengths involving joint j's two points (its own pair excluded).
void LengthsOfJoint(const std::vector<JointEnds>& joints, const BodyGroups& g, std::size_t j, std::vector<double>* mine) {
  mine->clear();
  for (std::size_t i : {2 * j, 2 * j + 1})
    for (std::size_t k = g.begin[i]; k < g.end[i]; ++k)
      if (g.order[k] / 2 != j) mine->push_back(LinkLength(joints, i, g.order[k]));
}

}  // namespace

std::vector<StrayJointPoint> FindStrayJointPoints(const std::vector<JointEnds>& joints) {
  std::vector<StrayJointPoint> stray;
  for (const auto& j : joints)
    for (const auto& p : j.point)
      if (!p.allFinite()) return stray;  // no median of undefined lengths
  const BodyGroups g = GroupByBody(joints);
  const std::size_t n = 2 * joints.size();
  // Every link length once; per point the nearest other joint point of its body.
  std::vector<double> all, nearest(n, -1);
  for (std::size_t first = 0; first < n; first = g.end[g.order[first]])
    for (std::size_t x = first; x < g.end[g.order[first]]; ++x)
      for (std::size_t y = x + 1; y < g.end[g.order[first]]; ++y) {
        const std::size_t a = g.order[x], b = g.order[y];
        if (a / 2 == b / 2) continue;
        const double d = LinkLength(joints, a, b);
        all.push_back(d);
        for (std::size_t i : {a, b}) nearest[i] = nearest[i] < 0 ? d : std::min(nearest[i], d);
      }
  // The joints judged (both ends share a body with another joint, two lengths
  // left without it) and the ranks of their medians: the window to sort.
  std::vector<std::size_t> judged, count(joints.size(), 0);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    if (nearest[2 * j] < 0 || nearest[2 * j + 1] < 0) continue;
    for (std::size_t i : {2 * j, 2 * j + 1})
      count[j] += g.end[i] - g.begin[i] - 1 - (joints[j].body[0] == joints[j].body[1] ? 1 : 0);
    if (all.size() >= count[j] + 2) judged.push_back(j);
  }
  if (judged.empty()) return stray;
  std::size_t first = all.size(), last = 0;
  for (std::size_t j : judged) {
    const std::size_t t = (all.size() - count[j]) / 2;
    first = std::min(first, t);
    last = std::max(last, t + count[j]);
  }
  LengthWindow window{std::move(all)};
  window.Arrange(first, last);
  std::vector<double> mine, inside;
  for (std::size_t j : judged) {
    LengthsOfJoint(joints, g, j, &mine);
    const double typical = SelectExcluding(window, mine, (window.lengths.size() - mine.size()) / 2, &inside);
    const double near = std::min(nearest[2 * j], nearest[2 * j + 1]);
    if (typical > 0 && near > 5 * typical) stray.push_back({j, near, typical});
  }
  return stray;
}

}  // namespace mechkin
