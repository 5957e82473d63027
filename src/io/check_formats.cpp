#include "io/check_formats.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "analysis/enum_names.hpp"
#include "io/check_report_writer.hpp"

namespace mechkin {

namespace {

using nlohmann::json;

void AddPlaces(const std::vector<Diagnostic>& ds, json* list) {
  for (size_t k = 0; k < ds.size() && k < list->size(); ++k)
    if (ds[k].line > 0) (*list)[k]["line"] = ds[k].line, (*list)[k]["column"] = ds[k].column;
}

std::string ValueText(const ExpectValue& v) {
  switch (v.kind) {
    case ExpectValue::Kind::Count: return std::to_string(v.count);
    case ExpectValue::Kind::Word: return json(v.word).dump();
    case ExpectValue::Kind::Number: return json(v.number).dump();
    case ExpectValue::Kind::Absent: break;
  }
  return "null";
}

// "expect grubler = 4 FAILED (actual 3)", as the text report says it.
std::string FailedExpectText(const ExpectationResult& e) {
  return "expect " + e.key + " = " + ValueText(e.expected) + " FAILED (actual " + ValueText(e.actual) + ")" +
         (e.where.empty() ? "" : ": " + e.where);
}

// One finding of a file in every CI form: severity, rule, text, place.
struct Finding {
  const char* level;  // error | warning
  const char* rule;
  std::string message, fix, pointer;
  int line = 0, column = 0;
};

const char* ErrorRule(CheckVerdict v) {
  switch (v) {
    case CheckVerdict::Timeout: return "mechkin/timeout";
    case CheckVerdict::Error: return "mechkin/internal-error";
    default: return "mechkin/invalid";
  }
}

std::vector<Finding> FindingsOf(const FileCheck& c) {
  std::vector<Finding> out;
  for (const Diagnostic& d : c.report.errors)
    out.push_back({"error", ErrorRule(c.verdict), d.message, d.fix, d.pointer, d.line, d.column});
  for (const Diagnostic& d : c.report.warnings)
    out.push_back({"warning", "mechkin/warning", d.message, d.fix, d.pointer, d.line, d.column});
  for (size_t k = 0; k < c.report.expectations.size(); ++k) {
    const ExpectationResult& e = c.report.expectations[k];
    if (e.held) continue;
    const TextPosition p = k < c.expect_places.size() ? c.expect_places[k] : TextPosition{};
    out.push_back({"error", "mechkin/expect-failed", FailedExpectText(e), "", "/expect/" + e.key, p.line, p.column});
  }
  return out;
}

// A file path as a SARIF artifact URI: relative paths stay relative (to the
// repository root a code-review tool resolves them against), percent-encoded.
std::string ArtifactUri(const std::string& path) {
  static const char* kHex = "0123456789ABCDEF";
  std::string out = path.size() > 0 && path[0] == '/' ? "file://" : "";
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '/' || c == '-' || c == '_' || c == '.' || c == '~') out += static_cast<char>(c);
    else out += std::string("%") + kHex[c >> 4] + kHex[c & 15];
  }
  return out;
}

json SarifRules() {
  const std::vector<std::pair<const char*, const char*>> rules = {
      {"mechkin/invalid", "The mechanism file is not valid (format v1, docs/format.md)"},
      {"mechkin/expect-failed", "An `expect` assertion of the file does not hold"},
      {"mechkin/warning", "A problem that does not make the file invalid"},
      {"mechkin/timeout", "The check of the file overran its time limit (check --timeout)"},
      {"mechkin/internal-error", "The check itself failed: please report the file"}};
  json out = json::array();
  for (const auto& [id, text] : rules) out.push_back({{"id", id}, {"shortDescription", {{"text", text}}}});
  return out;
}

json SarifResult(const std::string& file, const Finding& f) {
  json location = {{"physicalLocation", {{"artifactLocation", {{"uri", ArtifactUri(file)}}}}}};
  if (f.line > 0) location["physicalLocation"]["region"] = {{"startLine", f.line}, {"startColumn", f.column}};
  json r = {{"ruleId", f.rule},
            {"level", f.level},
            {"message", {{"text", f.message + (f.fix.empty() ? "" : " (fix: " + f.fix + ")")}}},
            {"locations", json::array({location})}};
  if (!f.pointer.empty()) r["properties"] = {{"pointer", f.pointer}};
  return r;
}

}  // namespace

std::string CheckLineJsonText(const FileCheck& c) {
  json j = CheckReportJson(c.report);
  j["verdict"] = ToString(c.verdict);
  AddPlaces(c.report.errors, &j["errors"]);
  AddPlaces(c.report.warnings, &j["warnings"]);
  for (size_t k = 0; k < c.expect_places.size() && k < j["expect"].size(); ++k)
    if (c.expect_places[k].line > 0)
      j["expect"][k]["line"] = c.expect_places[k].line, j["expect"][k]["column"] = c.expect_places[k].column;
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string CheckSarifText(const std::vector<FileCheck>& checks) {
  json results = json::array();
  for (const FileCheck& c : checks)
    for (const Finding& f : FindingsOf(c)) results.push_back(SarifResult(c.report.file, f));
  json driver = {{"name", "mechkin"}, {"rules", SarifRules()}};
  json run = {{"tool", {{"driver", driver}}}, {"columnKind", "unicodeCodePoints"}, {"results", results}};
  json log = {{"$schema", "https://json.schemastore.org/sarif-2.1.0.json"}, {"version", "2.1.0"},
              {"runs", json::array({run})}};
  return log.dump(2, ' ', false, json::error_handler_t::replace);
}

void PrintGccDiagnostics(const FileCheck& c, std::ostream& out) {
  for (const Finding& f : FindingsOf(c)) {
    std::string place = c.report.file;
    if (f.line > 0) place += ":" + std::to_string(f.line) + ":" + std::to_string(f.column);
    out << place << ": " << f.level << ": " << (f.pointer.empty() ? "" : f.pointer + ": ") << f.message << "\n";
    if (!f.fix.empty()) out << place << ": note: fix: " << f.fix << "\n";
  }
}

bool ReadCheckLines(const std::string& path, CheckLines* lines, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return true;  // nothing written yet
  std::string line;
  size_t offset = 0, number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (in.eof()) break;  // no newline after it: cut short by a kill, dropped
    offset += line.size() + 1;
    json j = json::parse(line, nullptr, false);
    CheckVerdict v{};
    if (j.is_discarded() || !j.is_object() || !j.contains("file") || !j["file"].is_string() ||
        !j.contains("verdict") || !j["verdict"].is_string() || !Parse(j["verdict"].get<std::string>(), &v)) {
      *error = path + ":" + std::to_string(number) + ": not a line of `check --format jsonl`";
      return false;
    }
    lines->verdicts[j["file"].get<std::string>()] = v;
    lines->complete_bytes = offset;
  }
  return true;
}

SyncedLines::~SyncedLines() {
  std::string ignored;
  Close(&ignored);
}

bool SyncedLines::Open(const std::string& path, size_t keep_bytes, std::string* error) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  struct stat st {};
  const bool regular = fd_ >= 0 && ::fstat(fd_, &st) == 0 && S_ISREG(st.st_mode);
  if (fd_ < 0 || (regular && (::ftruncate(fd_, static_cast<off_t>(keep_bytes)) != 0 || ::lseek(fd_, 0, SEEK_END) < 0))) {
    *error = "cannot open '" + path + "' for writing: " + std::strerror(errno);
    return false;
  }
  worker_ = std::thread([this] { Work(); });
  return true;
}

constexpr size_t kMaxQueuedLines = 1024;  // a bound on the memory lines wait in

bool SyncedLines::Append(std::string line, std::string* error) {
  std::unique_lock<std::mutex> lock(mutex_);
  room_.wait(lock, [&] { return queue_.size() < kMaxQueuedLines || failed_; });
  if (failed_) {
    *error = error_;
    return false;
  }
  queue_.push_back(std::move(line));
  ready_.notify_one();
  return true;
}

bool SyncedLines::Close(std::string* error) {
  if (worker_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closing_ = true;
    }
    ready_.notify_one();
    worker_.join();
  }
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (failed_) *error = error_;
  return !failed_;
}

void SyncedLines::Work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    ready_.wait(lock, [&] { return !queue_.empty() || closing_; });
    if (queue_.empty()) return;
    // Every line queued while the last sync ran, in one write and one fsync (a disk's
    // sync takes 0.3-2 ms: one per line would bound the run to that rate).
    std::string lines;
    for (; !queue_.empty(); queue_.pop_front()) lines += queue_.front() + "\n";
    room_.notify_all();
    if (failed_) continue;  // drop the rest: Append reports the failure
    lock.unlock();
    const bool ok = WriteAndSync(lines);
    lock.lock();
    if (!ok) failed_ = true, room_.notify_all();
  }
}

// Whole lines in one write (continued only after a short write), then fsync.
bool SyncedLines::WriteAndSync(const std::string& whole) {
  std::string why;
  for (size_t done = 0; done < whole.size();) {
    const ssize_t n = ::write(fd_, whole.data() + done, whole.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      why = std::string("writing the output failed: ") + std::strerror(n < 0 ? errno : EIO);
      break;
    }
    done += static_cast<size_t>(n);
  }
  if (why.empty() && ::fsync(fd_) != 0 && errno != EINVAL)  // EINVAL: a pipe or device, nothing to sync
    why = std::string("syncing the output failed: ") + std::strerror(errno);
  if (why.empty()) return true;
  std::lock_guard<std::mutex> lock(mutex_);
  error_ = why;
  return false;
}

}  // namespace mechkin
