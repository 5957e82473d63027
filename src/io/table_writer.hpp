// Motion tables as CSV or JSON, streamed row by row as the run computes them
// (memory independent of the number of steps). Numbers are written in the
// shortest form that reads back to the same double (std::to_chars).
//
// CSV: the header line of column names with units ("t [s]", "crank.x_t [mm/s]"),
// then one line per row; a table that ends early is preceded by
// "# PARTIAL TABLE: <why>". JSON: {"columns": [{"name", "unit"}...], "rows": [[...]],
// "mechkin_table": 1, "partial": bool, "note"?: why, "reductions"?: [{"name", "of",
// "reduce", "value", "unit", "t"?, "located"?, "gradient"?, "problem"?}]}.
#pragma once

#include <string>
#include <vector>

#include "analysis/enum_names.hpp"  // TableFormat
#include "analysis/motion.hpp"
#include "io/output_file.hpp"

namespace mechkin {

class TableWriter : public RowSink {
 public:
  /// Writes the header at once.
  TableWriter(const MotionLayout& layout, TableFormat format, OutputFile* file);
  bool Append(const double* row, int size) override;
  /// Ends the table and commits the file; `partial_note` non-empty marks it partial.
  /// JSON: `reductions` become the table's "reductions" array (docs/format.md "Reductions").
  bool Finish(const std::string& partial_note, std::string* error, const std::vector<ReductionResult>& reductions = {});

 private:
  // to_chars' shortest round-trip form of a double is at most 24 characters.
  static constexpr int kMaxNumberChars = 32;
  char* AppendNumber(double v, char* out) const;
  TableFormat format_;
  OutputFile* file_;
  std::vector<char> buffer_;  // one row's text
  bool first_row_ = true;
};

/// Writes a whole Motion (the Python package's to_csv, tests) to `path`.
bool WriteMotion(const Motion& motion, TableFormat format, const std::string& path, std::string* error,
                 const std::vector<std::string>& inputs = {});

/// Escapes text for a CSV cell (quoted when it holds a comma, quote or newline).
std::string CsvCell(const std::string& text);
/// Escapes text for a JSON string body (no surrounding quotes).
std::string JsonEscape(const std::string& text);
/// Escapes text for XML/SVG/HTML content and attributes.
std::string XmlEscape(const std::string& text);

}  // namespace mechkin
