// Reductions and motion bounds as a user meets them (issue 29): `run` prints each
// reduction on stderr and a JSON table carries them; `expect` min/max fail `check` and
// `run` with exit 1, the value and where, and hold with exit 0; a bad reduction is
// refused with its JSON pointer and a fix (exit 1). The numbers are the closed forms
// of the four-bar's transmission angle (tests/analysis/reduction_test.cpp derives them:
// μ_min = acos(17200/19200) = 26.3838° at t = 5/6 s, μ_max = acos(0.0625) = 86.4167°).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace mechkin {
namespace reduction_cli_test {

using mechkin_test::RunCli;
using mechkin_test::RunCliWithStderr;
using nlohmann::json;

std::string WriteTemp(const std::string& name, const json& doc) {
  const std::string p = ::testing::TempDir() + "/" + name;
  std::ofstream(p) << doc.dump(1);
  return p;
}

json Transmission() {
  std::ifstream f(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/four-bar-transmission-angle.json");
  json j = json::parse(f);
  j["analysis"]["steps"] = 50;
  j.erase("expect");
  j["outputs"].erase(j["outputs"].size() - 1);  // the file's own reduction: the tests add theirs
  j["outputs"].push_back({{"name", "mu_min"}, {"type", "reduction"}, {"of", "transmission"}, {"reduce", "min"}});
  return j;
}

const double kMuMin = std::acos(17200.0 / 19200.0) * 180 / M_PI;

TEST(ReductionCli, RunPrintsTheReductionAndTheJsonTableCarriesIt) {
  const std::string file = WriteTemp("mu.json", Transmission());
  const auto text = RunCliWithStderr("run " + file + " --sensitivity b -o /dev/null", "&1");
  EXPECT_EQ(text.code, 0) << text.out;
  EXPECT_NE(text.out.find("mechkin run: mu_min = min of transmission: 26.38"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("at t = 0.83333"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("d/d(b) = "), std::string::npos) << text.out;
  const auto table = RunCliWithStderr("run " + file + " --format json", "/dev/null");
  ASSERT_EQ(table.code, 0);
  const json j = json::parse(table.out);
  ASSERT_EQ(j["reductions"].size(), 1u);
  EXPECT_EQ(j["reductions"][0]["name"], "mu_min");
  EXPECT_EQ(j["reductions"][0]["reduce"], "min");
  EXPECT_NEAR(j["reductions"][0]["value"].get<double>(), kMuMin, 1e-7);
  EXPECT_NEAR(j["reductions"][0]["t"].get<double>(), 5.0 / 6.0, 1e-6);
  EXPECT_EQ(j["reductions"][0]["located"], true);
}

TEST(ReductionCli, ExpectMinAndMaxFailAndHoldInCheckAndRun) {
  json doc = Transmission();
  doc["expect"] = {{"mobility", 1}, {"min", {{"transmission", 40}}}, {"max", {{"transmission", 90}}}};
  const std::string failing = WriteTemp("bound-fail.json", doc);
  const auto checked = RunCli("check " + failing);
  EXPECT_EQ(checked.code, 1) << checked.out;
  EXPECT_NE(checked.out.find("expect mobility = 1: held"), std::string::npos) << checked.out;
  EXPECT_NE(checked.out.find("expect min/transmission = 40.0: FAILED (actual 26.38"), std::string::npos) << checked.out;
  EXPECT_NE(checked.out.find("minimum of transmission at t = 0.83333"), std::string::npos) << checked.out;
  EXPECT_NE(checked.out.find("expect max/transmission = 90.0: held"), std::string::npos) << checked.out;
  const auto ran = RunCliWithStderr("run " + failing + " -o /dev/null", "&1");
  EXPECT_EQ(ran.code, 1) << ran.out;
  EXPECT_NE(ran.out.find("expect min/transmission = 40.0: FAILED (actual 26.38"), std::string::npos) << ran.out;
  EXPECT_EQ(ran.out.find("max/transmission"), std::string::npos) << ran.out;  // held: not printed
  doc["expect"]["min"]["transmission"] = 26;
  doc["expect"]["max"]["transmission"] = 86.5;
  const std::string holding = WriteTemp("bound-hold.json", doc);
  EXPECT_EQ(RunCli("check " + holding).code, 0);
  EXPECT_EQ(RunCliWithStderr("run " + holding + " -o /dev/null", "/dev/null").code, 0);
  doc["expect"]["max"]["transmission"] = 86.4;  // below μ_max = 86.4167°: between rows it is caught
  EXPECT_EQ(RunCli("check " + WriteTemp("bound-tight.json", doc)).code, 1);
}

TEST(ReductionCli, BadReductionsNamePointerAndFix) {
  struct Case { json output; std::string error, fix; };
  const std::vector<Case> cases = {
      {{{"name", "r"}, {"type", "reduction"}, {"of", "transmision"}, {"reduce", "min"}},
       "/outputs/4/of: 'of' names no output 'transmision'", "did you mean 'transmission'?"},
      {{{"name", "r"}, {"type", "reduction"}, {"of", "transmission"}, {"reduce", "minimum"}},
       "/outputs/4/reduce: unknown reduction 'minimum'", "use one of min, max, rms, mean, at"},
      {{{"name", "r"}, {"type", "reduction"}, {"of", "transmission"}, {"reduce", "at"}},
       "/outputs/4: a reduction \"at\" needs 't'", "add \"t\""},
      {{{"name", "r"}, {"type", "reduction"}, {"of", "transmission"}, {"reduce", "rms"}, {"t", 0.5}},
       "/outputs/4/t: 't' goes with \"reduce\": \"at\" only", "remove 't'"},
      {{{"name", "r"}, {"type", "reduction"}, {"of", "transmission"}, {"reduce", "at"}, {"t", 2}},
       "/outputs/4/t: t = 2 s is outside the run (0 to 1 s)", "within /analysis"}};
  for (size_t k = 0; k < cases.size(); ++k) {
    json doc = Transmission();
    doc["outputs"].erase(doc["outputs"].size() - 1);
    doc["outputs"].push_back(cases[k].output);
    const auto r = RunCli("check " + WriteTemp("bad" + std::to_string(k) + ".json", doc));
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_NE(r.out.find(cases[k].error), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(cases[k].fix), std::string::npos) << r.out;
  }
  json doc = Transmission();
  doc["expect"] = {{"min", {{"transmision", 40}}}};
  const auto r = RunCli("check " + WriteTemp("bad-bound.json", doc));
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("/expect/min/transmision: expect min names no output 'transmision'"), std::string::npos)
      << r.out;
}

}  // namespace reduction_cli_test
}  // namespace mechkin
