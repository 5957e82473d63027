// Joint definition frames (constraints.md §4) and the mechanism's length scale.
#pragma once

#include "model/model.hpp"

namespace mechkin {

/// Global joint frame at `origin` with h = unit(axis). f is unit(hint) projected
/// onto the plane normal to h (the robust variant of §4), or any perpendicular
/// when no hint is given; g = h × f.
JointFrame MakeFrame(const Vec3& origin, const Vec3& axis);
JointFrame MakeFrame(const Vec3& origin, const Vec3& axis, const Vec3& f_hint);

/// The same frame in the coordinates of a body at (r, A): s' = Aᵀ(P − r), f' = Aᵀf, ...
JointFrame ToLocal(const JointFrame& global, const Vec3& r, const Mat3& A);

/// The mechanism's size (m): the largest distance of a body origin or joint
/// point from their centroid at the design pose. Every length tolerance is
/// relative to it, so results do not depend on the unit the file is written in.
double CharacteristicLength(const Model& model);

}  // namespace mechkin
