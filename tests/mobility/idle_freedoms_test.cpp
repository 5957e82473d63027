// Idle freedoms on models with many of them: every free body has six (three spins
// about its own axes, three slides), whichever rank path runs; 1000 of them are
// 6000 directions, each kept independent of the others found before it.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>

#include "mobility/mobility.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace idle_freedoms_test {

using nlohmann::json;

json FreeBodies(int n) {
  json bodies = json::array();
  for (int i = 0; i < n; ++i) bodies.push_back({{"name", "b" + std::to_string(i)}, {"position", {0.1 * i, 0.02 * (i % 3), 0}}});
  return {{"mechkin", 1}, {"units", {{"length", "m"}, {"angle", "deg"}}}, {"bodies", bodies}, {"joints", json::array()}};
}

void ExpectSixEach(const MobilityReport& r, int n) {
  ASSERT_EQ(r.idle.size(), static_cast<size_t>(6 * n));
  std::map<std::string, int> spins, slides;
  for (const auto& f : r.idle) {
    const bool spin = f.description.find(" spins about its own axis ") != std::string::npos;
    ++(spin ? spins : slides)[f.body];
    EXPECT_EQ(f.description.rfind("body `" + f.body + "`", 0), 0u) << f.description;
  }
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(spins["b" + std::to_string(i)], 3);
    EXPECT_EQ(slides["b" + std::to_string(i)], 3);
  }
}

TEST(IdleFreedoms, SixForEveryFreeBodyOnBothRankPaths) {
  const MobilityReport dense = CalcMobility(testing_files::FromJson(FreeBodies(40)));
  EXPECT_EQ(dense.rank_method, "svd");
  ExpectSixEach(dense, 40);
  const MobilityReport sparse = CalcMobility(testing_files::FromJson(FreeBodies(1000)));
  EXPECT_EQ(sparse.rank_method, "sparse-qr");
  ExpectSixEach(sparse, 1000);
}

// A chain of n bodies hung from the ground by spherical joints, b0 to b{n−1}, the
// joint points zig-zagging (or all on one line). Each body but the last spins about
// the line through its two joint points (n − 1), the last about its one joint point
// (3); each pair but the last turns about the line through its two outer joint
// points, which moves its middle joint: new (n − 2); the last pair turns about its
// one outer point, of which the turn about the line to the middle joint is the two
// bodies' own spins (2 new). So 2n + 2 idle freedoms. On a line, every pair's turn
// about the common line is its bodies' own spins: n + 4. Many pairs overlap along
// the chain, so these test the independence check as well as the count.
json SphericalChain(int n, bool zigzag) {
  json j = FreeBodies(n);
  for (int i = 0; i < n; ++i)
    j["joints"].push_back({{"name", "s" + std::to_string(i)}, {"type", "spherical"},
                           {"body1", i == 0 ? std::string("ground") : "b" + std::to_string(i - 1)},
                           {"body2", "b" + std::to_string(i)},
                           {"origin", {0.1 * i - 0.05, zigzag ? 0.01 * (i % 2) : 0.01, 0}}});
  return j;
}

TEST(IdleFreedoms, SphericalChainsOnBothRankPaths) {
  for (int n : {40, 300}) {
    const MobilityReport zigzag = CalcMobility(testing_files::FromJson(SphericalChain(n, true)));
    EXPECT_EQ(zigzag.rank_method, n > 200 ? "sparse-qr" : "svd");
    EXPECT_EQ(static_cast<int>(zigzag.idle.size()), 2 * n + 2) << n;
    const MobilityReport line = CalcMobility(testing_files::FromJson(SphericalChain(n, false)));
    EXPECT_EQ(static_cast<int>(line.idle.size()), n + 4) << n;
  }
}

}  // namespace
}  // namespace mechkin
