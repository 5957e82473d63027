// Loading a mechanism file for a command that runs it (run, view): the loader's
// warnings and errors go to `err`, each prefixed with the file's name.
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include <vector>

#include "analysis/load.hpp"
#include "importers/importers.hpp"
#include "io/output_file.hpp"

namespace mechkin {

/// The compiled model, or nothing when the file is invalid (its errors printed).
/// `overrides`: --set values of the file's parameters. A foreign file (URDF, MJCF,
/// SDFormat: cli/commands/foreign.hpp) is imported with `foreign`'s drives and span.
std::optional<Model> LoadForCommand(const std::string& file, std::ostream& err,
                                    const ParameterOverrides& overrides = {},
                                    const importers::ImportOptions& foreign = {});
/// Writes a finished report to `path` (empty or "-": `out`) atomically; on failure
/// prints "mechkin COMMAND: why" and returns false. `inputs`: files it must not overwrite.
bool WriteReport(const std::string& path, const std::vector<std::string>& inputs, const std::string& text,
                 const std::string& command, std::ostream& out, std::ostream& err);
/// The report's destination opened before the work (refused: an input, a
/// directory, an unwritable folder); "mechkin COMMAND: why" printed on failure.
bool OpenReport(const std::string& path, const std::vector<std::string>& inputs, const std::string& command,
                OutputFile* file, std::ostream& out, std::ostream& err);
/// Writes the finished report into a file OpenReport opened, atomically.
bool CommitReport(OutputFile* file, const std::string& text, const std::string& command, std::ostream& err);
/// Reads "--set NAME=NUMBER" options; false (the problem printed) for a malformed one.
bool ParseOverrides(const std::vector<std::string>& settings, ParameterOverrides* out, std::ostream& err);
/// "i/N" with whole numbers 1 ≤ i ≤ N (a job array's shard: `check --shard`, `sweep --shard`);
/// false for anything else ("1/2/3", "1/2x", "0/2").
bool ParseShardText(const std::string& text, int* shard, int* shards);

}  // namespace mechkin
