// The CLI validates through the run request: `run --tol T`, `view --tol T` (and
// range, sweep, tolerance) accept and refuse the same values with
// RunRequest::IsValid's message; `--order 1` on a file with inertia behaves the same
// in run and view and shows the forces of an `--order 2` run.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/run_request.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace run_request_cli_test {

const std::string kBin = MECHKIN_BINARY;
const std::string kSrc = MECHKIN_SOURCE_DIR;

struct Result {
  int code;
  std::string out;  // stdout and stderr
};

Result Mechkin(const std::string& args) {
  Result r{0, ""};
  FILE* p = ::popen((kBin + " " + args + " 2>&1").c_str(), "r");
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

std::string Temp(const std::string& name) { return ::testing::TempDir() + "/run-request-" + name; }

// The four-bar with masses and gravity, written to a file: forces by default.
std::string FourBarWithInertiaFile() {
  nlohmann::json j = testing_files::ReadJson("planar-four-bar.json");
  j["units"]["mass"] = "kg";
  j["gravity"] = {0, -9810, 0};
  for (auto& b : j["bodies"])
    b["inertia"] = {{"mass", 1.5}, {"center", b["position"]}, {"moments", {{200, 0, 0}, {0, 300, 0}, {0, 0, 400}}}};
  j["analysis"]["steps"] = 24;
  const std::string path = Temp("four-bar-inertia.json");
  std::ofstream(path) << j.dump(1);
  return path;
}

// A CSV table as header → column of cell texts (the exact digits written).
std::map<std::string, std::vector<std::string>> ReadCsv(const std::string& path) {
  std::ifstream f(path);
  std::string line, cell;
  std::getline(f, line);
  std::vector<std::string> header;
  std::stringstream h(line);
  while (std::getline(h, cell, ',')) header.push_back(cell);
  std::map<std::string, std::vector<std::string>> columns;
  while (std::getline(f, line)) {
    std::stringstream row(line);
    for (size_t k = 0; std::getline(row, cell, ','); ++k) columns[header.at(k)].push_back(cell);
  }
  return columns;
}

TEST(RunRequestCli, RunViewRangeSweepAndToleranceAgreeOnEveryTolerance) {
  const std::string four_bar = kSrc + "/mechanisms/planar-four-bar.json";
  const std::string slider = kSrc + "/mechanisms/parametric-slider-crank.json";
  struct Case { const char* text; bool valid; const char* shown; };
  for (const Case c : {Case{"1e-16", false, "1e-16"}, Case{"1e-15", true, ""}, Case{"1e-3", true, ""},
                       Case{"5e-3", false, "0.005"}, Case{"0", false, "0"}, Case{"-1", false, "-1"},
                       Case{"nan", false, "nan"}}) {
    const std::string tol = std::string(" --tol ") + c.text;
    const std::vector<Result> results = {
        Mechkin("run " + four_bar + tol + " -o " + Temp("t.csv")),
        Mechkin("view " + four_bar + tol + " --max-frames 10 -o " + Temp("t.html")),
        Mechkin("range " + four_bar + tol + " --steps 8"),
        Mechkin("sweep " + slider + tol + " --grid crank=40:41:2 --threads 1"),
        Mechkin("tolerance " + slider + tol)};
    for (const Result& r : results) {
      if (c.valid) {
        EXPECT_EQ(r.code, 0) << c.text << ": " << r.out;
        EXPECT_EQ(r.out.find("--tol:"), std::string::npos) << r.out;
      } else {
        EXPECT_EQ(r.code, 2) << c.text << ": " << r.out;
        EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "--tol: " + RunRequest::ToleranceProblem(c.shown)) << r.out;
      }
    }
  }
}

TEST(RunRequestCli, OrderOutOfRangeIsRefusedWithTheRequestMessage) {
  const std::string four_bar = kSrc + "/mechanisms/planar-four-bar.json";
  for (const char* cmd : {"run", "view", "sweep", "tolerance"}) {
    const Result r = Mechkin(std::string(cmd) + " " + four_bar + " --order 5");
    EXPECT_EQ(r.code, 2) << cmd << ": " << r.out;
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "--order: " + RunRequest::OrderProblem("5")) << r.out;
  }
}

// Order 1 and order 2 runs of a file with inertia solve the same (the forces need
// accelerations): every column of the order-1 table is the order-2 table's, digit for digit.
TEST(RunRequestCli, OrderOneWithInertiaRunsAndShowsTheForcesOfOrderTwo) {
  const std::string file = FourBarWithInertiaFile();
  const Result one = Mechkin("run " + file + " --order 1 -o " + Temp("one.csv"));
  const Result two = Mechkin("run " + file + " --order 2 -o " + Temp("two.csv"));
  ASSERT_EQ(one.code, 0) << one.out;
  ASSERT_EQ(two.code, 0) << two.out;
  const auto a = ReadCsv(Temp("one.csv")), b = ReadCsv(Temp("two.csv"));
  int forces = 0;
  for (const auto& [name, cells] : a) {
    EXPECT_EQ(name.find("_tt"), std::string::npos) << name;  // order 1 shows no accelerations
    ASSERT_TRUE(b.count(name)) << name;
    EXPECT_EQ(cells, b.at(name)) << name;
    if (name.find(".effort") != std::string::npos || name.find(".fx") != std::string::npos) ++forces;
  }
  EXPECT_EQ(forces, 1 + 4);  // the driver's effort and each joint's fx
  // view at order 1 keeps the forces too (it dropped them before): same exit as run.
  const Result view = Mechkin("view " + file + " --order 1 -o " + Temp("one.html"));
  EXPECT_EQ(view.code, 0) << view.out;
  std::ifstream page(Temp("one.html"));
  const std::string html((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find(".effort"), std::string::npos);
}

// `--error-bounds measured` measures every row's bounds: the motion's cells are the
// default run's to the digit, the error_bound columns differ (the four-bar's regular
// rows take measured values instead of κ's); an unknown choice exits 2, nothing written.
TEST(RunRequestCli, MeasuredErrorBoundsChangeOnlyTheBoundColumns) {
  const std::string file = kSrc + "/mechanisms/planar-four-bar.json";
  ASSERT_EQ(Mechkin("run " + file + " -o " + Temp("auto.csv")).code, 0);
  ASSERT_EQ(Mechkin("run " + file + " --error-bounds measured -o " + Temp("measured.csv")).code, 0);
  const auto a = ReadCsv(Temp("auto.csv")), m = ReadCsv(Temp("measured.csv"));
  ASSERT_EQ(a.size(), m.size());
  int bound_columns = 0, differing = 0;
  for (const auto& [name, cells] : a) {
    ASSERT_TRUE(m.count(name)) << name;
    if (name.rfind("error_bound", 0) != 0) {
      EXPECT_EQ(cells, m.at(name)) << name;
      continue;
    }
    ++bound_columns;
    for (size_t i = 0; i < cells.size(); ++i) differing += cells[i] != m.at(name)[i];
  }
  EXPECT_EQ(bound_columns, 4);
  EXPECT_GT(differing, 100);
  std::remove(Temp("never.csv").c_str());
  const Result bad = Mechkin("run " + file + " --error-bounds sometimes -o " + Temp("never.csv"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.out.find("--error-bounds"), std::string::npos) << bad.out;
  EXPECT_FALSE(std::ifstream(Temp("never.csv")).good());
}

}  // namespace
}  // namespace mechkin
