// Writing a MechanismSpec as a format-v1 mechanism file (docs/format.md): the
// counterpart of the reader for specs built in code (`mechkin import`). The keys
// written are those a spec built from numbers holds: header, units, ground markers,
// bodies (position, orientation, inertia, markers), joints (on markers or global
// geometry, limits, pitch), couplers, drivers with expression functions, analysis.
// Reading the text back gives the same spec (tests/importers).
#pragma once

#include <string>

#include "spec/spec.hpp"

namespace mechkin {

/// The file's text (indented, short arrays on one line, ending in a newline).
std::string MechanismSpecJson(const MechanismSpec& spec);

}  // namespace mechkin
