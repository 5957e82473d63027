// Idle freedoms on models with many of them: every free body has six (three spins
// about its own axes, three slides), whichever rank path runs; 1000 of them are
// 6000 directions, each kept independent of the others found before it.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>

#include "mobility/mobility.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace {

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

}  // namespace
}  // namespace mechkin
