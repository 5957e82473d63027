// Clearance between bodies along the motion (issue 28, docs/format.md "Clearance"):
// the minimum distance between two bodies' shapes, its closest points, and its time
// derivative from the closest points' velocities (constraints.md §13). The distance
// queries are FCL's (a private dependency of this layer: no FCL type appears here).
#pragma once

#include <memory>
#include <vector>

#include "constraints/system.hpp"

namespace mechkin {

/// Two bodies whose clearance is measured; `output` is the clearance output that
/// asks for it (−1: a pair `check --clearance` chose).
struct ClearancePair {
  BodyIndex body1 = kGround, body2 = kGround;
  int output = -1;
};

struct ClearanceValue {
  double distance = 0;  // m, the smallest over the two bodies' shapes; negative: penetration depth
  double rate = 0;      // m/s, d(distance)/dt = n·(v₂ − v₁) at the closest points (§13); NaN when undefined
  Vec3 point1 = Vec3::Zero(), point2 = Vec3::Zero();  // closest points on body1's and body2's shapes (global, m)
};

/// A body's clearance geometry: its `shape` and its `shapes` (ground's: the file's ground shapes).
std::vector<const Shape*> ClearanceShapes(const Model& model, BodyIndex body);
/// The pairs of the model's clearance outputs, in output order.
std::vector<ClearancePair> ClearanceOutputPairs(const Model& model);
/// Every pair of bodies (ground included) that both have shapes and that no joint
/// connects directly (jointed bodies touch at their joint by design).
std::vector<ClearancePair> ShapedBodyPairs(const Model& model);

/// Evaluates clearances of fixed pairs. Builds the FCL geometry once; an evaluation
/// allocates nothing of its own (FCL's GJK may).
class ClearanceEvaluator {
 public:
  ClearanceEvaluator(const Model& model, std::vector<ClearancePair> pairs);
  ~ClearanceEvaluator();
  ClearanceEvaluator(const ClearanceEvaluator&) = delete;
  ClearanceEvaluator& operator=(const ClearanceEvaluator&) = delete;

  const std::vector<ClearancePair>& pairs() const { return pairs_; }
  int size() const { return static_cast<int>(pairs_.size()); }
  /// The pair's clearance at s; `with_rate`: s carries velocities (order ≥ 1).
  ClearanceValue Evaluate(const SystemState& s, int pair, bool with_rate) const;
  /// A radius about the body origin enclosing every shape of the body (m).
  double Reach(BodyIndex body) const;

 private:
  struct Geometry;  // FCL's shapes of one body, with their frames in the body
  const Geometry& Of(BodyIndex body) const;

  std::vector<ClearancePair> pairs_;
  std::vector<std::unique_ptr<Geometry>> bodies_;  // per body, then ground last
  double tolerance_ = 0;                           // GJK's distance tolerance (m)
};

}  // namespace mechkin
