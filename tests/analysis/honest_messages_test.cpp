// Issue 23 item 10: messages that say what happened. A start value beyond the
// range names the limit's bracket (not only the residuals); a velocity ratio at
// order 0 is "not computed", not a worst case of 0 with NaN contributions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/kinematic_analysis.hpp"
#include "analysis/tolerance.hpp"
#include "model/loader.hpp"
#include "../test_files.hpp"

namespace mechkin {
namespace honest_messages_test {

// The planar four-bar driven at its rocker D, starting at −120° where the rocker
// (swinging about 60° in all) cannot go: the continuation from the design value 0
// in 10° increments gets to −10° and fails at −20°.
TEST(HonestMessages, AStartBeyondTheRangeNamesTheLimit) {
  nlohmann::json j = testing_files::ReadJson("planar-four-bar.json");
  j["drivers"][0]["joint"] = "D";
  j["drivers"][0]["function"] = "-120*t";
  j["analysis"] = {{"start", 1}, {"end", 1.2}, {"steps", 10}};
  j.erase("expect");
  const AnalysisReport rep = RunKinematicAnalysis(testing_files::FromJson(j), AnalysisOptions{},
                                                  [](const SystemState&, const StepDiagnostics&) { return true; });
  EXPECT_EQ(rep.stop, StopKind::AssemblyFailed) << rep.message;
  EXPECT_NE(rep.message.find("driver `motor` wants -120 deg at t = start but the mechanism follows it from 0 only to "
                             "-10 deg (fails at -20 deg): a limit of motion or singular position lies between these"),
            std::string::npos)
      << rep.message;
  // The residual list is never empty: three rows named after it.
  const size_t list = rep.message.find("largest residuals:");
  ASSERT_NE(list, std::string::npos) << rep.message;
  EXPECT_EQ(std::count(rep.message.begin() + static_cast<long>(list), rep.message.end(), '\n'), 3) << rep.message;
}

TEST(HonestMessages, AVelocityRatioAtOrderZeroIsNotComputed) {
  nlohmann::json j = testing_files::ReadJson("parametric-slider-crank.json");
  j["outputs"].push_back({{"name", "ratio"}, {"type", "velocity_ratio"}, {"output", "stroke"}, {"input", "motor"}});
  j.erase("expect");
  const ToleranceReport rep = AnalyzeTolerances(testing_files::FromJson(j), ToleranceOptions{});
  ASSERT_TRUE(rep.ok) << rep.message;
  int ratios = 0;
  for (const ToleranceColumn& c : rep.columns) {
    if (c.name.rfind("ratio", 0) != 0) {
      EXPECT_TRUE(c.not_computed.empty()) << c.name;
      for (double w : c.worst_case) EXPECT_TRUE(std::isfinite(w)) << c.name;
      continue;
    }
    ++ratios;
    EXPECT_EQ(c.not_computed.rfind("not computed at order 0", 0), 0u) << c.not_computed;
    EXPECT_TRUE(c.worst_case.empty());
    EXPECT_TRUE(c.contributions.empty());
  }
  EXPECT_EQ(ratios, 1);
}

}  // namespace
}  // namespace mechkin
