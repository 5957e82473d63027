// Reading and validating format-v1 mechanism files (../shared/design/format-v1.md).
//
// Every problem of a file is collected (not just the first), each naming the
// JSON pointer of the offending value, what is wrong and how to fix it. The
// loader never throws for bad input.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace mechkin {

struct Diagnostic {
  std::string pointer;  // JSON pointer ("" = the whole file), e.g. "/joints/3/axis"
  std::string message;  // what is wrong
  std::string fix;      // how to fix it (may be empty)
  std::string ToString() const;
};

struct LoadResult {
  std::optional<Model> model;  // set only when errors is empty
  std::vector<Diagnostic> errors;
  std::vector<Diagnostic> warnings;
  bool ok() const { return errors.empty() && model.has_value(); }
};

/// Largest file the loader reads (bytes).
constexpr std::size_t kMaxFileBytes = 256u << 20;

/// Parameter values that replace the file's ("--set crank=105").
using ParameterOverrides = std::map<std::string, double>;

LoadResult LoadMechanismFile(const std::string& path, const ParameterOverrides& overrides = {});
LoadResult LoadMechanismText(const std::string& text, const std::string& source_name,
                             const ParameterOverrides& overrides = {});
/// The model compiled again with other parameter values (the same file text).
LoadResult WithParameters(const Model& model, const ParameterOverrides& overrides);

}  // namespace mechkin
