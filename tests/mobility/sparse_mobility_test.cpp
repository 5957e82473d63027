// The large-model (sparse QR) mobility path against the dense SVD path on the same
// models, and on chains far beyond the dense limit against their known answers and
// against the other formulation of the same mechanism.
#include <gtest/gtest.h>

#include <cmath>
#include <glob.h>
#include <nlohmann/json.hpp>

#include "analysis/motion.hpp"
#include "mobility/mobility.hpp"
#include "analysis/load.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace sparse_mobility_test {

using nlohmann::json;

// N Grashof crank-rocker loops in series (as tools/make_chain.py): rockers R_i pinned
// to ground at x = 0.1 i about z; coupler C_i joins R_{i−1} to R_i. `planar`: the
// coupler joints are revolutes about z (3 redundant equations per loop); otherwise a
// universal and a spherical joint (no redundancy). Same rocker motion either way.
json Chain(int loops, bool planar, int steps) {
  const double crank = 0.04, coupler = 0.12, rocker = 0.08, frame = 0.10;
  json bodies = json::array({{{"name", "R0"}, {"position", {0, 0, 0}}}});
  json joints = json::array({{{"name", "pivot0"}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "R0"},
                              {"origin", {0, 0, 0}}, {"axis", {0, 0, 1}}}});
  double theta = M_PI / 3;
  for (int i = 1; i <= loops; ++i) {
    const double ox = frame * (i - 1), o2x = frame * i;
    const double bx = ox + crank * std::cos(theta), by = crank * std::sin(theta);
    const double dx = o2x - bx, dy = -by, d = std::hypot(dx, dy);
    const double a = (coupler * coupler - rocker * rocker + d * d) / (2 * d), h = std::sqrt(coupler * coupler - a * a);
    const double cx = bx + a * dx / d - h * dy / d, cy = by + a * dy / d + h * dx / d;
    const double ux = (cx - bx) / coupler, uy = (cy - by) / coupler;
    const std::string n = std::to_string(i), prev = std::to_string(i - 1);
    bodies.push_back({{"name", "C" + n}, {"position", {(bx + cx) / 2, (by + cy) / 2, 0}}});
    bodies.push_back({{"name", "R" + n}, {"position", {o2x, 0, 0}}});
    if (planar) {
      joints.push_back({{"name", "A" + n}, {"type", "revolute"}, {"body1", "R" + prev}, {"body2", "C" + n},
                        {"origin", {bx, by, 0}}, {"axis", {0, 0, 1}}});
      joints.push_back({{"name", "B" + n}, {"type", "revolute"}, {"body1", "C" + n}, {"body2", "R" + n},
                        {"origin", {cx, cy, 0}}, {"axis", {0, 0, 1}}});
    } else {
      joints.push_back({{"name", "U" + n}, {"type", "universal"}, {"body1", "R" + prev}, {"body2", "C" + n},
                        {"origin", {bx, by, 0}}, {"axis1", {0, 0, 1}}, {"axis2", {-uy, ux, 0}}});
      joints.push_back({{"name", "S" + n}, {"type", "spherical"}, {"body1", "C" + n}, {"body2", "R" + n},
                        {"origin", {cx, cy, 0}}});
    }
    joints.push_back({{"name", "pivot" + n}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "R" + n},
                      {"origin", {o2x, 0, 0}}, {"axis", {0, 0, 1}}});
    theta = std::atan2(cy, cx - o2x);
  }
  return {{"mechkin", 1}, {"units", {{"length", "m"}, {"angle", "deg"}}}, {"bodies", bodies}, {"joints", joints},
          {"drivers", {{{"name", "crank"}, {"type", "rotation"}, {"joint", "pivot0"}, {"function", "90*t"}}}},
          {"outputs", {{{"name", "first"}, {"type", "joint"}, {"joint", "pivot1"}},
                       {{"name", "third"}, {"type", "joint"}, {"joint", "pivot3"}},
                       {{"name", "last"}, {"type", "joint"}, {"joint", "pivot" + std::to_string(loops)}}}},
          {"analysis", {{"start", 0}, {"end", 1}, {"steps", steps}}}};
}

std::vector<std::string> Descriptions(const MobilityReport& r) {
  std::vector<std::string> d;
  for (const auto& e : r.redundant_equations) d.push_back(e.description + " <- " + json(e.fixed_by).dump());
  return d;
}

void ExpectSameAnalysis(const MobilityReport& dense, const MobilityReport& sparse, const std::string& what) {
  ASSERT_EQ(dense.assembled, sparse.assembled) << what;
  EXPECT_EQ(dense.rank_method, "svd");
  EXPECT_EQ(sparse.rank_method, "sparse-qr");
  EXPECT_EQ(dense.rank, sparse.rank) << what;
  EXPECT_EQ(dense.mobility, sparse.mobility) << what;
  EXPECT_EQ(dense.redundant, sparse.redundant) << what;
  EXPECT_EQ(Descriptions(dense), Descriptions(sparse)) << what;
  EXPECT_EQ(dense.idle.size(), sparse.idle.size()) << what;
  EXPECT_EQ(dense.dof_after_drivers, sparse.dof_after_drivers) << what;
  EXPECT_EQ(dense.driving_status, sparse.driving_status) << what;
  EXPECT_EQ(dense.conflicting_drivers, sparse.conflicting_drivers) << what;
  EXPECT_EQ(dense.remaining_freedoms.size(), sparse.remaining_freedoms.size()) << what;
}

TEST(SparseMobility, AgreesWithTheDensePathOnEveryBundledMechanism) {
  glob_t g;
  ASSERT_EQ(glob((std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/*.json").c_str(), 0, nullptr, &g), 0);
  for (size_t k = 0; k < g.gl_pathc; ++k) {
    const LoadResult r = LoadMechanismFile(g.gl_pathv[k]);
    ASSERT_TRUE(r.ok()) << g.gl_pathv[k];
    ExpectSameAnalysis(CalcMobility(*r.model), CalcMobilitySparse(*r.model), g.gl_pathv[k]);
  }
  globfree(&g);
}

TEST(SparseMobility, AgreesWithTheDensePathOnAnOverconstrainedChain) {
  const Model m = testing_files::FromJson(Chain(20, true, 10));
  const MobilityReport dense = CalcMobility(m), sparse = CalcMobilitySparse(m);
  EXPECT_EQ(dense.redundant, 60);
  ExpectSameAnalysis(dense, sparse, "20 planar loops");
}

TEST(SparseMobility, UnderDrivenAndOverDrivenLargeModels) {
  json under = Chain(120, false, 10);  // 241 bodies: the sparse path
  under["drivers"] = json::array();
  const MobilityReport u = CalcMobility(testing_files::FromJson(under));
  EXPECT_EQ(u.rank_method, "sparse-qr");
  EXPECT_EQ(u.driving_status, DrivingStatus::Under);
  ASSERT_EQ(u.remaining_freedoms.size(), 1u);
  EXPECT_NE(u.remaining_freedoms[0].find("`R"), std::string::npos) << u.remaining_freedoms[0];
  json over = Chain(120, false, 10);
  over["drivers"].push_back({{"name", "second"}, {"type", "rotation"}, {"joint", "pivot7"}, {"function", "10*t"}});
  const MobilityReport o = CalcMobility(testing_files::FromJson(over));
  EXPECT_EQ(o.driving_status, DrivingStatus::Over);
  EXPECT_EQ(o.conflicting_drivers, std::vector<std::string>{"second"});
}

// 1000 planar loops (2001 bodies, 15,005 equations): the answer is known exactly,
// and every set-aside row is one of the out-of-plane rows of a later pivot.
TEST(SparseMobility, ThousandLoopPlanarChain) {
  const Model m = testing_files::FromJson(Chain(1000, true, 10));
  const MobilityReport r = CalcMobility(m);
  ASSERT_TRUE(r.assembled);
  EXPECT_EQ(r.rank_method, "sparse-qr");
  EXPECT_EQ(r.mobility, 1);
  EXPECT_EQ(r.redundant, 3000);
  EXPECT_EQ(r.driving_status, DrivingStatus::Full);
  EXPECT_TRUE(r.idle.empty());
  for (const auto& e : r.redundant_equations) {
    EXPECT_EQ(e.description.rfind("joint `pivot", 0), 0u) << e.description;
    const bool out_of_plane = e.description.find("translation along global z") != std::string::npos ||
                              e.description.find("rotation about its frame's") != std::string::npos;
    EXPECT_TRUE(out_of_plane) << e.description;
  }
}

// The overconstrained planar chain runs with its redundant rows set aside and moves
// exactly as the spatial U-S version of the same geometry (the other formulation).
TEST(SparseMobility, LargeOverconstrainedChainRunsLikeItsSpatialTwin) {
  TableOptions table;
  table.si = true;
  table.order = 2;
  table.all_bodies = false;
  const Motion planar = RunMotion(testing_files::FromJson(Chain(150, true, 8)), {}, table);
  const Motion spatial = RunMotion(testing_files::FromJson(Chain(150, false, 8)), {}, table);
  ASSERT_EQ(planar.rows(), 9);
  ASSERT_EQ(spatial.rows(), 9);
  // The swing dies out along the chain (the last rocker moves ~1e-46 rad), so the
  // comparison is on the first rockers, relative, and on the last one, absolute.
  for (const char* col : {"first", "first_t", "first_tt", "third", "third_t", "third_tt", "last"}) {
    const int cp = planar.layout().Find(col), cs = spatial.layout().Find(col);
    ASSERT_GE(cp, 0);
    double scale = 0;
    for (int r = 0; r < 9; ++r) scale = std::max(scale, std::abs(spatial.at(r, cs)));
    for (int r = 0; r < 9; ++r)
      EXPECT_NEAR(planar.at(r, cp), spatial.at(r, cs), std::max(1e-9 * scale, 1e-12)) << col << " row " << r;
  }
}

}  // namespace
}  // namespace mechkin
