// The front door for models (every caller: CLI, Python, sweeps, tolerance,
// sensitivity, tools): read the file, compile it (model/compile.hpp) and, for a
// file whose joints name markers, close its loops (analysis/assemble_model.hpp),
// so that no caller can hold an unassembled model. Files without markers are
// exactly what compile gives.
#pragma once

#include <memory>
#include <string>

#include "model/compile.hpp"
#include "model/loader.hpp"

namespace mechkin {

LoadResult LoadMechanismFile(const std::string& path, const ParameterOverrides& overrides = {});
LoadResult LoadMechanismText(const std::string& text, const std::string& source_name,
                             const ParameterOverrides& overrides = {});
/// The model compiled again from its spec with other parameter values (earlier
/// overrides kept, these added), and assembled.
LoadResult WithParameters(const Model& model, const ParameterOverrides& overrides);
/// Compile (model/compile.hpp) and assemble a spec built directly (Python, tests).
LoadResult CompileMechanism(std::shared_ptr<const MechanismSpec> spec, const ParameterOverrides& overrides = {});
LoadResult CompileMechanism(const MechanismSpec& spec, const ParameterOverrides& overrides = {});
/// Closes the loops of a loaded model placed by markers (a no-op for other files);
/// a loop that cannot close becomes the result's error.
LoadResult Assembled(LoadResult loaded);

}  // namespace mechkin
