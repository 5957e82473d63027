// `mechkin check` for many files and for CI (issue 31): one JSON line per file
// (`--format jsonl`, appended and synced line by line with `-o`, read back by
// `--resume`), SARIF 2.1.0 (`--format sarif`, what code-review tools annotate
// from) and compiler-style lines (`--format gcc`: `file:line:col: error: ...`).
// All from the typed FileCheck (analysis/check_file.hpp).
#pragma once

#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "analysis/check_file.hpp"

namespace mechkin {

/// One line (no newline) of `--format jsonl`: the file's object of `--format json`
/// plus "verdict", and "line"/"column" on every located error, warning and expect.
std::string CheckLineJsonText(const FileCheck& check);
/// The SARIF 2.1.0 log of the checked files (in the given order).
std::string CheckSarifText(const std::vector<FileCheck>& checks);
/// `--format gcc`: one line per error, warning and failed expect (`file:line:col:
/// error: message`, a fix as a `note:` line); nothing for a clean file.
void PrintGccDiagnostics(const FileCheck& check, std::ostream& out);

/// What an output of `--format jsonl` already holds (`check --resume`).
struct CheckLines {
  std::map<std::string, CheckVerdict> verdicts;  // file → verdict, per complete line
  size_t complete_bytes = 0;  // up to the last newline (a line cut short by a kill is dropped)
};
/// Reads `path` (a missing file holds nothing); false with *error naming the line
/// when a complete line is not a check result.
bool ReadCheckLines(const std::string& path, CheckLines* lines, std::string* error);

/// An output opened for appending lines, each written whole and synced (fsync) to the
/// disk, so a killed run loses no line written. The writes happen on a thread of their
/// own (the checks do not wait for the disk); the lines queued while one sync runs are
/// written together and synced by the next (one fsync for them all).
class SyncedLines {
 public:
  SyncedLines() = default;
  SyncedLines(const SyncedLines&) = delete;
  SyncedLines& operator=(const SyncedLines&) = delete;
  ~SyncedLines();
  /// Opens (creates) `path`, keeping its first `keep_bytes` bytes (the rest is cut).
  bool Open(const std::string& path, size_t keep_bytes, std::string* error);
  /// Queues `line` (a newline is added); false with *error once a write has failed.
  bool Append(std::string line, std::string* error);
  /// Waits until every queued line is written and synced; false with *error otherwise.
  bool Close(std::string* error);

 private:
  void Work();
  bool WriteAndSync(const std::string& whole);

  int fd_ = -1;
  std::mutex mutex_;
  std::condition_variable ready_, room_;
  std::deque<std::string> queue_;
  bool closing_ = false, failed_ = false;
  std::string error_;
  std::thread worker_;
};

}  // namespace mechkin
