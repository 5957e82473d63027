// The "couplers" section (docs/format.md): what the reader and compile accept, and
// the messages (JSON pointer, problem, fix) for what they refuse.
#include <gtest/gtest.h>

#include "analysis/load.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace couplers_spec_test {

using nlohmann::json;

json TwoShafts(const json& couplers) {
  return {{"mechkin", 1},
          {"units", {{"length", "mm"}, {"angle", "deg"}}},
          {"bodies", {{{"name", "a"}, {"position", {0, 0, 0}}}, {{"name", "b"}, {"position", {50, 0, 0}}},
                      {{"name", "c"}, {"position", {0, 50, 0}}}}},
          {"joints", {{{"name", "Ra"}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "a"}, {"origin", {0, 0, 0}}, {"axis", {0, 0, 1}}},
                      {{"name", "Rb"}, {"type", "revolute"}, {"body1", "ground"}, {"body2", "b"}, {"origin", {50, 0, 0}}, {"axis", {0, 0, 1}}},
                      {{"name", "Pc"}, {"type", "prismatic"}, {"body1", "ground"}, {"body2", "c"}, {"origin", {0, 50, 0}}, {"axis", {1, 0, 0}}},
                      {{"name", "Cc"}, {"type", "cylindrical"}, {"body1", "ground"}, {"body2", "c"}, {"origin", {0, 50, 0}}, {"axis", {1, 0, 0}}}}},
          {"couplers", couplers}};
}

// The first error's pointer and message.
std::pair<std::string, std::string> FirstError(const json& j) {
  const LoadResult r = LoadMechanismText(j.dump(), "inline");
  if (r.errors.empty()) return {"", ""};
  return {r.errors[0].pointer, r.errors[0].message + " | " + r.errors[0].fix};
}

TEST(CouplerSpec, EveryTypeCompiles) {
  const json cs = {{{"name", "g"}, {"type", "gear"}, {"joint1", "Ra"}, {"joint2", "Rb"}, {"ratio", "-24/12"}},
                   {{"name", "r"}, {"type", "rack_pinion"}, {"joint1", "Ra"}, {"joint2", "Pc"}, {"pitch_radius", 8}},
                   {{"name", "s"}, {"type", "screw_coupling"}, {"joint1", "Rb"}, {"joint2", "Pc"}, {"pitch", 5}},
                   {{"name", "e"}, {"type", "belt"}, {"joint1", "Rb"}, {"joint2", "Ra"}, {"ratio", 0.5}},
                   {{"name", "k"}, {"type", "coupling"}, {"joints", {"Ra", "Cc", "Pc"}}, {"coefficients", {1, 2, -3}},
                    {"coordinates", {"rotation", "translation", "translation"}}, {"constant", 4}}};
  const LoadResult r = LoadMechanismText(TwoShafts(cs).dump(), "inline");
  ASSERT_TRUE(r.ok()) << r.errors[0].ToString();
  const Model& m = *r.model;
  ASSERT_EQ(m.couplers.size(), 5u);
  EXPECT_EQ(m.couplers[0].kind, CouplerKind::Gear);
  EXPECT_DOUBLE_EQ(m.couplers[0].ratio, -2);
  EXPECT_DOUBLE_EQ(m.couplers[1].ratio, 0.008);  // pitch radius in m
  EXPECT_DOUBLE_EQ(m.couplers[2].ratio, 0.005);  // pitch in m per turn
  EXPECT_FALSE(m.couplers[1].coordinates[1].rotation);
  // Σ c q = c0 in file units (deg, mm) → SI, divided by the largest slide coefficient
  // (3 per mm = 3000 per m): 1/(π/180)/3000 θ + (2/3) s_Cc − s_Pc = 4/3000.
  const Coupler& k = m.couplers[4];
  EXPECT_NEAR(k.coordinates[0].coefficient, (180 / M_PI) / 3000, 1e-15);
  EXPECT_NEAR(k.coordinates[1].coefficient, 2.0 / 3, 1e-15);
  EXPECT_NEAR(k.coordinates[2].coefficient, -1, 1e-15);
  EXPECT_NEAR(k.constant, 4.0 / 3000, 1e-18);
}

TEST(CouplerSpec, UnknownJointIsNamedWithItsPointer) {
  const auto [ptr, msg] = FirstError(TwoShafts({{{"name", "g"}, {"type", "gear"}, {"joint1", "Ra"}, {"joint2", "Rbb"}, {"ratio", 2}}}));
  EXPECT_EQ(ptr, "/couplers/0/joint2");
  EXPECT_NE(msg.find("unknown joint 'Rbb'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("did you mean 'Rb'"), std::string::npos) << msg;
}

TEST(CouplerSpec, WrongJointTypeForTheCoupler) {
  auto [ptr, msg] = FirstError(TwoShafts({{{"name", "g"}, {"type", "gear"}, {"joint1", "Ra"}, {"joint2", "Pc"}, {"ratio", 2}}}));
  EXPECT_EQ(ptr, "/couplers/0/joint2");
  EXPECT_NE(msg.find("a gear coupler needs a rotation, and prismatic joint 'Pc' has none"), std::string::npos) << msg;
  std::tie(ptr, msg) = FirstError(TwoShafts({{{"name", "r"}, {"type", "rack_pinion"}, {"joint1", "Ra"}, {"joint2", "Rb"}, {"pitch_radius", 8}}}));
  EXPECT_EQ(ptr, "/couplers/0/joint2");
  EXPECT_NE(msg.find("needs a translation"), std::string::npos) << msg;
  // A cylindrical joint in a coupling without "coordinates": which one is asked for.
  std::tie(ptr, msg) = FirstError(TwoShafts({{{"name", "k"}, {"type", "coupling"}, {"joints", {"Ra", "Cc"}}, {"coefficients", {1, 1}}}}));
  EXPECT_EQ(ptr, "/couplers/0/joints/1");
  EXPECT_NE(msg.find("has a rotation and a translation"), std::string::npos) << msg;
}

TEST(CouplerSpec, ZeroRatioAndOtherRefusals) {
  auto [ptr, msg] = FirstError(TwoShafts({{{"name", "g"}, {"type", "gear"}, {"joint1", "Ra"}, {"joint2", "Rb"}, {"ratio", 0}}}));
  EXPECT_EQ(ptr, "/couplers/0/ratio");
  EXPECT_NE(msg.find("non-zero"), std::string::npos) << msg;
  std::tie(ptr, msg) = FirstError(TwoShafts({{{"name", "g"}, {"type", "gear"}, {"joint1", "Ra"}, {"joint2", "Ra"}, {"ratio", 2}}}));
  EXPECT_EQ(ptr, "/couplers/0/joint2");
  EXPECT_NE(msg.find("same joint"), std::string::npos) << msg;
  std::tie(ptr, msg) = FirstError(TwoShafts({{{"name", "g"}, {"type", "gear"}, {"joint1", "Ra"}, {"joint2", "Rb"}, {"raito", 2}}}));
  EXPECT_EQ(ptr, "/couplers/0/raito");
  EXPECT_NE(msg.find("unknown key"), std::string::npos) << msg;
  std::tie(ptr, msg) = FirstError(TwoShafts({{{"name", "g"}, {"type", "gears"}, {"joint1", "Ra"}, {"joint2", "Rb"}}}));
  EXPECT_EQ(ptr, "/couplers/0/type");
  EXPECT_NE(msg.find("did you mean 'gear'"), std::string::npos) << msg;
  std::tie(ptr, msg) = FirstError(TwoShafts({{{"name", "k"}, {"type", "coupling"}, {"joints", {"Ra", "Rb"}}, {"coefficients", {1}}}}));
  EXPECT_EQ(ptr, "/couplers/0/coefficients");
  std::tie(ptr, msg) = FirstError(TwoShafts({{{"name", "g"}, {"type", "gear"}, {"joint1", "Ra"}, {"joint2", "Rb"}, {"ratio", 1}},
                                             {{"name", "g"}, {"type", "belt"}, {"joint1", "Ra"}, {"joint2", "Rb"}, {"ratio", 1}}}));
  EXPECT_EQ(ptr, "/couplers/1/name");
}

}  // namespace
}  // namespace mechkin
