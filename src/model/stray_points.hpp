#pragma once

#include <cstddef>
#include <vector>

#include "math/rotation.hpp"

namespace mechkin {

/// One joint's two ends for the stray-joint-point guard: the body on each side
/// (any integer id; equal ids mean the same body) and that side's joint point in
/// global coordinates at the design pose.
struct JointEnds {
  int body[2] = {0, 0};
  Vec3 point[2] = {Vec3::Zero(), Vec3::Zero()};
};

/// A joint whose points lie far from every other joint point of both its bodies.
struct StrayJointPoint {
  std::size_t joint = 0;  ///< index into the input
  double nearest = 0;     ///< distance from the joint to the nearest other joint point of its bodies
  double typical = 0;     ///< median of the link lengths not involving the joint
};

/// The stray joint points (a slipped digit such as 1352 typed for 135.2), in joint order.
///
/// A link length is the distance between two points of different joints on the
/// same body. Joint j is stray when each of its two ends shares a body with some
/// other joint's point, at least two link lengths do not involve j, the median of
/// those (the element at index n/2 of the n sorted lengths) is positive, and the
/// nearest other joint point of either end is more than 5 times that median.
///
/// Cost: O(P + W log W + Σ_j m_j) time and O(P) memory for P link lengths, where
/// m_j are the lengths involving joint j (Σ m_j = 2P) and W ≤ max m_j + 1 is the
/// window of ranks where the medians fall. P is the sum over bodies of k(k−1)/2
/// for k joint points on the body: linear in the joints when every body carries a
/// bounded number of joints, quadratic in the joints of one body that carries
/// many (a ground holding every pivot: 12.5 million lengths for 5001 pivots).
/// All lengths are partitioned once (nth_element) and only the window sorted; the
/// median without joint j is found in it by a binary search that discounts j's
/// own lengths, so there is no sort per joint.
std::vector<StrayJointPoint> FindStrayJointPoints(const std::vector<JointEnds>& joints);

}  // namespace mechkin
