// Where tables go: atomic replacement, refusing the input, write-through to
// devices and FIFOs, symlinks kept, failed writes reported, partial marks.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "io/async_sink.hpp"
#include "io/output_file.hpp"
#include "io/table_writer.hpp"

namespace mechkin {
namespace output_file_test {

std::string Dir() {
  static std::string d = [] {
    std::string t = ::testing::TempDir() + "/mechkin-io-XXXXXX";
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

int FilesIn(const std::string& dir) {
  int n = 0;
  for (FILE* p = ::popen(("ls -A '" + dir + "'").c_str(), "r"); p;) {
    char line[512];
    while (std::fgets(line, sizeof line, p)) ++n;
    ::pclose(p);
    break;
  }
  return n;
}

TEST(OutputFile, ReplacesTheTargetOnlyOnCommit) {
  const std::string dir = Dir() + "/commit";
  ::mkdir(dir.c_str(), 0755);
  const std::string path = dir + "/table.csv";
  std::ofstream(path) << "old\n";
  ::chmod(path.c_str(), 0640);
  OutputFile f;
  std::string why;
  ASSERT_TRUE(f.Open(path, {}, &why)) << why;
  f.Write("new\n");
  EXPECT_EQ(Read(path), "old\n");  // untouched until the commit
  EXPECT_EQ(FilesIn(dir), 2);      // the target and one hidden temporary
  ASSERT_TRUE(f.Commit("", &why)) << why;
  EXPECT_EQ(Read(path), "new\n");
  struct stat st {};
  ::stat(path.c_str(), &st);
  EXPECT_EQ(st.st_mode & 0777, 0640u);  // the target's mode is kept
  EXPECT_EQ(FilesIn(dir), 1);
}

TEST(OutputFile, AbortLeavesTheOldContentAndNoTemporary) {
  const std::string dir = Dir() + "/abort";
  ::mkdir(dir.c_str(), 0755);
  const std::string path = dir + "/t.csv";
  std::ofstream(path) << "old\n";
  {
    OutputFile f;
    std::string why;
    ASSERT_TRUE(f.Open(path, {}, &why));
    f.Write("half");
  }  // destroyed without a commit (a failed or interrupted run)
  EXPECT_EQ(Read(path), "old\n");
  EXPECT_EQ(FilesIn(dir), 1);
}

TEST(OutputFile, RefusesToOverwriteAnInput) {
  const std::string path = Dir() + "/input.json";
  std::ofstream(path) << "{}";
  OutputFile f;
  std::string why;
  EXPECT_FALSE(f.Open(Dir() + "/./input.json", {path}, &why));
  EXPECT_NE(why.find("input"), std::string::npos) << why;
  EXPECT_EQ(Read(path), "{}");
}

TEST(OutputFile, WritesThroughASymlinkAndKeepsTheLink) {
  const std::string target = Dir() + "/real.csv", link = Dir() + "/link.csv";
  std::ofstream(target) << "old";
  ::unlink(link.c_str());
  ASSERT_EQ(::symlink(target.c_str(), link.c_str()), 0);
  OutputFile f;
  std::string why;
  ASSERT_TRUE(f.Open(link, {}, &why));
  f.Write("new");
  ASSERT_TRUE(f.Commit("", &why)) << why;
  struct stat st {};
  ASSERT_EQ(::lstat(link.c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  EXPECT_EQ(Read(target), "new");
}

TEST(OutputFile, WritesToCharacterDevicesDirectly) {
  OutputFile f;
  std::string why;
  ASSERT_TRUE(f.Open("/dev/null", {}, &why)) << why;
  f.Write("x");
  ASSERT_TRUE(f.Commit("", &why)) << why;
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));  // still the device
}

TEST(OutputFile, AFullDeviceIsAFailureWithTheErrnoText) {
  OutputFile f;
  std::string why;
  ASSERT_TRUE(f.Open("/dev/full", {}, &why)) << why;
  std::string big(1 << 17, 'x');  // larger than the buffer: written at once
  f.Write(big);
  EXPECT_FALSE(f.Commit("", &why));
  EXPECT_NE(why.find("No space left"), std::string::npos) << why;
}

TEST(OutputFile, RefusesADirectory) {
  OutputFile f;
  std::string why;
  EXPECT_FALSE(f.Open(Dir(), {}, &why));
  EXPECT_NE(why.find("directory"), std::string::npos);
}

TEST(OutputFile, PartialNoteLeadsTheFileAndTheStream) {
  const std::string path = Dir() + "/partial.csv";
  OutputFile f;
  std::string why;
  ASSERT_TRUE(f.Open(path, {}, &why));
  f.Write("t [s]\n0\n");
  ASSERT_TRUE(f.Commit("# PARTIAL TABLE: stopped\n", &why)) << why;
  EXPECT_EQ(Read(path), "# PARTIAL TABLE: stopped\nt [s]\n0\n");
  std::ostringstream out;
  OutputFile g;
  ASSERT_TRUE(g.Open("", {}, &why, &out));
  g.Write("rows\n");
  ASSERT_TRUE(g.Commit("# note\n", &why));
  EXPECT_EQ(out.str(), "# note\nrows\n");
}

TEST(TableWriter, ShortestRoundTripNumbersAndEscapedNames) {
  EXPECT_EQ(CsvCell("a,b"), "\"a,b\"");
  EXPECT_EQ(CsvCell("say \"x\""), "\"say \"\"x\"\"\"");
  EXPECT_EQ(XmlEscape("</text><script>"), "&lt;/text&gt;&lt;script&gt;");
  EXPECT_EQ(JsonEscape("a\"b\\\n"), "a\\\"b\\\\\\n");
}

// A sink that records rows, to check that the writer thread keeps their order.
struct Recorder : RowSink {
  std::vector<double> seen;
  bool Append(const double* row, int size) override {
    seen.insert(seen.end(), row, row + size);
    return true;
  }
};

TEST(AsyncRowSink, DeliversEveryRowInOrder) {
  Recorder rec;
  {
    AsyncRowSink sink(&rec, 3, 7, 2);  // small chunks: many hand-overs
    for (int r = 0; r < 1000; ++r) {
      const double row[3] = {double(r), r + 0.5, -double(r)};
      ASSERT_TRUE(sink.Append(row, 3));
    }
    ASSERT_TRUE(sink.Drain());
  }
  ASSERT_EQ(rec.seen.size(), 3000u);
  for (int r = 0; r < 1000; ++r) EXPECT_EQ(rec.seen[3 * r + 1], r + 0.5);
}

}  // namespace
}  // namespace mechkin
