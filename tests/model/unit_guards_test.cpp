// Unit slips get a warning with the pointer and a fix (issue "Say what engineers measure").
#include <gtest/gtest.h>

#include "test_files.hpp"

namespace mechkin {
namespace unit_guards_test {

bool Warns(const LoadResult& r, const std::string& pointer, const std::string& words) {
  for (const auto& w : r.warnings)
    if (w.pointer == pointer && (w.message + " " + w.fix).find(words) != std::string::npos) return true;
  return false;
}

TEST(UnitGuards, RadiansWrittenInADegreeFile) {
  nlohmann::json doc = testing_files::ReadJson("planar-four-bar.json");
  doc["drivers"][0]["function"] = "2*pi*t";
  const LoadResult slip = LoadMechanismText(doc.dump(), "inline");
  ASSERT_TRUE(slip.ok());
  EXPECT_TRUE(Warns(slip, "/drivers/0/function", "write 360*t"));
  doc["drivers"][0]["function"] = "360*t";
  EXPECT_FALSE(Warns(LoadMechanismText(doc.dump(), "inline"), "/drivers/0/function", "360*t"));
  doc["drivers"][0]["function"] = "20*sin(2*pi*t)";  // pi, but a 40° swing: meant
  EXPECT_TRUE(LoadMechanismText(doc.dump(), "inline").warnings.empty());
}

TEST(UnitGuards, DistanceLinkThousandTimesTheMechanism) {
  nlohmann::json doc = testing_files::ReadJson("r-ss-r-distance-link.json");
  doc["joints"][1]["length"] = 105000;  // mm typed for µm, say
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  EXPECT_TRUE(Warns(r, "/joints/1", "over 1000 times")) << (r.warnings.empty() ? "" : r.warnings[0].ToString());
}

}  // namespace
}  // namespace mechkin

namespace mechkin {
namespace unit_guards_test {

// The frame pivot typed 1000 for 100: the rocker grows to 869 mm; D is far from every
// other joint of ground and of the rocker (7× the other links' median, 120 mm).
TEST(UnitGuards, StrayJointPoint) {
  nlohmann::json doc = testing_files::ReadJson("planar-four-bar.json");
  EXPECT_TRUE(LoadMechanismText(doc.dump(), "inline").warnings.empty());
  doc["joints"][3]["origin"][0] = 1000.0;
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  EXPECT_TRUE(Warns(r, "/joints/3", "typical length")) << (r.warnings.empty() ? "" : r.warnings[0].ToString());
}

}  // namespace
}  // namespace mechkin
