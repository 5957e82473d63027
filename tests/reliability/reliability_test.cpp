// Hardening (issue: never crash, never lose a byte, never write where it must
// not): every finding is a test here, run against the real executable.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "test_files.hpp"

namespace reliability_test {

using nlohmann::json;
const std::string kBin = MECHKIN_BINARY;

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
    std::string t = ::testing::TempDir() + "/mechkin-rel-XXXXXX";
    return std::string(::mkdtemp(t.data()));
  }();
  return d;
}

std::string Write(const std::string& name, const std::string& text) {
  const std::string p = Dir() + "/" + name;
  std::ofstream(p) << text;
  return p;
}

std::string Read(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

json SliderCrank() { return mechkin::testing_files::ReadJson("spatial-slider-crank.json"); }

std::string Source(const std::string& name) { return std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/" + name; }

TEST(Crashes, HugeCoordinateIsRefusedAndOtherFilesStillReported) {
  json j = SliderCrank();
  j["bodies"][1]["position"][0] = 1e155;
  const std::string bad = Write("huge.json", j.dump());
  const Result r = Mechkin("check " + bad + " " + Source("planar-four-bar.json"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("/bodies/1/position/0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("beyond 1e12 m"), std::string::npos);
  EXPECT_NE(r.out.find("planar four-bar"), std::string::npos) << "the good file's report is there";
}

TEST(Crashes, LongExpressionsAreEvaluatedOrRefusedNeverCrash) {
  json j = SliderCrank();
  std::string f = "360*t";
  for (int k = 0; k < 5000; ++k) f += "+0*t";
  j["drivers"][0]["function"] = f;  // 20 KB: accepted, evaluated without recursion
  j["analysis"]["steps"] = 10;
  EXPECT_EQ(Mechkin("run " + Write("long.json", j.dump()) + " -o " + Dir() + "/long.csv").code, 0);
  std::string huge = "360*t";
  while (huge.size() < 500000) huge += "+0*t";
  j["drivers"][0]["function"] = huge;
  const Result r = Mechkin("check " + Write("huge-expr.json", j.dump()));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("longer than 65536 characters"), std::string::npos) << r.out.substr(0, 400);
}

TEST(Crashes, NestingLimitIsStated) {
  json j = SliderCrank();
  j["drivers"][0]["function"] = std::string(64, '(') + "360*t" + std::string(64, ')');
  EXPECT_EQ(Mechkin("check " + Write("nest64.json", j.dump())).code, 0);
  j["drivers"][0]["function"] = std::string(70, '(') + "360*t" + std::string(70, ')');
  const Result r = Mechkin("check " + Write("nest70.json", j.dump()));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("at most 64 levels"), std::string::npos) << r.out;
}

TEST(Crashes, NonAsciiTextIsNamedAndJsonStaysValid) {
  json j = SliderCrank();
  j["drivers"][0]["function"] = "\xe2\x88\x92" "360*t";  // Unicode minus
  const Result r = Mechkin("check " + Write("minus.json", j.dump()));
  EXPECT_NE(r.out.find("U+2212"), std::string::npos) << r.out;
  // A bad byte in a name: the JSON report must still parse.
  std::string text = SliderCrank().dump();
  text.replace(text.find("\"crank\""), 7, "\"cr\xff" "nk\"");
  const Result rj = Mechkin("check --format json " + Write("badbyte.json", text));
  EXPECT_EQ(rj.code, 1);
  json parsed;
  EXPECT_NO_THROW(parsed = json::parse(rj.out)) << rj.out;
}

TEST(Writes, OutputOntoTheInputIsRefused) {
  const std::string in = Write("self.json", SliderCrank().dump());
  const Result r = Mechkin("run " + in + " -o " + in);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("onto the input"), std::string::npos) << r.out;
  EXPECT_EQ(json::parse(Read(in)), SliderCrank());
}

TEST(Writes, DevNullStaysADevice) {
  EXPECT_EQ(Mechkin("run " + Source("planar-four-bar.json") + " -o /dev/null").code, 0);
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(Writes, AFullDeviceIsExit1WithTheReason) {
  const Result run = Mechkin("run " + Source("planar-four-bar.json") + " -o /dev/full");
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find("No space left"), std::string::npos) << run.out;
  EXPECT_EQ(Mechkin("check " + Source("planar-four-bar.json") + " > /dev/full").code, 1);
  EXPECT_EQ(Mechkin("run " + Source("planar-four-bar.json") + " > /dev/full").code, 1);
}

TEST(Writes, AFullFilesystemLeavesTheOldFileAndNoTemporary) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to mount a tmpfs";
  const std::string dir = Dir() + "/small";
  ::mkdir(dir.c_str(), 0755);
  if (::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=64k") != 0) GTEST_SKIP() << "cannot mount a tmpfs here";
  std::ofstream(dir + "/t.csv") << "old\n";
  const Result r = Mechkin("run " + Source("spatial-slider-crank.json") + " -o " + dir + "/t.csv");
  const std::string after = Read(dir + "/t.csv");
  
  FILE* p = ::popen(("ls -A " + dir).c_str(), "r");
  char buf[256];
  std::string listing;
  while (std::fgets(buf, sizeof buf, p)) listing += buf;
  ::pclose(p);
  ::umount(dir.c_str());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("No space left"), std::string::npos) << r.out;
  EXPECT_EQ(after, "old\n");
  EXPECT_EQ(listing, "t.csv\n");
}

TEST(Writes, UnwritablePathFailsBeforeTheAnalysis) {
  json j = SliderCrank();
  j["analysis"]["steps"] = 2000000;
  const auto t0 = std::chrono::steady_clock::now();
  const Result r = Mechkin("run " + Write("long-run.json", j.dump()) + " -o /nonexistent-dir/x.csv");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("cannot create"), std::string::npos) << r.out;
  // Sanity bound only (the run itself would take seconds): it never started.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
}

// Runs `args` in a child, sends `sig` after `ms`, returns the exit code (128+sig when killed).
int RunAndSignal(const std::vector<std::string>& args, int sig, int ms) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(kBin.c_str()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 2);
    ::execv(kBin.c_str(), argv.data());
    ::_exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
  ::kill(pid, sig);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int FilesIn(const std::string& dir) {
  FILE* p = ::popen(("ls -A " + dir + " | wc -l").c_str(), "r");
  int n = 0;
  if (std::fscanf(p, "%d", &n) != 1) n = -1;
  ::pclose(p);
  return n;
}

TEST(Signals, SigtermRemovesTheTemporaryAndKeepsTheOldTable) {
  json j = SliderCrank();
  j["analysis"]["steps"] = 3000000;
  const std::string in = Write("sig.json", j.dump());
  const std::string dir = Dir() + "/sig";
  ::mkdir(dir.c_str(), 0755);
  std::ofstream(dir + "/t.csv") << "old\n";
  EXPECT_EQ(RunAndSignal({"run", in, "-o", dir + "/t.csv"}, SIGTERM, 400), 128 + SIGTERM);
  EXPECT_EQ(Read(dir + "/t.csv"), "old\n");
  EXPECT_EQ(FilesIn(dir), 1);
}

TEST(Signals, SigintWithKeepPartialWritesAPartialTable) {
  json j = SliderCrank();
  j["analysis"]["steps"] = 3000000;
  const std::string in = Write("sigint.json", j.dump());
  const std::string out = Dir() + "/partial.csv";
  EXPECT_EQ(RunAndSignal({"run", in, "-o", out, "--keep-partial"}, SIGINT, 400), 130);
  const std::string text = Read(out);
  EXPECT_EQ(text.rfind("# PARTIAL TABLE: interrupted (SIGINT)\nt [s],", 0), 0u) << text.substr(0, 200);
  EXPECT_GT(std::count(text.begin(), text.end(), '\n'), 10);
}

TEST(Escaping, BenchPlotEscapesTheModelName) {
  json j = mechkin::testing_files::ReadJson("planar-four-bar.json");
  j["name"] = "</text><script>alert(1)</script>";
  j["analysis"]["steps"] = 24;
  const std::string svg = Dir() + "/front.svg";
  const Result r = Mechkin("bench " + Write("evil.json", j.dump()) + " --quick --repeats 1 --csv " + Dir() + "/g.csv --svg " + svg);
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string text = Read(svg);
  EXPECT_EQ(text.find("<script>"), std::string::npos);
  EXPECT_NE(text.find("&lt;/text&gt;&lt;script&gt;"), std::string::npos);
}

TEST(Inputs, DirectoriesDevicesPipesAndStdin) {
  Result r = Mechkin("check " + Dir());
  EXPECT_NE(r.out.find("is a directory"), std::string::npos) << r.out;
  r = Mechkin("check /dev/zero");
  EXPECT_NE(r.out.find("is a device"), std::string::npos) << r.out;
  r = Mechkin("check - < " + Source("planar-four-bar.json"));
  EXPECT_EQ(r.code, 0) << r.out;
  r = Mechkin("check /dev/stdin < " + Source("planar-four-bar.json"));  // a pipe or file descriptor path
  EXPECT_EQ(r.code, 0) << r.out;
}

TEST(Limits, FarStartTimesAssembleAtOnce) {
  json j = SliderCrank();
  j["analysis"] = {{"start", 1e5}, {"end", 1e5 + 1}, {"steps", 36}};  // the crank at 3.6e7 deg
  const std::string out = Dir() + "/far.csv";
  const Result r = Mechkin("run " + Write("far.json", j.dump()) + " -o " + out);
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string text = Read(out);
  const auto header = text.substr(0, text.find('\n'));
  EXPECT_NE(text.find("\n1e+05,"), std::string::npos) << text.substr(0, 300);  // shortest round-trip form
  j["analysis"] = {{"start", 1e8}, {"end", 1e8 + 1}, {"steps", 36}};  // 3.6e10 deg: no int overflow
  EXPECT_EQ(Mechkin("run " + Write("farther.json", j.dump()) + " -o " + Dir() + "/farther.csv").code, 0);
}

TEST(Limits, UndefinedDriverFunctionsAreNamedByCheckAndRefusedByRun) {
  for (const char* f : {"360*sqrt(t)", "log(t)", "1/t", "asin(2*t-1)", "(1e10*t)^64", "exp(1000*t)"}) {
    json j = SliderCrank();
    j["drivers"][0]["function"] = f;
    const std::string path = Write("undefined.json", j.dump());
    const Result c = Mechkin("check " + path);
    EXPECT_EQ(c.code, 1) << f;
    EXPECT_NE(c.out.find("/drivers/0/function"), std::string::npos) << f << c.out;
    const Result r = Mechkin("run " + path + " -o " + Dir() + "/u.csv");
    EXPECT_EQ(r.code, 1) << f;
    EXPECT_EQ(r.out.find("internal error"), std::string::npos) << f << r.out;
  }
}

TEST(Limits, TablesWithTwoRowsAndOvershootWarnings) {
  json j = SliderCrank();
  j["drivers"][0]["function"] = {{"table", {{0, 0}, {1, 360}}}};
  const std::string two = Dir() + "/two.csv";
  ASSERT_EQ(Mechkin("run " + Write("two.json", j.dump()) + " --outputs crank_angle --bodies '' -o " + two).code, 0);
  EXPECT_NE(Read(two).find("\n0.5,180,360,"), std::string::npos) << Read(two).substr(0, 300);
  j["drivers"][0]["function"] = {{"table", {{0, 0}, {0.2, 0}, {0.4, 0}, {0.5, 90}, {0.6, 90}, {0.8, 90}, {1, 90}}}};
  const Result r = Mechkin("check " + Write("stairs.json", j.dump()));
  EXPECT_NE(r.out.find("overshoots the data"), std::string::npos) << r.out;
  j["drivers"][0]["function"]["interpolation"] = "linear";
  EXPECT_EQ(Mechkin("check " + Write("stairs-linear.json", j.dump())).out.find("overshoots"), std::string::npos);
}

TEST(Smaller, ReservedNamesFarPointsDuplicateKeysAndLongLists) {
  json j = SliderCrank();
  j["outputs"][0]["name"] = "residual";
  EXPECT_NE(Mechkin("check " + Write("reserved.json", j.dump())).out.find("built-in table column"), std::string::npos);
  j = SliderCrank();
  j["bodies"][2]["position"][0] = 1e7;
  EXPECT_NE(Mechkin("check " + Write("farpoint.json", j.dump())).out.find("farther from the middle"), std::string::npos);
  std::string text = SliderCrank().dump();
  text.insert(text.find("\"name\":\"crank\"") + 1 + std::string("\"name\":\"crank\"").size() - 1, ",\"name\":\"crank\"");
  EXPECT_NE(Mechkin("check " + Write("dupkey.json", text)).out.find("appears more than once"), std::string::npos);
  // 3000 misspelled references among 3000 bodies: messages stay short.
  json big = {{"mechkin", 1}, {"bodies", json::array()}, {"joints", json::array()}};
  for (int b = 0; b < 3000; ++b) {
    big["bodies"].push_back({{"name", "b" + std::to_string(b)}, {"position", {b, 0, 0}}});
    big["joints"].push_back({{"name", "j" + std::to_string(b)}, {"type", "spherical"}, {"body1", "ground"},
                             {"body2", "x" + std::to_string(b)}, {"origin", {b, 0, 0}}});
  }
  const Result r = Mechkin("check " + Write("many.json", big.dump()));
  EXPECT_EQ(r.code, 1);
  EXPECT_LT(r.out.size(), 3000u * 400) << "the candidate lists are capped";
  EXPECT_NE(r.out.find("in all)"), std::string::npos);
}

TEST(Smaller, TolNanIsAnArgumentError) {
  const Result r = Mechkin("run " + Source("planar-four-bar.json") + " --tol nan");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("[1e-15, 1e-3]"), std::string::npos) << r.out;
}

TEST(Smaller, BenchReferenceIsValidated) {
  const std::string mm = Dir() + "/mm.csv";
  ASSERT_EQ(Mechkin("run " + Source("planar-four-bar.json") + " -o " + mm).code, 0);  // file units, not SI
  const Result a = Mechkin("bench " + Source("planar-four-bar.json") + " --quick --reference " + mm + " --csv " + Dir() +
                       "/g.csv --svg " + Dir() + "/f.svg");
  EXPECT_EQ(a.code, 1);
  EXPECT_NE(a.out.find("not in SI units"), std::string::npos) << a.out;
  const std::string junk = Write("junk.csv", "t [s],x [m]\n0,abc\n");
  const Result b = Mechkin("bench " + Source("planar-four-bar.json") + " --quick --reference " + junk + " --csv " + Dir() +
                       "/g.csv --svg " + Dir() + "/f.svg");
  EXPECT_EQ(b.code, 1);
  EXPECT_NE(b.out.find("is not a number"), std::string::npos) << b.out;
}

}  // namespace
