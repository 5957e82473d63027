#include "io/output_file.hpp"

#include "io/interrupt.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace mechkin {
namespace {

constexpr size_t kBufferSize = 1 << 16;

bool WriteAll(int fd, const char* data, size_t size, int* err) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      *err = errno;
      return false;
    }
    data += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

std::string RealPath(const std::string& p) {
  char buf[PATH_MAX];
  return ::realpath(p.c_str(), buf) ? std::string(buf) : std::string();
}

std::string DirectoryOf(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string BaseOf(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// A file's identity: its device and inode when it exists, and its canonical path
// (the real folder plus the name when the file does not exist yet).
struct FileIdentity {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::string canonical;
};

FileIdentity IdentityOf(const std::string& path) {
  FileIdentity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.device = st.st_dev;
    id.inode = st.st_ino;
  }
  id.canonical = RealPath(path);
  if (id.canonical.empty()) {
    const std::string folder = RealPath(DirectoryOf(path));
    id.canonical = folder.empty() ? path : folder + "/" + BaseOf(path);
  }
  return id;
}

bool IsInput(const std::string& target, const std::string& input) {
  struct stat t {}, in {};
  return ::stat(target.c_str(), &t) == 0 && ::stat(input.c_str(), &in) == 0 && t.st_dev == in.st_dev &&
         t.st_ino == in.st_ino;
}

}  // namespace

bool SameFile(const std::string& a, const std::string& b) {
  const FileIdentity x = IdentityOf(a), y = IdentityOf(b);
  if (x.exists && y.exists) return x.device == y.device && x.inode == y.inode;
  return x.canonical == y.canonical;
}

bool DistinctOutputs(const std::vector<std::string>& paths, const std::vector<std::string>& options, std::string* error) {
  for (size_t i = 0; i < paths.size(); ++i)
    for (size_t k = i + 1; k < paths.size(); ++k) {
      if (paths[i].empty() || paths[i] == "-" || paths[k].empty() || paths[k] == "-") continue;
      if (!SameFile(paths[i], paths[k])) continue;
      *error = options[i] + " '" + paths[i] + "' and " + options[k] + " '" + paths[k] +
               "' are the same file: one would overwrite the other; give two different paths";
      return false;
    }
  return true;
}

OutputFile::~OutputFile() { Abort(); }

bool OutputFile::Open(const std::string& path, const std::vector<std::string>& inputs, std::string* error,
                      std::ostream* standard_output, const std::string& what) {
  buffer_.reserve(kBufferSize);
  if (path.empty() || path == "-") {
    to_stdout_ = true;
    stream_ = standard_output;
    FILE* f = std::tmpfile();
    fd_ = f ? ::dup(::fileno(f)) : -1;
    if (f) std::fclose(f);
    if (fd_ < 0) { *error = std::string("cannot create a temporary file: ") + std::strerror(errno); return false; }
    return true;
  }
  const std::string real = RealPath(path);
  for (const auto& in : inputs)
    if (!in.empty() && in != "-" && IsInput(path, in)) {
      *error = "refusing to write " + what + " onto the input file '" + in + "': choose another output path";
      return false;
    }
  struct stat st {};
  target_ = real.empty() ? path : real;  // follow a symlink to the real target; the link stays
  if (::stat(target_.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) { *error = "'" + path + "' is a directory: give a file name"; return false; }
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
      direct_ = true;
      fd_ = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC);
      if (fd_ < 0) { *error = "cannot write '" + path + "': " + std::strerror(errno); return false; }
      return true;
    }
    if (!S_ISREG(st.st_mode)) { *error = "'" + path + "' is not a regular file, a character device or a FIFO"; return false; }
    mode_ = st.st_mode & 07777;
  } else {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    mode_ = 0666 & ~mask;
  }
  // ".<name>.XXXXXX" in the target's directory, shortened so it fits NAME_MAX.
  std::string base = BaseOf(target_).substr(0, 200);
  std::string tmpl = DirectoryOf(target_) + "/." + base + ".XXXXXX";
  std::vector<char> name(tmpl.begin(), tmpl.end());
  name.push_back('\0');
  fd_ = ::mkstemp(name.data());
  if (fd_ < 0) { *error = "cannot create a file next to '" + path + "': " + std::strerror(errno); return false; }
  tmp_path_ = name.data();
  RegisterTemporaryFile(tmp_path_.c_str());
  ::fchmod(fd_, mode_);
  return true;
}

bool OutputFile::Flush() {
  if (!failed_ && !buffer_.empty() && !WriteAll(fd_, buffer_.data(), buffer_.size(), &write_errno_)) failed_ = true;
  buffer_.clear();
  return !failed_;
}

bool OutputFile::Write(const char* data, size_t size) {
  if (failed_ || fd_ < 0) return false;
  if (buffer_.size() + size > kBufferSize && !Flush()) return false;
  if (size >= kBufferSize) {
    if (!WriteAll(fd_, data, size, &write_errno_)) failed_ = true;
    return !failed_;
  }
  buffer_.insert(buffer_.end(), data, data + size);
  return true;
}

// The temporary file's content from its start, chunk by chunk, to `sink` (which
// returns false, having set *error, to stop).
bool OutputFile::ReadBack(const std::function<bool(const char*, size_t)>& sink, std::string* error) {
  if (::lseek(fd_, 0, SEEK_SET) < 0) { *error = std::strerror(errno); return false; }
  std::vector<char> chunk(kBufferSize);
  for (;;) {
    const ssize_t n = ::read(fd_, chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) { *error = std::strerror(errno); return false; }
    if (n == 0) return true;
    if (!sink(chunk.data(), static_cast<size_t>(n))) return false;
  }
}

// Writes `first_line` and then the temporary file's content to `fd`.
bool OutputFile::CopyTo(int fd, const std::string& first_line, std::string* error) {
  int err = 0;
  if (!first_line.empty() && !WriteAll(fd, first_line.data(), first_line.size(), &err)) {
    *error = std::strerror(err);
    return false;
  }
  return ReadBack(
      [&](const char* data, size_t n) {
        if (WriteAll(fd, data, n, &err)) return true;
        *error = std::strerror(err);
        return false;
      },
      error);
}

bool OutputFile::CopyToStream(const std::string& first_line, std::string* error) {
  std::ostream& out = *stream_;
  out << first_line;
  if (!ReadBack([&](const char* data, size_t n) { out.write(data, static_cast<std::streamsize>(n)); return true; }, error))
    return false;
  out.flush();
  if (!out) { *error = std::strerror(errno ? errno : EIO); return false; }
  return true;
}

bool OutputFile::Commit(const std::string& first_line, std::string* error) {
  const std::string where = to_stdout_ ? "the standard output" : "'" + target_ + "'";
  if (!Flush()) { *error = "write to " + where + " failed: " + std::strerror(write_errno_); Abort(); return false; }
  if (direct_) {
    committed_ = true;
    const bool ok = ::close(fd_) == 0;
    fd_ = -1;
    if (!ok) *error = "closing " + where + " failed: " + std::strerror(errno);
    return ok;
  }
  if (to_stdout_) {
    const bool ok = stream_ ? CopyToStream(first_line, error) : CopyTo(1, first_line, error);
    if (!ok) *error = "write to the standard output failed: " + *error;
    Abort();
    committed_ = true;
    return ok;
  }
  if (!first_line.empty()) {
    // Rare (a partial table): rewrite with the note in front.
    OutputFile with_note;
    if (!with_note.Open(target_, {}, error) || !CopyTo(with_note.fd_, first_line, error)) {
      *error = "write to " + where + " failed: " + *error;
      Abort();
      return false;
    }
    Abort();
    return with_note.Commit("", error);
  }
  if (::close(fd_) != 0) {
    fd_ = -1;
    *error = "write to " + where + " failed: " + std::strerror(errno);
    Abort();
    return false;
  }
  fd_ = -1;
  if (::rename(tmp_path_.c_str(), target_.c_str()) != 0) {
    *error = "cannot rename the finished table onto " + where + ": " + std::strerror(errno);
    Abort();
    return false;
  }
  UnregisterTemporaryFile(tmp_path_.c_str());
  tmp_path_.clear();
  committed_ = true;
  return true;
}

void OutputFile::Abort() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!tmp_path_.empty()) {
    ::unlink(tmp_path_.c_str());
    UnregisterTemporaryFile(tmp_path_.c_str());
  }
  tmp_path_.clear();
}

}  // namespace mechkin

namespace mechkin {

bool WriteFileAtomically(const std::string& path, const std::string& content, std::string* error) {
  OutputFile file;
  if (!file.Open(path, {}, error)) return false;
  file.Write(content);
  return file.Commit("", error);
}

}  // namespace mechkin
