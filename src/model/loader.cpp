#include "model/loader.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "spec/reader.hpp"

namespace mechkin {

namespace {

// Reads all of `fd` up to the size limit. A stream that stays silent longer
// than `timeout_ms` (a FIFO with no writer, a terminal) is given up on.
bool ReadStream(int fd, std::string* text, std::string* why, int timeout_ms) {
  char buf[1 << 16];
  for (;;) {
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, timeout_ms);
    if (ready == 0) { *why = "nothing arrived for " + std::to_string(timeout_ms / 1000) + " s"; return false; }
    if (ready < 0 && errno == EINTR) continue;
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) { *why = std::strerror(errno); return false; }
    if (n == 0) return true;
    if (text->size() + static_cast<size_t>(n) > kMaxFileBytes) { *why = "larger than 256 MiB"; return false; }
    text->append(buf, static_cast<size_t>(n));
  }
}

}  // namespace

// The reader's and compile's diagnostics merge into the file's order.
LoadResult LoadTextUnassembled(const std::string& text, const std::string& source_name,
                             const ParameterOverrides& overrides) {
  LoadResult result;
  SpecReadResult read = ReadMechanismSpec(text, source_name);
  DiagnosticLog compiled;
  if (read.spec) {
    result.model = CompileModel(std::make_shared<const MechanismSpec>(std::move(*read.spec)), overrides, &compiled);
  }
  DiagnosticLog::Merge(read.diagnostics, compiled, &result.errors, &result.warnings);
  if (!result.errors.empty()) result.model.reset();
  return result;
}

LoadResult WithParametersUnassembled(const Model& model, const ParameterOverrides& overrides) {
  if (!model.spec) {
    LoadResult result;
    result.errors.push_back({"", "this model was not compiled from a spec", "load it with LoadMechanismFile"});
    return result;
  }
  ParameterOverrides merged;
  for (const auto& p : model.parameters)
    if (p.overridden) merged[p.name] = p.value;
  for (const auto& kv : overrides) merged[kv.first] = kv.second;
  return Compile(model.spec, merged, model.expressions);
}

bool ReadMechanismFileText(const std::string& path, std::string* text, Diagnostic* error) {
  auto fail = [&](const std::string& msg, const std::string& fix) {
    *error = Diagnostic{"", msg, fix};
    return false;
  };
  const bool standard_input = path == "-";
  struct stat st {};
  if (!standard_input && ::stat(path.c_str(), &st) != 0)
    return fail("cannot open '" + path + "': " + std::strerror(errno), "check the path and permissions");
  if (!standard_input && S_ISDIR(st.st_mode))
    return fail("'" + path + "' is a directory", "give a mechanism JSON file inside it");
  if (!standard_input && (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) || S_ISSOCK(st.st_mode)))
    return fail("'" + path + "' is a device, not a file", "give a mechanism JSON file");
  if (!standard_input && S_ISREG(st.st_mode) && static_cast<std::size_t>(st.st_size) > kMaxFileBytes)
    return fail("file is larger than 256 MiB", "a mechanism file is a few kilobytes; check the path");
  // Pipes, FIFOs and the standard input are read as streams, with a time-out.
  const int fd = standard_input ? 0 : ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return fail("cannot open '" + path + "': " + std::strerror(errno), "check the path and permissions");
  if (!standard_input) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  std::string why;
  const bool ok = ReadStream(fd, text, &why, 10000);
  if (!standard_input) ::close(fd);
  if (!ok) return fail("cannot read '" + path + "': " + why, "give a complete mechanism JSON file");
  return true;
}

LoadResult LoadFileUnassembled(const std::string& path, const ParameterOverrides& overrides) {
  std::string text;
  Diagnostic error;
  if (!ReadMechanismFileText(path, &text, &error)) {
    LoadResult result;
    result.errors.push_back(error);
    return result;
  }
  return LoadTextUnassembled(text, MechanismSourceName(path), overrides);
}

std::string MechanismSourceName(const std::string& path) { return path == "-" ? "<stdin>" : path; }

}  // namespace mechkin
