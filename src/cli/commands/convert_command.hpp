// `mechkin convert FILE [--to markers|global] [-o OUT]`: the file rewritten in the
// other form (docs/format.md "Converting between the forms").
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>

namespace mechkin {

struct ConvertCommandOptions {
  std::string file, output, to;  // to: "markers", "global" or empty (the other form)
};

void SetupConvertCommand(CLI::App& app, ConvertCommandOptions* options);
int RunConvertCommand(const ConvertCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
