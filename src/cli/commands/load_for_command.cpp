#include <cmath>
#include <cstdlib>
#include "cli/commands/load_for_command.hpp"

#include "io/output_file.hpp"

#include "analysis/load.hpp"
#include "cli/commands/foreign.hpp"

namespace mechkin {

std::optional<Model> LoadForCommand(const std::string& file, std::ostream& err, const ParameterOverrides& overrides,
                                    const importers::ImportOptions& foreign) {
  if (!ForeignOptionsFit(file, foreign, err)) return std::nullopt;
  LoadResult loaded = LoadAnyMechanism(file, overrides, foreign);
  for (const auto& w : loaded.warnings) err << file << ": warning: " << w.ToString() << "\n";
  if (!loaded.ok()) {
    for (const auto& e : loaded.errors) err << file << ": error: " << e.ToString() << "\n";
    return std::nullopt;
  }
  return std::move(loaded.model);
}

bool WriteReport(const std::string& path, const std::vector<std::string>& inputs, const std::string& text,
                 const std::string& command, std::ostream& out, std::ostream& err) {
  OutputFile file;
  std::string why;
  if (!file.Open(path, inputs, &why, &out) || !file.Write(text) || !file.Commit("", &why)) {
    err << "mechkin " << command << ": " << why << "\n";
    return false;
  }
  return true;
}

bool OpenReport(const std::string& path, const std::vector<std::string>& inputs, const std::string& command,
                OutputFile* file, std::ostream& out, std::ostream& err) {
  std::string why;
  if (file->Open(path, inputs, &why, &out)) return true;
  err << "mechkin " << command << ": " << why << "\n";
  return false;
}

bool CommitReport(OutputFile* file, const std::string& text, const std::string& command, std::ostream& err) {
  std::string why;
  file->Write(text);  // a failed write makes Commit fail with its errno text
  if (file->Commit("", &why)) return true;
  err << "mechkin " << command << ": " << why << "\n";
  return false;
}

bool ParseOverrides(const std::vector<std::string>& settings, ParameterOverrides* out, std::ostream& err) {
  for (const auto& s : settings) {
    const auto eq = s.find('=');
    const std::string name = s.substr(0, eq == std::string::npos ? 0 : eq);
    const std::string value = eq == std::string::npos ? "" : s.substr(eq + 1);
    char* end = nullptr;
    const double v = value.empty() ? 0 : std::strtod(value.c_str(), &end);
    if (name.empty() || value.empty() || end != value.c_str() + value.size() || !std::isfinite(v)) {
      err << "mechkin: --set '" << s << "': expected NAME=NUMBER, e.g. --set crank=105\n";
      return false;
    }
    (*out)[name] = v;
  }
  return true;
}

bool ParseShardText(const std::string& text, int* shard, int* shards) {
  const auto slash = text.find('/');
  if (slash == std::string::npos) return false;
  const auto whole = [](const std::string& part, int* v) {  // each side a whole integer
    size_t used = 0;
    try {
      *v = std::stoi(part, &used);
    } catch (const std::exception&) {
      return false;
    }
    return used == part.size();
  };
  return whole(text.substr(0, slash), shard) && whole(text.substr(slash + 1), shards) && *shards >= 1 &&
         *shard >= 1 && *shard <= *shards;
}

}  // namespace mechkin
