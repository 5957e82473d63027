// Importers (issue 26, docs/import.md): mechanisms from where they already live —
// URDF, MJCF (MuJoCo XML) and SDFormat files — read into a MechanismSpec
// (src/spec), never into JSON text: `mechkin import` writes the spec with the io
// layer's writer, and check/run/view compile it directly.
//
// The layer depends on math and spec only. XML is read with tinyxml2 so that every
// message names the file, the line and the element. Nothing here throws for bad
// input: every problem is an ImportMessage, and a file with an error gives no spec.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "spec/spec.hpp"

namespace mechkin::importers {

enum class ForeignFormat { None, Urdf, Mjcf, Sdf, FreeCad };

/// "URDF", "MJCF", "SDFormat", "FreeCAD"; "" for None.
std::string FormatName(ForeignFormat format);

/// What a file is, from its extension and its first bytes: a .urdf/.sdf/.world/.xml/.mjcf
/// file or any file starting with '<' is XML and its root element decides (robot: URDF,
/// mujoco: MJCF, sdf: SDFormat); .FCStd (or a zip) is FreeCAD; anything else
/// (a mechanism JSON file) is None.
ForeignFormat DetectForeignFormat(const std::string& path, const std::string& head);

/// One problem of a foreign file: where (the file, the line, the element) and why.
struct ImportMessage {
  std::string file;
  int line = 0;         // 0: the whole file
  std::string element;  // e.g. <joint name="B">
  std::string message;  // the reason
  std::string fix;      // how to fix it (may be empty)
  /// "FILE:LINE: <element>" (the place), as the pointer of a Diagnostic.
  std::string Place() const;
  /// "FILE:LINE: <element>: message — fix".
  std::string ToString() const;
};

/// Choices the foreign file does not make: which joints are driven and the span.
struct ImportOptions {
  std::vector<std::pair<std::string, std::string>> drives;  // joint name, function of t (SI: rad, m)
  double start = 0, end = 1;
  int steps = 360;
  bool span_given = false;  // --span: analysis written even without drives
};

struct ImportResult {
  ForeignFormat format = ForeignFormat::None;
  std::optional<MechanismSpec> spec;  // set when there are no errors
  std::vector<ImportMessage> errors, warnings;
  /// The written file's JSON pointers ("/joints/3") → the source place they come from.
  std::map<std::string, std::string> origins;
  bool ok() const { return errors.empty() && spec.has_value(); }
  /// The source place of a diagnostic pointer of the written spec: its longest
  /// prefix in `origins` ("" when none).
  std::string OriginOf(const std::string& pointer) const;
};

/// Reads and imports `path` (its format detected). `display_name` names it in messages.
ImportResult ImportFile(const std::string& path, const ImportOptions& options = {});
/// Imports XML text of a known format (tests, standard input).
ImportResult ImportText(const std::string& text, ForeignFormat format, const std::string& display_name,
                        const ImportOptions& options = {});

}  // namespace mechkin::importers
