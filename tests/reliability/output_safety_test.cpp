// Issue 24, output safety: every file a command writes goes through one path
// (io/output_file.hpp). Never the input mechanism file (by inode: a symlink or a
// hard link to it counts), never two outputs of one command onto one file, the
// destination checked before the work. Run against the real executable.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace output_safety_test {

const std::string kBin = MECHKIN_BINARY;
const std::string kMechanisms = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/";

struct Result {
  int code;
  std::string out;  // stdout and stderr together
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

std::string Dir() {
  static std::string d = [] {
    std::string t = ::testing::TempDir() + "/mechkin-out-XXXXXX";
    return std::string(::mkdtemp(t.data()));
  }();
  return d;
}

std::string Read(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

bool Exists(const std::string& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0;
}

// A private copy of a bundled parametric mechanism (the tests may try to overwrite it).
std::string CopyOf(const std::string& bundled, const std::string& name) {
  const std::string p = Dir() + "/" + name;
  std::ofstream(p, std::ios::binary) << Read(kMechanisms + bundled);
  return p;
}

// The exit code `run -o INPUT` gives: every writer must give the same.
int RunOntoInputCode() {
  const std::string in = CopyOf("parametric-slider-crank.json", "run-self.json");
  return Mechkin("run " + in + " -o " + in).code;
}

// `command` (with INPUT where the input goes and OUT where the output goes) run
// with OUT = the input itself, a symlink to it and a hard link to it: refused
// each time with run -o INPUT's exit code, the input unchanged byte for byte.
void ExpectInputRefused(const std::string& command, const std::string& tag) {
  const std::string in = CopyOf("parametric-slider-crank.json", tag + ".json");
  const std::string original = Read(in);
  const std::string symlink = Dir() + "/" + tag + "-symlink.out", hardlink = Dir() + "/" + tag + "-hardlink.out";
  ASSERT_EQ(::symlink(in.c_str(), symlink.c_str()), 0);
  ASSERT_EQ(::link(in.c_str(), hardlink.c_str()), 0);
  const int expected = RunOntoInputCode();
  ASSERT_EQ(expected, 1);
  for (const std::string& out : {in, symlink, hardlink}) {
    std::string args = command;
    args.replace(args.find("INPUT"), 5, in);
    args.replace(args.find("OUT"), 3, out);
    const Result r = Mechkin(args);
    EXPECT_EQ(r.code, expected) << args << "\n" << r.out;
    EXPECT_NE(r.out.find("onto the input file"), std::string::npos) << args << "\n" << r.out;
    EXPECT_EQ(Read(in), original) << args << ": the input changed";
  }
  struct stat st {};
  ASSERT_EQ(::lstat(symlink.c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode)) << "the link stays a link";
}

TEST(OutputSafety, RunRefusesTheInputThroughLinks) { ExpectInputRefused("run INPUT -o OUT", "run"); }

TEST(OutputSafety, ViewPageRefusesTheInput) { ExpectInputRefused("view INPUT -o OUT", "view-page"); }

TEST(OutputSafety, ViewGltfRefusesTheInput) {
  ExpectInputRefused("view INPUT -o " + Dir() + "/gltf-page.html --gltf OUT", "view-gltf");
  EXPECT_FALSE(Exists(Dir() + "/gltf-page.html")) << "refused before the page was written";
}

TEST(OutputSafety, BenchCsvAndSvgRefuseTheInput) {
  ExpectInputRefused("bench --quick INPUT --svg " + Dir() + "/b.svg --csv OUT", "bench-csv");
  ExpectInputRefused("bench --quick INPUT --csv " + Dir() + "/b.csv --svg OUT", "bench-svg");
  EXPECT_FALSE(Exists(Dir() + "/b.svg"));
  EXPECT_FALSE(Exists(Dir() + "/b.csv"));
}

TEST(OutputSafety, SweepToleranceAndRangeReportsRefuseTheInput) {
  ExpectInputRefused("sweep INPUT --grid crank=30:50:3 -o OUT", "sweep");
  ExpectInputRefused("tolerance INPUT -o OUT", "tolerance");
  ExpectInputRefused("range INPUT -o OUT", "range");
}

TEST(OutputSafety, SweepMergeRefusesAShardAsItsOutput) {
  const std::string in = CopyOf("parametric-slider-crank.json", "merge-in.json");
  const std::string a = Dir() + "/shard-a.json", b = Dir() + "/shard-b.json";
  ASSERT_EQ(Mechkin("sweep " + in + " --grid crank=30:50:4 --shard 1/2 --format json -o " + a).code, 0);
  ASSERT_EQ(Mechkin("sweep " + in + " --grid crank=30:50:4 --shard 2/2 --format json -o " + b).code, 0);
  const std::string shard = Read(b);
  const Result r = Mechkin("sweep --merge " + a + " " + b + " -o " + b);
  EXPECT_EQ(r.code, RunOntoInputCode()) << r.out;
  EXPECT_NE(r.out.find("onto the input file"), std::string::npos) << r.out;
  EXPECT_EQ(Read(b), shard);
}

// Two outputs of one command onto one file: refused before any work, nothing written.
TEST(OutputSafety, TwoOutputsOntoOneFileAreRefused) {
  const std::string in = CopyOf("parametric-slider-crank.json", "twice.json");
  const std::string page = Dir() + "/twice.html";
  Result r = Mechkin("view " + in + " -o " + page + " --gltf " + page);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("are the same file"), std::string::npos) << r.out;
  EXPECT_FALSE(Exists(page));
  // The same file under another name: an existing page and a hard link to it.
  std::ofstream(page) << "old page\n";
  const std::string alias = Dir() + "/twice-alias.glb";
  ASSERT_EQ(::link(page.c_str(), alias.c_str()), 0);
  r = Mechkin("view " + in + " -o " + page + " --gltf " + alias);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("are the same file"), std::string::npos) << r.out;
  EXPECT_EQ(Read(page), "old page\n");
  const std::string grid = Dir() + "/twice.csv";
  r = Mechkin("bench --quick " + in + " --csv " + grid + " --svg " + Dir() + "/./twice.csv");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("are the same file"), std::string::npos) << r.out;
  EXPECT_FALSE(Exists(grid));
}

// The destination is opened before the work: an unwritable path fails at once
// (the 200,000-sample sweep and Monte-Carlo would take minutes; the bound is a sanity bound).
TEST(OutputSafety, UnwritableReportPathsFailBeforeTheWork) {
  const std::string in = CopyOf("parametric-slider-crank.json", "unwritable.json");
  for (const std::string& args : {"sweep " + in + " --samples 200000 -o /nonexistent-dir/s.csv",
                                  "tolerance " + in + " --monte-carlo 200000 -o /nonexistent-dir/t.txt",
                                  "view " + in + " -o " + Dir() + "/ok.html --gltf /nonexistent-dir/v.glb",
                                  "bench " + in + " --csv /nonexistent-dir/b.csv"}) {
    const auto t0 = std::chrono::steady_clock::now();
    const Result r = Mechkin(args);
    EXPECT_EQ(r.code, 1) << args << "\n" << r.out;
    EXPECT_NE(r.out.find("cannot create"), std::string::npos) << args << "\n" << r.out;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0) << args;
  }
  EXPECT_FALSE(Exists(Dir() + "/ok.html")) << "the page is not written when the glTF cannot be";
}

}  // namespace
