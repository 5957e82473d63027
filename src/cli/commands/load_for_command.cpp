#include "cli/commands/load_for_command.hpp"

#include "model/loader.hpp"

namespace mechkin {

std::optional<Model> LoadForCommand(const std::string& file, std::ostream& err) {
  LoadResult loaded = LoadMechanismFile(file);
  for (const auto& w : loaded.warnings) err << file << ": warning: " << w.ToString() << "\n";
  if (!loaded.ok()) {
    for (const auto& e : loaded.errors) err << file << ": error: " << e.ToString() << "\n";
    return std::nullopt;
  }
  return std::move(loaded.model);
}

}  // namespace mechkin
