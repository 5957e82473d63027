// `mechkin bench` reads its runs through column descriptors: part names that
// look like derivative suffixes must not change what it measures.
#include <gtest/gtest.h>

#include "analysis/speed_accuracy.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace speed_accuracy_test {

using testing_files::FromJson;
using testing_files::ReadJson;

std::string Renamed(std::string text, const std::vector<std::pair<std::string, std::string>>& names) {
  for (const auto& [from, to] : names)
    for (size_t at = 0; (at = text.find("\"" + from + "\"", at)) != std::string::npos; at += to.size() + 2)
      text.replace(at, from.size() + 2, "\"" + to + "\"");
  return text;
}

std::vector<BenchResult> Bench(const Model& m) {
  const ReferenceTable ref = ReferenceFromMotion(RunForBench(m, {PositionSolver::Newton, 1e-13, 3, Formulation::Omega, 160}));
  const std::vector<BenchSetting> grid = {{PositionSolver::Newton, 1e-4, 0, Formulation::Omega, 40},
                                          {PositionSolver::Newton, 1e-10, 3, Formulation::Omega, 40}};
  BenchOptions o;
  o.repeats = 1;
  return RunBench(m, grid, ref, o);
}

TEST(Bench, PartNamesWithDerivativeSuffixesChangeNothing) {
  nlohmann::json plain = ReadJson("spatial-slider-crank.json");
  plain["analysis"]["steps"] = 40;
  const std::string odd_text = Renamed(plain.dump(), {{"crank", "crank_top"}, {"rod", "rod_tip"},
                                                      {"slider", "slider_tt"}, {"piston", "piston_t"},
                                                      {"crank_angle", "angle_ttt"}});
  ASSERT_NE(odd_text.find("rod_tip"), std::string::npos);
  const std::vector<BenchResult> a = Bench(FromJson(plain));
  const std::vector<BenchResult> b = Bench(FromJson(nlohmann::json::parse(odd_text)));
  ASSERT_EQ(a.size(), b.size());
  for (size_t r = 0; r < a.size(); ++r)
    for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(a[r].error[k], b[r].error[k]) << "setting " << r << " order " << k;
  // The loose setting really is inaccurate: an error of 0 would mean nothing was compared.
  EXPECT_GT(b[0].worst_error(), 1e-12);
  EXPECT_LT(b[1].worst_error(), 1e-6);
}

}  // namespace
}  // namespace mechkin
