// Joint angle columns are continuous from the design pose and a driven joint's
// column equals its driver's value (format: "never wrapped"), whatever the step.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace joint_angle_test {

// The screw jack's crank angle column ("turns", deg) and its velocity under `function`.
std::pair<std::vector<double>, std::vector<double>> Turns(const std::string& function, int steps, double end = 10) {
  nlohmann::json j = testing_files::ReadJson("screw-jack.json");
  j["drivers"][0]["function"] = function;
  j["analysis"] = {{"start", 0}, {"end", end}, {"steps", steps}};
  const Model m = testing_files::FromJson(j);
  TableOptions t;
  t.order = 1;
  const Motion motion = RunMotion(m, AnalysisOptions{}, t);
  EXPECT_TRUE(motion.complete) << motion.stop.message;
  return {motion.Column(motion.layout().Find("turns")), motion.Column(motion.layout().Find("turns_t"))};
}

TEST(JointAngles, DrivenJointReadsItsDriverFromTheFirstRow) {
  auto [a, v] = Turns("720 + 360*t", 200);
  EXPECT_NEAR(a.front(), 720, 1e-9);
  EXPECT_NEAR(a.back(), 720 + 3600, 1e-9);
  auto [b, w] = Turns("-270 + 360*t", 200);
  EXPECT_NEAR(b.front(), -270, 1e-9);
  auto [c, x] = Turns("180 + 360*t", 200);
  EXPECT_NEAR(c.front(), 180, 1e-9);
}

TEST(JointAngles, ThousandTurnsBackwardsReadMinus2000Pi) {
  auto [a, v] = Turns("-360000*t", 36000, 1);
  EXPECT_NEAR(a.back(), -360000, 1e-6);
}

TEST(JointAngles, TwoHundredDegreesPerRowStayContinuous) {
  auto [a, v] = Turns("72000*t", 360, 1);
  EXPECT_NEAR(a.back(), 72000, 1e-6);
  for (size_t k = 1; k < a.size(); ++k) EXPECT_NEAR(a[k] - a[k - 1], 200, 1e-6) << "row " << k;
}

}  // namespace
}  // namespace mechkin
