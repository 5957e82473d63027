// `mechkin check FILE...`: validate mechanism files and report their mobility.
//
// Exit status: 0 when every file is valid and every `expect` holds, 1 otherwise.
// The JSON report (--format json) has these stable keys:
//   {"mechkin_check": 1, "ok": bool, "files": [FileReport...]}
// FileReport: file, valid, name, bodies, joints {type: count}, drivers,
//   grubler, dof_after_drivers_count, mobility {...} (when valid), expect [{key,
//   expected, actual, held}], errors [{pointer, message, fix}], warnings [...].
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "cli/commands/foreign.hpp"

namespace mechkin {

struct CheckOptions {
  std::vector<std::string> files;
  std::string format = "text";  // text | json
  std::vector<std::string> set;  // --set NAME=VALUE
  bool branches = false;         // count the assembly branches at the design driver values
  int restarts = 200;
  ForeignOptions foreign;        // --drive, --span: for imported files
  bool clearance = false;        // sweep the analysis span: the tightest pair of shaped bodies and where
};

void SetupCheckCommand(CLI::App& app, CheckOptions* options);
int RunCheck(const CheckOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
