// Reading a format-v1 mechanism file (docs/format.md) into a MechanismSpec.
//
// The reader checks the file's structure: JSON syntax (line and column), duplicate
// keys, unknown and missing keys (with did-you-mean), value types and names. It
// resolves nothing: parameter expressions, units and references by name are
// compile's (src/model/compile.hpp). It never throws for bad input.
#pragma once

#include <optional>
#include <string>

#include "spec/diagnostic.hpp"
#include "spec/spec.hpp"

namespace mechkin {

struct SpecReadResult {
  /// Set unless the text is not JSON or not a JSON object; `spec->valid` is false
  /// when `diagnostics` holds errors.
  std::optional<MechanismSpec> spec;
  DiagnosticLog diagnostics;
};

SpecReadResult ReadMechanismSpec(const std::string& text, const std::string& source_name);

}  // namespace mechkin
