#include "io/load_any.hpp"

#include <fstream>

#include "io/spec_writer.hpp"

namespace mechkin {

importers::ForeignFormat ForeignFormatOf(const std::string& path) {
  if (path == "-") return importers::ForeignFormat::None;
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) return importers::ForeignFormat::None;  // the loader says why
  std::string head(4096, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  // An empty file is still named by its extension (an empty .urdf is a malformed URDF).
  return importers::DetectForeignFormat(path, head);
}

Diagnostic LocatedInSource(const importers::ImportResult& imported, Diagnostic d) {
  const std::string at = imported.OriginOf(d.pointer);
  if (!at.empty()) d.pointer = at + " (" + (d.pointer.empty() ? "/" : d.pointer) + " of the imported file)";
  return d;
}

LoadResult LoadAnyMechanism(const std::string& path, const ParameterOverrides& overrides,
                            const importers::ImportOptions& foreign, std::string* imported_text) {
  if (ForeignFormatOf(path) == importers::ForeignFormat::None) return LoadMechanismFile(path, overrides);
  const importers::ImportResult imported = importers::ImportFile(path, foreign);
  LoadResult result;
  for (const auto& w : imported.warnings) result.warnings.push_back({w.Place(), w.message, w.fix});
  if (!imported.ok()) {
    for (const auto& e : imported.errors) result.errors.push_back({e.Place(), e.message, e.fix});
    return result;
  }
  LoadResult compiled = CompileMechanism(*imported.spec, overrides);
  for (auto& w : compiled.warnings) result.warnings.push_back(LocatedInSource(imported, w));
  for (auto& e : compiled.errors) result.errors.push_back(LocatedInSource(imported, e));
  result.model = std::move(compiled.model);
  if (!result.errors.empty()) result.model.reset();
  if (result.model && imported_text) *imported_text = MechanismSpecJson(*imported.spec);
  return result;
}

}  // namespace mechkin
