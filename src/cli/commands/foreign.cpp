#include "cli/commands/foreign.hpp"

#include <cmath>
#include <cstdlib>

#include "cli/commands/load_for_command.hpp"
#include "io/load_any.hpp"
#include "io/spec_writer.hpp"

namespace mechkin {

void AddForeignOptions(CLI::App* cmd, ForeignOptions* o) {
  cmd->add_option("--drive", o->drives,
                  "For an imported (URDF, MJCF, SDFormat) file: drive JOINT by FUNCTION of t in rad or m, e.g. "
                  "--drive crank='2*pi*t' (repeatable)");
  cmd->add_option("--span", o->span,
                  "For an imported file: the analysis span START:END:STEPS (default 0:1:360 when --drive is given)");
}

bool ParseForeignOptions(const ForeignOptions& typed, importers::ImportOptions* out, std::ostream& err) {
  for (const std::string& d : typed.drives) {
    const auto eq = d.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == d.size()) {
      err << "mechkin: --drive '" << d << "': expected JOINT=FUNCTION, e.g. --drive crank='2*pi*t'\n";
      return false;
    }
    out->drives.push_back({d.substr(0, eq), d.substr(eq + 1)});
  }
  if (typed.span.empty()) return true;
  const char* s = typed.span.c_str();
  char* end = nullptr;
  const double a = std::strtod(s, &end);
  const bool c1 = *end == ':';
  const double b = c1 ? std::strtod(end + 1, &end) : 0;
  const bool c2 = *end == ':';
  const double n = c2 ? std::strtod(end + 1, &end) : 0;
  if (!c1 || !c2 || *end || !(b > a) || !(n >= 1) || n != std::floor(n) || n > 1e7 || !std::isfinite(a)) {
    err << "mechkin: --span '" << typed.span << "': expected START:END:STEPS with END > START, e.g. --span 0:1:360\n";
    return false;
  }
  out->start = a, out->end = b, out->steps = static_cast<int>(n), out->span_given = true;
  return true;
}

bool ForeignOptionsFit(const std::string& path, const importers::ImportOptions& options, std::ostream& err) {
  if (options.drives.empty() && !options.span_given) return true;
  if (ForeignFormatOf(path) != importers::ForeignFormat::None) return true;
  err << "mechkin: " << path << ": --drive and --span are for imported (URDF, MJCF, SDFormat) files; "
      << "a mechanism file has its own drivers and analysis\n";
  return false;
}

bool ForeignHasDrives(const std::string& path, const importers::ImportOptions& foreign, const Model& model,
                      const std::string& command, std::ostream& err) {
  if (!foreign.drives.empty() || ForeignFormatOf(path) == importers::ForeignFormat::None) return true;
  std::string names;
  for (const auto& j : model.joints) names += (names.empty() ? "" : ", ") + j.name;
  err << "mechkin " << command << ": " << path << ": an imported file drives no joint: give --drive JOINT=FUNCTION "
      << "(a function of t in rad or m, e.g. --drive " << (model.joints.empty() ? "J" : model.joints[0].name)
      << "='2*pi*t'); joints: " << names << "\n";
  return false;
}

void SetupImportCommand(CLI::App& app, ImportCommandOptions* o) {
  CLI::App* cmd = app.add_subcommand(
      "import", "Write the mechanism file of a URDF, MJCF (MuJoCo) or SDFormat file: bodies by link, joints by name, "
                "markers at the joint frames, loops kept (docs/import.md)");
  cmd->add_option("file", o->file, "A .urdf, MJCF .xml or .sdf file")->required();
  cmd->add_option("-o,--output", o->output, "Output file (default or '-': stdout); written atomically, never the input");
  AddForeignOptions(cmd, &o->foreign);
}

int RunImportCommand(const ImportCommandOptions& o, std::ostream& out, std::ostream& err) {
  importers::ImportOptions options;
  if (!ParseForeignOptions(o.foreign, &options, err)) return 2;
  if (ForeignFormatOf(o.file) == importers::ForeignFormat::None) {
    err << "mechkin import: " << o.file << ": not a URDF, MJCF or SDFormat file (or it cannot be read)\n";
    return 1;
  }
  const importers::ImportResult imported = importers::ImportFile(o.file, options);
  for (const auto& w : imported.warnings) err << "warning: " << w.ToString() << "\n";
  for (const auto& e : imported.errors) err << "error: " << e.ToString() << "\n";
  if (!imported.ok()) return 1;
  // The written file must load: compile it now, its problems named at their source.
  const LoadResult check = CompileMechanism(*imported.spec);
  for (const auto& e : check.errors) err << "error: " << LocatedInSource(imported, e).ToString() << "\n";
  if (!check.ok()) return 1;
  if (!WriteReport(o.output, {o.file}, MechanismSpecJson(*imported.spec), "import", out, err)) return 1;
  return 0;
}

}  // namespace mechkin
