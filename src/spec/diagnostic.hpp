// Diagnostics of a mechanism file: what is wrong, where (JSON pointer) and how to fix it.
//
// The reader (src/spec) and the compile step (src/model/compile) both report into
// a DiagnosticLog; each entry carries its place in the file (section, element) so
// that the two lists merge into the order the problems appear in the file.
#pragma once

#include <string>
#include <vector>

namespace mechkin {

struct Diagnostic {
  std::string pointer;  // JSON pointer ("" = the whole file), e.g. "/joints/3/axis"
  std::string message;  // what is wrong
  std::string fix;      // how to fix it (may be empty)
  // Where the pointer is in the file's text (spec/text_position.hpp), 1-based; column
  // in Unicode code points. 0: not located (no pointer, no text, or not yet located).
  int line = 0, column = 0;
  std::string ToString() const;
};

/// The sections of a file in the order they are read and compiled.
enum class Section { Parse, Header, Parameters, Units, Ground, Bodies, Joints, Couplers, Drivers, Analysis, Outputs, Expect,
                     Gravity, Loads, View, WholeModel };

/// Errors and warnings, each with its place (section, element index) in the file.
class DiagnosticLog {
 public:
  void SetPlace(Section section, int element = 0) {
    place_ = (static_cast<long long>(section) << 32) + element;
  }
  void Error(const std::string& ptr, const std::string& msg, const std::string& fix = "") {
    errors.push_back({ptr, msg, fix});
    error_places_.push_back(place_);
  }
  void Warn(const std::string& ptr, const std::string& msg, const std::string& fix = "") {
    warnings.push_back({ptr, msg, fix});
    warning_places_.push_back(place_);
  }
  bool has_errors() const { return !errors.empty(); }

  /// `first`'s and `second`'s entries in file order (at one place, `first`'s come first).
  static void Merge(const DiagnosticLog& first, const DiagnosticLog& second, std::vector<Diagnostic>* errors,
                    std::vector<Diagnostic>* warnings);

  std::vector<Diagnostic> errors, warnings;

 private:
  long long place_ = 0;
  std::vector<long long> error_places_, warning_places_;
};

// Text helpers shared by the reader and the compile step (did-you-mean fixes).

/// A JSON pointer token: '~' → "~0", '/' → "~1".
std::string EscapeToken(const std::string& key);
/// The names of a list, at most 12 of them.
std::string Join(const std::vector<std::string>& names);
/// The closest choice to a mistyped word, or "" when none is close.
std::string DidYouMean(const std::string& word, const std::vector<std::string>& choices);
/// A long user string cut to 40 characters for a message.
std::string Shorten(const std::string& s);
/// A number in a message: up to 10 significant digits.
std::string FormatNumber(double value);

}  // namespace mechkin
