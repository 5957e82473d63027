#include "cli/commands/convert_command.hpp"

#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include "cli/commands/load_for_command.hpp"
#include "io/convert.hpp"

namespace mechkin {

void SetupConvertCommand(CLI::App& app, ConvertCommandOptions* o) {
  CLI::App* cmd = app.add_subcommand(
      "convert", "Rewrite a file between its two forms (joints on global geometry, joints on markers): same motion");
  cmd->add_option("file", o->file, "Mechanism file (format v1; '-': standard input)")->required();
  cmd->add_option("--to", o->to, "Form to write: markers or global (default: the other form than the file's)")
      ->check(CLI::IsMember({"markers", "global"}));
  cmd->add_option("-o,--output", o->output, "Output file (default or '-': stdout); written atomically, never the input");
}

namespace {

// The file's text and its model (without overrides); the file's problems printed as by `run`.
std::optional<Model> LoadWithText(const std::string& file, std::string* text, std::ostream& err) {
  if (file == "-") {
    *text = std::string(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
    LoadResult loaded = LoadMechanismText(*text, "<stdin>");
    for (const auto& w : loaded.warnings) err << file << ": warning: " << w.ToString() << "\n";
    for (const auto& e : loaded.errors) err << file << ": error: " << e.ToString() << "\n";
    if (!loaded.ok()) return std::nullopt;
    return std::move(loaded.model);
  }
  std::optional<Model> model = LoadForCommand(file, err);
  if (!model) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (!in) {
    err << "mechkin convert: cannot read '" << file << "' again\n";
    return std::nullopt;
  }
  *text = buffer.str();
  return model;
}

}  // namespace

int RunConvertCommand(const ConvertCommandOptions& o, std::ostream& out, std::ostream& err) {
  std::string text;
  const std::optional<Model> model = LoadWithText(o.file, &text, err);
  if (!model) return 1;
  const FileForm from = FormOf(*model->spec);
  const FileForm to = o.to == "markers"  ? FileForm::Markers
                      : o.to == "global" ? FileForm::Global
                      : from == FileForm::Markers ? FileForm::Global
                                                  : FileForm::Markers;
  const ConvertResult result = ConvertMechanism(text, *model, to);
  if (!result.ok()) {
    err << "mechkin convert: " << o.file << ": " << result.error << "\n";
    return 1;
  }
  for (const auto& note : result.notes)
    err << "mechkin convert: " << o.file << ": note: " << note << "\n";
  if (!WriteReport(o.output, {o.file}, result.text, "convert", out, err)) return 1;
  return 0;
}

}  // namespace mechkin
