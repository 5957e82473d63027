// Loading format-v1 mechanism files: read the spec (src/spec/reader.hpp), then
// compile it (model/compile.hpp) — WITHOUT closing the loops of a file placed by
// markers (that needs the equations: analysis/load.hpp is the front door every
// caller uses; these are its model-level half).
//
// Every problem of a file is collected (not just the first), each naming the
// JSON pointer of the offending value, what is wrong and how to fix it. The
// loader never throws for bad input.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "model/compile.hpp"
#include "model/model.hpp"
#include "spec/diagnostic.hpp"

namespace mechkin {

/// Largest file the loader reads (bytes).
constexpr std::size_t kMaxFileBytes = 256u << 20;

/// The text of a mechanism file ("-": the standard input) as the loader reads it:
/// regular files up to kMaxFileBytes, streams with a 10 s silence limit; false with
/// *error (no pointer) for a path that cannot be read.
bool ReadMechanismFileText(const std::string& path, std::string* text, Diagnostic* error);
/// The source name the loader gives a path's model ("-": "<stdin>").
std::string MechanismSourceName(const std::string& path);
LoadResult LoadFileUnassembled(const std::string& path, const ParameterOverrides& overrides = {});
LoadResult LoadTextUnassembled(const std::string& text, const std::string& source_name,
                             const ParameterOverrides& overrides = {});
/// The model compiled again from its spec with other parameter values (earlier
/// overrides kept, these added).
LoadResult WithParametersUnassembled(const Model& model, const ParameterOverrides& overrides);

}  // namespace mechkin
