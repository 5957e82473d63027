// One file of `mechkin check` as a library call, and many files on threads
// (issue 31: checking a whole model library). The front ends format the typed
// results (io/check_report_writer.hpp); nothing here reads or writes JSON.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/check_report.hpp"
#include "analysis/load.hpp"
#include "spec/text_position.hpp"

namespace mechkin {

/// A file's outcome, in increasing severity (a run's worst verdict sets its exit
/// code): the file is valid and every `expect` held; an `expect` failed; the file is
/// invalid (or unreadable); its check overran the time limit; the check itself
/// failed (an internal error, reported as a bug).
enum class CheckVerdict { Ok, Failed, Invalid, Timeout, Error };

/// The exit code of one verdict, as `check` of a single file exits: 0 for Ok, else 1.
int ExitCodeOf(CheckVerdict verdict);

/// What to check of each file (the `check` options that apply per file).
struct CheckRequest {
  ParameterOverrides overrides;  // --set
  bool branches = false;         // --branches
  int restarts = 200;            // --restarts
  bool clearance = false;        // --clearance
  // > 0: a file whose check runs longer is stopped at its next stop point (between
  // the stages, before each branch restart, at each step of a clearance sweep) and
  // gets the verdict Timeout; the stages without a stop point inside (reading,
  // compiling and assembling the file, the rank of its equations) finish first.
  double timeout_seconds = 0;
  // A file this returns a load for is checked from that load (no line:column: not a
  // mechanism file's text); nullopt, or no function: read as a mechanism file. The CLI
  // passes the importers' load here (URDF, MJCF, SDFormat, FreeCAD).
  std::function<std::optional<LoadResult>(const std::string& path)> load_other;
};

struct FileCheck {
  CheckReport report;   // for Timeout: the file and one error saying where it stopped
  CheckVerdict verdict = CheckVerdict::Ok;
  double seconds = 0;   // wall-clock time of the check
  std::vector<TextPosition> expect_places;  // per report.expectations: its key in the file's "expect"
};

/// Reads and checks one file ("-": the standard input). Never throws: an exception
/// from the check becomes the verdict Error with its message. Every diagnostic with
/// a pointer carries its line and column in the file's text.
FileCheck CheckMechanismFile(const std::string& path, const CheckRequest& request);

/// Checks `files` on `jobs` threads (≥ 1) and hands each result to `deliver` (one
/// call at a time, from any of the threads): as the files finish, or with `in_order`
/// in the order of `files` (a finished file waits for the ones before it). `deliver`
/// returning false starts no further file (the running ones are still delivered).
void CheckFiles(const std::vector<std::string>& files, const CheckRequest& request, int jobs, bool in_order,
                const std::function<bool(size_t index, FileCheck&& result)>& deliver);

}  // namespace mechkin
