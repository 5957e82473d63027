// Compile: a MechanismSpec (src/spec) and parameter overrides → the immutable Model.
//
// Units to SI, names to indices, parameters resolved (in dependency order,
// each parsed once), joint and driver frames in body coordinates, functions of
// time, and the warning passes of a valid model. Every variant (a `--set`, a
// sensitivity side, a Monte-Carlo sample, a sweep row, `with_parameters`)
// compiles the same spec; the Model keeps the spec, never the file text.
// Never throws for bad input: every problem is a Diagnostic with its JSON pointer.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "spec/diagnostic.hpp"
#include "spec/spec.hpp"

namespace mechkin {

struct LoadResult {
  std::optional<Model> model;  // set only when errors is empty
  std::vector<Diagnostic> errors;
  std::vector<Diagnostic> warnings;
  bool ok() const { return errors.empty() && model.has_value(); }
};

/// Parameter values that replace the file's ("--set crank=105").
using ParameterOverrides = std::map<std::string, double>;

LoadResult Compile(const MechanismSpec& spec, const ParameterOverrides& overrides = {});
/// The same, sharing `spec` with the model (no copy).
LoadResult Compile(std::shared_ptr<const MechanismSpec> spec, const ParameterOverrides& overrides = {});
/// A variant: `expressions` (a model's, compiled from the same spec) saves parsing
/// the spec's expressions again; ignored when it belongs to another spec.
LoadResult Compile(std::shared_ptr<const MechanismSpec> spec, const ParameterOverrides& overrides,
                   std::shared_ptr<const ExpressionCache> expressions);
/// The model, or nullopt when `out` received errors (or the spec is not valid);
/// the diagnostics keep their places in the file (for merging with the reader's).
std::optional<Model> CompileModel(std::shared_ptr<const MechanismSpec> spec, const ParameterOverrides& overrides,
                                  DiagnosticLog* out, std::shared_ptr<const ExpressionCache> expressions = nullptr);

}  // namespace mechkin
