// `mechkin check FILE...`: validate mechanism files and report their mobility.
//
// Exit status: 0 when every file is valid and every `expect` holds, 1 otherwise
// (the worst file's verdict: analysis/check_file.hpp), 2 for unusable arguments.
// The JSON report (--format json) has these stable keys:
//   {"mechkin_check": 1, "ok": bool, "files": [FileReport...]}
// FileReport: file, valid, name, bodies, joints {type: count}, drivers,
//   grubler, dof_after_drivers_count, mobility {...} (when valid), expect [{key,
//   expected, actual, held}], errors [{pointer, message, fix}], warnings [...].
// For a library (issue 31): --files-from, --jobs, --shard, --timeout, --format
// jsonl|sarif|gcc, -o OUT (JSON lines, synced per line) with --resume, and a
// summary on stderr when more than one file is checked.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "cli/commands/foreign.hpp"

namespace mechkin {

struct CheckOptions {
  std::vector<std::string> files;
  std::string format = "text";  // text | json | jsonl | sarif | gcc
  std::vector<std::string> set;  // --set NAME=VALUE
  bool branches = false;         // count the assembly branches at the design driver values
  int restarts = 200;
  ForeignOptions foreign;        // --drive, --span: for imported files
  bool clearance = false;        // sweep the analysis span: the tightest pair of shaped bodies and where
  std::string files_from;        // --files-from LIST: one path a line ("-": the standard input)
  int jobs = 1;                  // --jobs N: files checked at once, on threads
  bool sorted = false;           // --sorted: results in the order of the list, whatever the jobs
  std::string shard;             // --shard i/N: the files with index ≡ i−1 (mod N)
  double timeout = 0;            // --timeout SECONDS per file (0: none)
  std::string output;            // -o OUT: the JSON lines appended and synced line by line
  bool resume = false;           // --resume: skip the files OUT already holds
  bool quiet = false;            // --quiet: no summary on stderr
};

void SetupCheckCommand(CLI::App& app, CheckOptions* options);
int RunCheck(const CheckOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
