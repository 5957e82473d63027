// Placement by markers (docs/format.md "Assembly from dimensions"): in a file whose
// joints name markers, compile places every body without a position along a
// spanning tree of the joints, so that each tree joint's two markers coincide
// (joint coordinate 0). The joints outside the tree close loops; the assembly
// (analysis/assemble_model.hpp) closes them by Newton, which needs the equations.
#include <deque>

#include "model/compiler.hpp"

namespace mechkin {

namespace {

// The global frame the child's marker must take: the parent's marker frame, or for
// a universal joint that frame with h and f exchanged (body2 carries axis2 as its h,
// constraints.md §5, U row), or for a distance link the parent's marker moved by the
// link's length along its f axis.
JointFrame ChildTarget(const Joint& j, const JointFrame& parent) {
  JointFrame t = parent;
  if (j.type->frames == JointFrameRule::CrossAxes) {
    t.f = parent.h;
    t.g = -parent.g;
    t.h = parent.f;
  } else if (j.type->frames == JointFrameRule::TwoPoints) {
    t.origin = parent.origin + j.length * parent.f;
  }
  return t;
}

Mat3 Columns(const JointFrame& f) {
  Mat3 m;
  m.col(0) = f.f;
  m.col(1) = f.g;
  m.col(2) = f.h;
  return m;
}

}  // namespace

// The child of tree joint `joint` (the body that is not `parent`) placed so that its
// marker frame takes the target frame: A_c F_c = G, r_c = o − A_c s_c.
void Compiler::PlaceChild(int joint, BodyIndex parent) {
  const Joint& j = model_.joints[joint];
  const bool parent_is_1 = j.body1 == parent;
  const BodyIndex child = parent_is_1 ? j.body2 : j.body1;
  const JointFrame& own = parent_is_1 ? j.frame2 : j.frame1;
  const auto [rp, Ap] = Pose(parent);
  const JointFrame& pf = parent_is_1 ? j.frame1 : j.frame2;
  JointFrame global;
  global.origin = rp + Ap * pf.origin;
  global.f = Ap * pf.f, global.g = Ap * pf.g, global.h = Ap * pf.h;
  const JointFrame target = ChildTarget(j, global);
  const Mat3 A = j.type->frames == JointFrameRule::TwoPoints ? Ap : Mat3(Columns(target) * Columns(own).transpose());
  Body& b = model_.bodies[child];
  b.euler = QuatFromMatrix(A);
  b.position = target.origin - CalcA(b.euler) * own.origin;
}

// Breadth-first from ground (then from each body no joint path ties to ground),
// preferring the joints that fix a relative pose over distance links: linear in
// bodies + joints. A body with a position keeps it (the sketch is the guess).
void Compiler::PlaceByMarkers() {
  const int n = model_.num_bodies();
  std::vector<std::vector<int>> adjacent(n + 1);  // node n is ground
  auto node = [&](BodyIndex b) { return b == kGround ? n : b; };
  for (size_t k = 0; k < model_.joints.size(); ++k) {
    adjacent[node(model_.joints[k].body1)].push_back(static_cast<int>(k));
    adjacent[node(model_.joints[k].body2)].push_back(static_cast<int>(k));
  }
  AssemblyRecord rec;
  rec.tree_joint.assign(n, -1);
  rec.sketched = sketched_;
  std::vector<bool> reached(n + 1, false), in_tree(model_.joints.size(), false);
  std::deque<int> queue;
  auto grow = [&](bool distance_links) {
    std::deque<int> q = queue;
    while (!q.empty()) {
      const int u = q.front();
      q.pop_front();
      for (int k : adjacent[u]) {
        const Joint& j = model_.joints[k];
        if (!distance_links && j.type->frames == JointFrameRule::TwoPoints) continue;
        const int v = node(j.body1) == u ? node(j.body2) : node(j.body1);
        if (reached[v]) continue;
        reached[v] = true;
        in_tree[k] = true;
        rec.tree_joint[v] = k;
        if (!sketched_[v]) PlaceChild(k, u == n ? kGround : u);
        q.push_back(v), queue.push_back(v);
      }
    }
  };
  for (int k = 0; k <= n; ++k) {  // ground first, then the free-standing groups
    const int root = k == 0 ? n : k - 1;
    if (reached[root]) continue;
    reached[root] = true;
    queue.assign(1, root);
    grow(false);
    grow(true);
  }
  for (int b = 0; b < n; ++b) {
    rec.guess_position.push_back(model_.bodies[b].position);
    rec.guess_euler.push_back(model_.bodies[b].euler);
  }
  for (size_t k = 0; k < model_.joints.size(); ++k)
    if (!in_tree[k]) rec.loops.push_back(AssemblyLoop{static_cast<int>(k), {}, 0, 0});
  model_.assembly = std::move(rec);
}

}  // namespace mechkin
