// Parsing the file text as JSON (syntax errors with line and column, duplicate keys).
#include <algorithm>
#include <functional>
#include <set>

#include "spec/json_reader.hpp"
#include "spec/text_position.hpp"

namespace mechkin::spec_reader {

namespace {

// Parses the text as JSON; on failure reports where (line and column) and why.
// Follows the parse to name duplicate keys by their JSON pointer (JSON allows
// them; the last one silently wins, which is rarely what the author meant).
class DuplicateKeyTracker {
 public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: frames_.push_back(Frame{true, {}, {}, 0}); break;
      case json::parse_event_t::array_start: frames_.push_back(Frame{false, {}, {}, 0}); break;
      case json::parse_event_t::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second) duplicates_.push_back(Pointer());
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        NextElement();
        break;
      case json::parse_event_t::value: NextElement(); break;
    }
    return true;
  }
  const std::vector<std::string>& duplicates() const { return duplicates_; }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string key;
    size_t index = 0;
  };
  void NextElement() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
  }
  std::string Pointer() const {
    std::string p;
    for (const Frame& f : frames_) p += "/" + (f.object ? EscapeToken(f.key) : std::to_string(f.index));
    return p;
  }
  std::vector<Frame> frames_;
  std::vector<std::string> duplicates_;
};


// Line and column (1-based) of byte `end` of the text.
std::string LineAndColumn(const std::string& text, size_t end) {
  size_t line = 1, col = 1;
  for (size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(col);
}

// Arrays and objects nest at most this deep (docs/format.md, "The idea"). Checked
// on the text before parsing: the parser's stack and the tracker's frames grow with
// the depth (a 20 MB file of '[' took 4.3 GB and 17 s to report its syntax error).
constexpr int kMaxJsonDepth = 100;

// The byte where the text first opens a level beyond kMaxJsonDepth (strings
// skipped), or npos: one pass, no allocation.
size_t TooDeepAt(const std::string& text) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

// The error just reported is at byte `at` of the text (its line and column fields).
void PlaceLastError(const std::string& text, size_t at, JsonReader& rd) {
  Diagnostic& d = rd.diagnostics().errors.back();
  const TextPosition p = PositionOfByte(text, at);
  d.line = p.line;
  d.column = p.column;
}

}  // namespace

bool ParseJson(const std::string& text, JsonReader& rd, json* doc_out) {
  json& doc = *doc_out;
  if (const size_t at = TooDeepAt(text); at != std::string::npos) {
    rd.Error("", "the JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels of '[' and '{' at " +
                     LineAndColumn(text, at),
             "a mechanism file needs a few levels: close the brackets left open before this point");
    PlaceLastError(text, at, rd);
    return false;
  }
  try {
    DuplicateKeyTracker tracker;
    doc = json::parse(text, std::ref(tracker));
    for (const auto& ptr : tracker.duplicates())
      rd.Warn(ptr, "the key appears more than once in its object; the last value is used",
              "remove the other occurrences");
  } catch (const json::parse_error& e) {
    const size_t end = std::min<size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    std::string what = e.what();
    const auto pos = what.find("syntax error");
    if (pos != std::string::npos) what = what.substr(pos);
    rd.Error("", "JSON syntax error at " + LineAndColumn(text, end) + ": " + what,
             text.empty() ? "the file is empty; start from a file in mechanisms/" : "fix the JSON syntax");
    PlaceLastError(text, end, rd);
    return false;
  } catch (const json::out_of_range& e) {
    // nlohmann reports overflowing numbers (1e999) without a position: find the token.
    std::string what = e.what(), where;
    const auto q1 = what.find('\''), q2 = what.rfind('\'');
    if (q1 != std::string::npos && q2 > q1) {
      const std::string token = what.substr(q1 + 1, q2 - q1 - 1);
      const size_t at = text.find(token);
      if (at != std::string::npos) where = " at " + LineAndColumn(text, at);
      what = "number '" + Shorten(token) + "' is too large for a double" + where;
    }
    rd.Error("", what, "use a finite value (|x| < 1.8e308)");
    return false;
  } catch (const std::exception& e) {
    rd.Error("", std::string("cannot parse the file as JSON: ") + e.what());
    return false;
  }

  return true;
}

}  // namespace mechkin::spec_reader
