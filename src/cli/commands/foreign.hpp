// Foreign files in every command that loads a mechanism (issue 26, docs/import.md):
// a URDF, MJCF or SDFormat file is detected by its extension and content, imported
// into a spec (src/importers) and compiled like a mechanism file; `--drive` and
// `--span` add what those files do not say (the driven joints, the time span).
// `mechkin import FILE [-o OUT]` writes the mechanism file instead.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/load.hpp"
#include "importers/importers.hpp"
#include "io/load_any.hpp"

namespace mechkin {

/// --drive JOINT=FUNCTION (repeatable) and --span START:END:STEPS, as typed.
struct ForeignOptions {
  std::vector<std::string> drives;
  std::string span;
};

void AddForeignOptions(CLI::App* cmd, ForeignOptions* options);
/// False (the problem printed) for a malformed --drive or --span.
bool ParseForeignOptions(const ForeignOptions& typed, importers::ImportOptions* out, std::ostream& err);

/// `options` given for a file that is not foreign: a message and false.
bool ForeignOptionsFit(const std::string& path, const importers::ImportOptions& options, std::ostream& err);

/// False (with a message naming the joints) when `path` is foreign and no --drive was
/// given: run and view need drivers, which those files do not have.
bool ForeignHasDrives(const std::string& path, const importers::ImportOptions& foreign, const Model& model,
                      const std::string& command, std::ostream& err);

struct ImportCommandOptions {
  std::string file;
  std::string output;  // -o; default stdout
  ForeignOptions foreign;
};

void SetupImportCommand(CLI::App& app, ImportCommandOptions* options);
int RunImportCommand(const ImportCommandOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
