// Loading a mechanism file for a command that runs it (run, view): the loader's
// warnings and errors go to `err`, each prefixed with the file's name.
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "model/model.hpp"

namespace mechkin {

/// The compiled model, or nothing when the file is invalid (its errors printed).
std::optional<Model> LoadForCommand(const std::string& file, std::ostream& err);

}  // namespace mechkin
