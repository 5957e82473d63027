// Loading any mechanism a user points at: a mechanism file (docs/format.md) or a
// foreign file (URDF, MJCF, SDFormat, FreeCAD; docs/import.md) imported into a spec
// and compiled. One place for the CLI's commands and the Python package.
#pragma once

#include <string>

#include "analysis/load.hpp"
#include "importers/importers.hpp"

namespace mechkin {

/// The foreign format of `path` (None for a mechanism file, standard input, or a file that cannot be read).
importers::ForeignFormat ForeignFormatOf(const std::string& path);

/// Loads a mechanism file or a foreign file. A foreign file's problems name their
/// place (FILE:LINE: <element>) as the diagnostics' pointer, and compile's problems
/// of the imported spec name the source place they come from. For a foreign file
/// that imports, `imported_text` (when given) receives the imported spec as a
/// mechanism file's text (what `mechkin import` writes).
LoadResult LoadAnyMechanism(const std::string& path, const ParameterOverrides& overrides,
                            const importers::ImportOptions& foreign, std::string* imported_text = nullptr);

/// A compile diagnostic of an imported spec, its pointer replaced by the source place
/// it comes from ("FILE:LINE: <element> (/joints/2 of the imported file)").
Diagnostic LocatedInSource(const importers::ImportResult& imported, Diagnostic d);

}  // namespace mechkin
