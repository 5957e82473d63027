// `mechkin convert` (docs/format.md "Converting between the forms"): a mechanism
// file rewritten between its two forms, the same mechanism and the same motion —
// joints on global design coordinates ("global"), or joints on markers fixed in
// their bodies ("markers").
//
// The converter edits the file's own JSON document (key order, descriptions,
// "$schema" and every section it does not concern are kept as written) using the
// compiled model for the numbers and the spec for the parameter expressions.
#pragma once

#include <string>
#include <vector>

#include "model/model.hpp"
#include "spec/spec.hpp"

namespace mechkin {

enum class FileForm { Markers, Global };

struct ConvertResult {
  std::string text;                // the converted file (when ok)
  std::vector<std::string> notes;  // what lost its parameter dependence (printed on stderr)
  std::string error;               // why the file cannot be converted exactly (nothing is written)
  bool ok() const { return error.empty(); }
};

/// Markers when any joint of the spec names markers, else global.
FileForm FormOf(const MechanismSpec& spec);

/// `text` is the file `model` was compiled from (without parameter overrides).
ConvertResult ConvertMechanism(const std::string& text, const Model& model, FileForm to);

}  // namespace mechkin
