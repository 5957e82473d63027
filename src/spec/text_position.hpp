// Where a JSON pointer is in a mechanism file's text (issue 31: every diagnostic
// carries the line and column of its pointer, for `check --format sarif|gcc|jsonl`).
//
// The text is walked as JSON along the pointer's tokens (strings with their escapes
// decoded, nested arrays and objects skipped whole), so a key is found in its own
// object only — never a same-named key of another object or a string value equal
// to it. An object key that appears more than once resolves to its last occurrence
// (the value JSON parsers keep). The place of a key is its opening quote; of an
// array element, its value's first character. A pointer that names something the
// text does not hold (a missing key) resolves to its deepest existing ancestor.
#pragma once

#include <string>
#include <vector>

#include "spec/diagnostic.hpp"

namespace mechkin {

/// A place in a text: 1-based line and column (columns count Unicode code points,
/// a tab one). line 0: not found.
struct TextPosition {
  int line = 0, column = 0;
};

/// The place of `pointer` (RFC 6901) in `text`; {0, 0} for "" or text that is not JSON
/// up to the pointer's target.
TextPosition LocateJsonPointer(const std::string& text, const std::string& pointer);
/// Sets line and column of every diagnostic with a pointer (one pass per diagnostic).
void LocateDiagnostics(const std::string& text, std::vector<Diagnostic>* diagnostics);
/// The place of byte `offset` of `text` (counting code points as LocateJsonPointer).
TextPosition PositionOfByte(const std::string& text, size_t offset);

}  // namespace mechkin
