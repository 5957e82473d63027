// Block-triangular structure and the block path (issue: speed — solve only what
// the question needs).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>

#include "analysis/kinematic_analysis.hpp"
#include "analysis/load.hpp"
#include "analysis/motion.hpp"
#include "test_files.hpp"
#include "kinematics/block_structure.hpp"
#include "kinematics/newton.hpp"

namespace mechkin {
namespace blocks_test {

// Each test writes its own file: ctest runs tests in parallel.
Model Chain(int n) {
  const std::string path = ::testing::TempDir() + "/chain-" + std::to_string(n) + "-" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".json";
  const std::string cmd = "python3 " + std::string(MECHKIN_SOURCE_DIR) + "/tools/make_chain.py " + std::to_string(n) + " " + path;
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  LoadResult r = LoadMechanismFile(path);
  EXPECT_TRUE(r.ok());
  return std::move(*r.model);
}

// The N-loop chain splits into N + 1 blocks: the driven crank R0 (6 unknowns), then
// one block per loop (coupler and rocker, 12 unknowns), each reading the one before.
TEST(Blocks, ChainSplitsIntoOneBlockPerLoop) {
  const Model m = Chain(10);
  const ConstraintSystem sys(m, true);
  NewtonSolver newton(sys, [&] { std::vector<int> r(sys.num_rows()); for (int k = 0; k < sys.num_rows(); ++k) r[k] = k; return r; }());
  BlockStructure bs;
  ASSERT_TRUE(FindBlockStructure(newton.jacobian(), &bs));
  ASSERT_EQ(bs.size(), 11);
  EXPECT_EQ(bs.rows[0].size(), 6u);
  EXPECT_TRUE(bs.deps[0].empty());
  for (int b = 1; b < bs.size(); ++b) {
    EXPECT_EQ(bs.rows[b].size(), 12u);
    EXPECT_EQ(bs.deps[b], std::vector<int>{b - 1});
  }
  // Asking for R3 needs the blocks of R0 … R3 only.
  std::vector<int> cols;
  for (int q = 0; q < 6; ++q) cols.push_back(6 * 5 + q);  // body 5 = R3 (R0, C1, R1, C2, R2, C3, R3)
  const auto need = NeededBlocks(bs, cols);
  EXPECT_EQ(std::count(need.begin(), need.end(), 1), 4);
}

// A closed loop is one block: nothing to skip.
TEST(Blocks, SliderCrankIsOneLoop) {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/spatial-slider-crank.json");
  ASSERT_TRUE(r.ok());
  const ConstraintSystem sys(*r.model, true);
  std::vector<int> rows(sys.num_rows());
  for (int k = 0; k < sys.num_rows(); ++k) rows[k] = k;
  NewtonSolver newton(sys, rows);
  BlockStructure bs;
  ASSERT_TRUE(FindBlockStructure(newton.jacobian(), &bs));
  // The crank (bearing + driver) is determined first, rod and slider together after it.
  ASSERT_EQ(bs.size(), 2);
  EXPECT_EQ(bs.rows[0].size(), 6u);
  EXPECT_EQ(bs.rows[1].size(), 12u);
}

// The block path solving only what R3 needs gives R3's motion as the full run does
// (both satisfy the residual tolerance 1e-10; they may differ by cond · tol).
TEST(Blocks, SelectedBodiesMatchTheFullRun) {
  const Model m = Chain(10);
  auto run = [&](std::vector<int> needed, AnalysisReport* rep) {
    TableOptions topt;
    topt.si = true;
    topt.all_bodies = false;
    topt.bodies = {"R3"};
    topt.all_outputs = false;
    MotionRecorder table(m, topt);
    AnalysisOptions o;
    o.needed_bodies = std::move(needed);
    *rep = RunKinematicAnalysis(m, o, [&](const SystemState& s, const StepDiagnostics& d) {
      return table.Record(s, d);
    });
    return testing_files::RowsOf(table.motion());
  };
  AnalysisReport full_rep, part_rep;
  const auto full = run({}, &full_rep);
  const auto part = run({5}, &part_rep);
  ASSERT_TRUE(full_rep.complete && part_rep.complete) << part_rep.message;
  EXPECT_EQ(full_rep.blocks, 11);
  EXPECT_EQ(full_rep.blocks_solved, 11);
  EXPECT_EQ(part_rep.blocks_solved, 4);
  double cond = 0;
  for (const auto& s : full_rep.steps) cond = std::max(cond, s.condition);
  ASSERT_EQ(full.size(), part.size());
  for (size_t c = 1; c < 1 + 3 * 4 + 4 + 3 * 3; ++c) {  // R3's columns
    double scale = 0, err = 0;
    for (size_t k = 0; k < full.size(); ++k) {
      scale = std::max(scale, std::abs(full[k][c]));
      err = std::max(err, std::abs(full[k][c] - part[k][c]));
    }
    EXPECT_LE(err, 10 * cond * 1e-10 * std::max(scale, 1e-3)) << "column " << c;
  }
}

}  // namespace
}  // namespace mechkin
