#include "analysis/check_file.hpp"

#include <chrono>
#include <map>
#include <mutex>
#include <sstream>

#include "analysis/parallel.hpp"
#include "spec/text_position.hpp"

namespace mechkin {

namespace {

// "/expect/mobility"; a motion bound's key "min/transmission" is two tokens.
std::string ExpectPointer(const std::string& key) {
  const size_t slash = key.find('/');
  if (slash == std::string::npos) return "/expect/" + EscapeToken(key);
  return "/expect/" + key.substr(0, slash) + "/" + EscapeToken(key.substr(slash + 1));
}

}  // namespace

int ExitCodeOf(CheckVerdict verdict) { return verdict == CheckVerdict::Ok ? 0 : 1; }

namespace {

using Clock = std::chrono::steady_clock;

CheckVerdict VerdictOf(const CheckReport& r) {
  if (!r.valid) return CheckVerdict::Invalid;
  return r.ok() ? CheckVerdict::Ok : CheckVerdict::Failed;
}

// The whole check of a loaded file; throws CheckStopped when `stop` turns true.
CheckReport CheckLoadedFile(const std::string& path, const LoadResult& loaded, const CheckRequest& request,
                            const InterruptPoll& stop) {
  StopPoint(stop, "reading and compiling the file");
  CheckReport r = CheckLoaded(path, loaded, stop);
  if (request.branches && loaded.ok()) {
    r.branches = CountBranches(*loaded.model, request.restarts, 1, stop);
    StopPoint(stop, "the branch count");
  }
  if (request.clearance && loaded.ok() && !r.clearance) {
    AddClearanceCheck(*loaded.model, &r, stop);
    StopPoint(stop, "the clearance sweep");
  }
  return r;
}

// The same text for every run (no measured time in it), so that the lines of two runs compare.
CheckReport StoppedReport(const std::string& path, double limit, const char* stage) {
  CheckReport r;
  r.file = path;
  std::ostringstream msg;
  msg.precision(6);
  msg << "the check overran its time limit of " << limit << " s and was stopped in " << stage;
  r.errors.push_back({"", msg.str(), "allow it more time (check --timeout), or check this file on its own"});
  return r;
}

}  // namespace

FileCheck CheckMechanismFile(const std::string& path, const CheckRequest& request) {
  FileCheck out;
  const Clock::time_point start = Clock::now();
  InterruptPoll stop;
  if (request.timeout_seconds > 0) {
    const auto deadline = start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(request.timeout_seconds));
    stop = [deadline] { return Clock::now() > deadline; };
  }
  std::string text;
  Diagnostic unreadable;
  try {
    std::optional<LoadResult> other = request.load_other ? request.load_other(path) : std::nullopt;
    if (other) {
      out.report = CheckLoadedFile(path, *other, request, stop);
    } else if (!ReadMechanismFileText(path, &text, &unreadable)) {
      out.report.file = path;
      out.report.errors.push_back(unreadable);
    } else {
      const LoadResult loaded = LoadMechanismText(text, MechanismSourceName(path), request.overrides);
      out.report = CheckLoadedFile(path, loaded, request, stop);
      LocateDiagnostics(text, &out.report.errors);
      LocateDiagnostics(text, &out.report.warnings);
      for (const ExpectationResult& e : out.report.expectations)
        out.expect_places.push_back(LocateJsonPointer(text, ExpectPointer(e.key)));
    }
    out.verdict = VerdictOf(out.report);
  } catch (const CheckStopped& s) {
    out.report = StoppedReport(path, request.timeout_seconds, s.stage);
    out.verdict = CheckVerdict::Timeout;
  } catch (const std::exception& e) {
    // Defensive: a failure on one file must not take the others' reports with it.
    out.report = CheckReport{};
    out.report.file = path;
    out.report.errors.push_back({"", std::string("the check of this file failed: ") + e.what(), "please report this file"});
    out.verdict = CheckVerdict::Error;
  }
  out.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

void CheckFiles(const std::vector<std::string>& files, const CheckRequest& request, int jobs, bool in_order,
                const std::function<bool(size_t, FileCheck&&)>& deliver) {
  std::mutex mutex;
  bool stopped = false;
  size_t next = 0;                       // in_order: the next index to deliver
  std::map<size_t, FileCheck> waiting;   // in_order: finished, waiting for an earlier file
  auto hand_over = [&](size_t index, FileCheck&& result) {
    std::lock_guard<std::mutex> lock(mutex);
    if (!in_order) {
      stopped = !deliver(index, std::move(result)) || stopped;
      return;
    }
    waiting.emplace(index, std::move(result));
    for (auto it = waiting.begin(); it != waiting.end() && it->first == next; it = waiting.erase(it), ++next)
      stopped = !deliver(it->first, std::move(it->second)) || stopped;
  };
  ParallelFor(static_cast<int>(files.size()), std::max(jobs, 1),
              [&](int i, int) { hand_over(static_cast<size_t>(i), CheckMechanismFile(files[i], request)); },
              [&] {
                std::lock_guard<std::mutex> lock(mutex);
                return stopped;
              });
}

}  // namespace mechkin
