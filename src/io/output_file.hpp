// Where a result goes: never half written, never in the wrong place.
//
// A regular-file target is written to an exclusively created temporary file in
// the target's own directory (mkstemp: unpredictable name, O_EXCL) and renamed
// into place only by Commit(); a symlink target is resolved first, so the link
// stays a link; the target's mode is kept. Character devices and FIFOs
// (/dev/null, a pipe) are written directly. The standard output is buffered in
// an anonymous temporary file so that a `# PARTIAL TABLE` line can still lead
// the table. Every write is checked; a failed write makes Commit() fail with
// the errno text and leaves the target untouched.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace mechkin {

class OutputFile {
 public:
  OutputFile() = default;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();  // removes the temporary file unless committed

  /// `path` empty or "-" = the stream `standard_output` (checked after flushing).
  /// `inputs`: files the target must not be (compared by device and inode, so a
  /// symlink or a hard link to an input is refused too). `what` names the content
  /// in that refusal ("the table", "the page").
  bool Open(const std::string& path, const std::vector<std::string>& inputs, std::string* error,
            std::ostream* standard_output = nullptr, const std::string& what = "the table");
  /// Buffered; false once any write has failed.
  bool Write(const char* data, size_t size);
  bool Write(const std::string& s) { return Write(s.data(), s.size()); }
  /// Moves the content into place, preceded by `first_line` when not empty.
  bool Commit(const std::string& first_line, std::string* error);
  /// Drops the temporary file (the target keeps its old content).
  void Abort();
  const std::string& temporary_path() const { return tmp_path_; }

 private:
  bool Flush();
  bool ReadBack(const std::function<bool(const char*, size_t)>& sink, std::string* error);
  bool CopyTo(int fd, const std::string& first_line, std::string* error);
  bool CopyToStream(const std::string& first_line, std::string* error);

  std::string target_, tmp_path_;
  int fd_ = -1;
  bool direct_ = false, to_stdout_ = false, failed_ = false, committed_ = false;
  int write_errno_ = 0;
  unsigned mode_ = 0644;
  std::vector<char> buffer_;
  std::ostream* stream_ = nullptr;
};

}  // namespace mechkin

namespace mechkin {
/// Writes `content` to `path` through OutputFile (never half written).
bool WriteFileAtomically(const std::string& path, const std::string& content, std::string* error);
/// True when `a` and `b` name one file: the same inode when both exist, else the
/// same canonical path (a file not yet written, reached through a linked folder).
bool SameFile(const std::string& a, const std::string& b);
/// The destinations of one command must be distinct files: false (and *error naming
/// the two options) when two are one. `paths[i]` is given by option `options[i]`;
/// empty paths and "-" (the standard output) are skipped.
bool DistinctOutputs(const std::vector<std::string>& paths, const std::vector<std::string>& options, std::string* error);
}  // namespace mechkin
