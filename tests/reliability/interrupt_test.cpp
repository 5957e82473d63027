// Interrupts everywhere (issue 24): SIGINT with --keep-partial stops sweep,
// tolerance --monte-carlo, range and view at their next step, writes what they
// have marked partial and exits 130, as `run --keep-partial` does; without
// --keep-partial (and on SIGTERM) the temporary output is removed and the signal
// ends the process. Before the fix these commands ran to the end and exited 0.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"

namespace interrupt_test {

using mechkin_test::RunAndSignal;
using mechkin_test::SignalledExit;
using nlohmann::json;

std::string Dir() {
  static std::string d = [] {
    std::string t = ::testing::TempDir() + "/mechkin-interrupt-XXXXXX";
    return std::string(::mkdtemp(t.data()));
  }();
  return d;
}

std::string Read(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

bool Exists(const std::string& p) {
  struct stat st;
  return ::stat(p.c_str(), &st) == 0;
}

const std::string kFourBar = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json";

// The parametric four-bar with `steps` steps (a run of seconds, so the signal comes mid-work).
std::string LongFourBar(int steps) {
  std::ifstream in(kFourBar);
  json j = json::parse(in);
  j["analysis"]["steps"] = steps;
  const std::string p = Dir() + "/four-bar-" + std::to_string(steps) + ".json";
  std::ofstream(p) << j.dump();
  return p;
}

// Data rows of a CSV after its header (lines not starting with '#', minus the header).
int DataRows(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  int rows = -1;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') ++rows;
  return rows;
}

// The signal arrives after the command has loaded its file and started (about 1 s of
// a run that takes tens of seconds); the test asserts what is written, not when.
constexpr int kSignalAfterMs = 1000;

TEST(Interrupts, SigintStopsA20000VariantSweepWithAPartialReport) {
  const std::string out = Dir() + "/sweep.csv";
  const SignalledExit e = RunAndSignal(
      {"sweep", kFourBar, "--samples", "20000", "--threads", "2", "-o", out, "--keep-partial"}, SIGINT, kSignalAfterMs);
  ASSERT_TRUE(e.exited) << "killed by signal " << e.signal;
  EXPECT_EQ(e.code, 130);
  const std::string text = Read(out);
  ASSERT_EQ(text.rfind("# PARTIAL SWEEP: interrupted; ", 0), 0u) << text.substr(0, 200);
  const int rows = DataRows(text);
  EXPECT_GT(rows, 0);
  EXPECT_LT(rows, 20000);
  // The note counts the rows written.
  EXPECT_NE(text.find("; " + std::to_string(rows) + " of 20000 variants summarised\n"), std::string::npos)
      << text.substr(0, 200);
  std::printf("partial sweep: %d of 20000 variants\n", rows);
}

TEST(Interrupts, PartialJsonShardIsMarkedAndMergeRefusesIt) {
  const std::string shard = Dir() + "/shard.json";
  const SignalledExit e = RunAndSignal({"sweep", kFourBar, "--samples", "20000", "--threads", "2", "--format", "json",
                                        "--shard", "1/2", "-o", shard, "--keep-partial"},
                                       SIGINT, kSignalAfterMs);
  ASSERT_TRUE(e.exited);
  EXPECT_EQ(e.code, 130);
  std::ifstream in(shard);
  const json doc = json::parse(in);
  ASSERT_EQ(doc.value("partial", false), true) << doc.dump().substr(0, 300);
  const std::string note = doc.value("note", "");
  EXPECT_EQ(note.rfind("interrupted; ", 0), 0u) << note;
  EXPECT_NE(note.find(" of 10000 variants"), std::string::npos) << note;
  const mechkin_test::CliResult merged = mechkin_test::RunCli("sweep --merge " + shard + " -o " + Dir() + "/m.csv");
  EXPECT_EQ(merged.code, 1);
  EXPECT_NE(merged.out.find("is a partial shard (interrupted; "), std::string::npos) << merged.out;
}

TEST(Interrupts, SigintWithoutKeepPartialLeavesNoOutput) {
  const std::string out = Dir() + "/no-partial.csv";
  const SignalledExit e =
      RunAndSignal({"sweep", kFourBar, "--samples", "20000", "--threads", "2", "-o", out}, SIGINT, kSignalAfterMs);
  EXPECT_FALSE(e.exited);
  EXPECT_EQ(e.signal, SIGINT);
  EXPECT_FALSE(Exists(out));
}

TEST(Interrupts, SigintStopsTheMonteCarloWithAPartialReport) {
  const std::string out = Dir() + "/tolerance.txt";
  const SignalledExit e = RunAndSignal({"tolerance", kFourBar, "--monte-carlo", "100000", "--threads", "2", "-o", out,
                                        "--keep-partial"},
                                       SIGINT, kSignalAfterMs);
  ASSERT_TRUE(e.exited);
  EXPECT_EQ(e.code, 130);
  const std::string text = Read(out);
  EXPECT_EQ(text.rfind("# PARTIAL REPORT: interrupted; ", 0), 0u) << text.substr(0, 200);
  EXPECT_NE(text.find("Monte-Carlo samples finished"), std::string::npos);
}

TEST(Interrupts, SigintStopsRangeWithAPartialReport) {
  const std::string out = Dir() + "/range.json";
  const SignalledExit e = RunAndSignal(
      {"range", kFourBar, "--steps", "10000000", "--format", "json", "-o", out, "--keep-partial"}, SIGINT, kSignalAfterMs);
  ASSERT_TRUE(e.exited);
  EXPECT_EQ(e.code, 130);
  std::ifstream in(out);
  const json doc = json::parse(in);
  EXPECT_EQ(doc.value("partial", false), true) << doc.dump();
  EXPECT_EQ(doc.value("note", ""), "interrupted");
  EXPECT_TRUE(doc["drivers"].empty()) << "the one driver was not finished";
}

TEST(Interrupts, SigintStopsViewWithThePageOfTheRowsSoFar) {
  const std::string page = Dir() + "/view.html";
  const SignalledExit e = RunAndSignal({"view", LongFourBar(2000000), "--order", "0", "-o", page, "--keep-partial"},
                                       SIGINT, kSignalAfterMs);
  ASSERT_TRUE(e.exited);
  EXPECT_EQ(e.code, 130);
  const std::string html = Read(page);
  EXPECT_NE(html.find("interrupted"), std::string::npos) << "the page marks where the motion stopped";
}

TEST(Interrupts, SigtermEndsTheSweepAndRemovesItsTemporary) {
  const std::string dir = Dir() + "/term";
  ::mkdir(dir.c_str(), 0755);
  std::ofstream(dir + "/s.csv") << "old\n";
  const SignalledExit e = RunAndSignal(
      {"sweep", kFourBar, "--samples", "20000", "--threads", "2", "-o", dir + "/s.csv", "--keep-partial"}, SIGTERM,
      kSignalAfterMs);
  EXPECT_FALSE(e.exited);
  EXPECT_EQ(e.signal, SIGTERM);
  EXPECT_EQ(Read(dir + "/s.csv"), "old\n");
}

}  // namespace
