#include "spec/text_position.hpp"

namespace mechkin {

namespace {

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

void AppendUtf8(unsigned long cp, std::string* out) {
  if (cp < 0x80) {
    *out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    *out += static_cast<char>(0xC0 | (cp >> 6));
    *out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    *out += static_cast<char>(0xE0 | (cp >> 12));
    *out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    *out += static_cast<char>(0xF0 | (cp >> 18));
    *out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    *out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// The JSON text walked without building it: every position is a byte offset.
class JsonWalk {
 public:
  explicit JsonWalk(const std::string& text) : t_(text) {}

  size_t SkipSpace(size_t i) const {
    while (i < t_.size() && IsSpace(t_[i])) ++i;
    return i;
  }
  char At(size_t i) const { return i < t_.size() ? t_[i] : '\0'; }

  // The string starting at t_[*i] == '"', decoded; *i moves past its closing quote.
  bool ReadString(size_t* i, std::string* out) const {
    size_t k = *i + 1;
    while (k < t_.size() && t_[k] != '"') {
      if (t_[k] != '\\') {
        *out += t_[k++];
        continue;
      }
      const char e = At(k + 1);
      k += 2;
      switch (e) {
        case 'b': *out += '\b'; break;
        case 'f': *out += '\f'; break;
        case 'n': *out += '\n'; break;
        case 'r': *out += '\r'; break;
        case 't': *out += '\t'; break;
        case 'u': AppendUtf8(ReadEscapedCodePoint(&k), out); break;
        default: *out += e;  // \" \\ \/
      }
    }
    if (k >= t_.size()) return false;
    *i = k + 1;
    return true;
  }

  // Moves *i past the value starting there (containers whole, strings with escapes).
  bool SkipValue(size_t* i) const {
    size_t k = *i;
    int depth = 0;
    do {
      const char c = At(k);
      if (c == '"') {
        std::string ignored;
        if (!ReadString(&k, &ignored)) return false;
        continue;
      }
      if (c == '\0' && k >= t_.size()) return false;
      if (c == '{' || c == '[') ++depth;
      else if (c == '}' || c == ']') --depth;
      else if (depth == 0) {  // a number or literal: up to its delimiter
        while (k < t_.size() && !IsSpace(t_[k]) && t_[k] != ',' && t_[k] != '}' && t_[k] != ']') ++k;
        break;
      }
      ++k;
    } while (depth > 0);
    *i = k;
    return depth == 0;
  }

 private:
  // \uXXXX at t_[*k - 1] == 'u' (a surrogate pair joined); *k moves past it.
  unsigned long ReadEscapedCodePoint(size_t* k) const {
    auto hex4 = [&](size_t at, unsigned long* v) {
      if (at + 4 > t_.size()) return false;
      *v = 0;
      for (size_t j = at; j < at + 4; ++j) {
        const char c = t_[j];
        const int digit = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
                                                            : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (digit < 0) return false;
        *v = *v * 16 + static_cast<unsigned long>(digit);
      }
      return true;
    };
    unsigned long cp = 0, low = 0;
    if (!hex4(*k, &cp)) return '?';
    *k += 4;
    if (cp >= 0xD800 && cp < 0xDC00 && At(*k) == '\\' && At(*k + 1) == 'u' && hex4(*k + 2, &low) && low >= 0xDC00 &&
        low < 0xE000) {
      *k += 6;
      cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
    }
    return cp;
  }
  const std::string& t_;
};

// The pointer's reference tokens, unescaped (~1 → '/', ~0 → '~'); false when malformed.
bool SplitPointer(const std::string& pointer, std::vector<std::string>* tokens) {
  if (pointer.empty() || pointer[0] != '/') return false;
  std::string token;
  for (size_t k = 1; k <= pointer.size(); ++k) {
    if (k == pointer.size() || pointer[k] == '/') {
      tokens->push_back(token);
      token.clear();
    } else if (pointer[k] == '~' && k + 1 < pointer.size() && (pointer[k + 1] == '0' || pointer[k + 1] == '1')) {
      token += pointer[++k] == '0' ? '~' : '/';
    } else {
      token += pointer[k];
    }
  }
  return true;
}

bool ArrayIndex(const std::string& token, size_t* index) {
  if (token.empty() || token.size() > 9 || (token.size() > 1 && token[0] == '0')) return false;
  for (char c : token)
    if (c < '0' || c > '9') return false;
  *index = std::stoul(token);
  return true;
}

// In the object at t[at] == '{': the last member named `key` (its key's and value's
// offsets); false when it has none.
bool FindMember(const JsonWalk& w, size_t at, const std::string& key, size_t* key_at, size_t* value_at) {
  bool found = false;
  size_t i = w.SkipSpace(at + 1);
  while (w.At(i) == '"') {
    const size_t start = i;
    std::string name;
    if (!w.ReadString(&i, &name)) return found;
    i = w.SkipSpace(i);
    if (w.At(i) != ':') return found;
    i = w.SkipSpace(i + 1);
    if (name == key) *key_at = start, *value_at = i, found = true;
    if (!w.SkipValue(&i)) return found;
    i = w.SkipSpace(i);
    if (w.At(i) != ',') break;
    i = w.SkipSpace(i + 1);
  }
  return found;
}

// In the array at t[at] == '[': the offset of element `index`; false when it has fewer.
bool FindElement(const JsonWalk& w, size_t at, size_t index, size_t* value_at) {
  size_t i = w.SkipSpace(at + 1);
  for (size_t n = 0; w.At(i) != ']' && w.At(i) != '\0'; ++n) {
    if (n == index) {
      *value_at = i;
      return true;
    }
    if (!w.SkipValue(&i)) return false;
    i = w.SkipSpace(i);
    if (w.At(i) != ',') return false;
    i = w.SkipSpace(i + 1);
  }
  return false;
}

// The byte offset of the pointer's target (or its deepest existing ancestor), npos
// for "" or a text that is not JSON.
size_t LocateOffset(const std::string& text, const std::string& pointer) {
  std::vector<std::string> tokens;
  if (!SplitPointer(pointer, &tokens)) return std::string::npos;
  const JsonWalk w(text);
  size_t at = w.SkipSpace(text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0);
  if (at >= text.size()) return std::string::npos;
  size_t found = at;
  for (const std::string& token : tokens) {
    size_t key_at = 0, value_at = 0, index = 0;
    if (w.At(at) == '{' && FindMember(w, at, token, &key_at, &value_at)) {
      found = key_at;
    } else if (w.At(at) == '[' && ArrayIndex(token, &index) && FindElement(w, at, index, &value_at)) {
      found = value_at;
    } else {
      break;
    }
    at = value_at;
  }
  return found;
}

}  // namespace

TextPosition PositionOfByte(const std::string& text, size_t offset) {
  TextPosition p{1, 1};
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++p.line;
      p.column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++p.column;
    }
  }
  return p;
}

TextPosition LocateJsonPointer(const std::string& text, const std::string& pointer) {
  const size_t at = LocateOffset(text, pointer);
  return at == std::string::npos ? TextPosition{} : PositionOfByte(text, at);
}

void LocateDiagnostics(const std::string& text, std::vector<Diagnostic>* diagnostics) {
  for (Diagnostic& d : *diagnostics) {
    if (d.pointer.empty() || d.line > 0) continue;
    const TextPosition p = LocateJsonPointer(text, d.pointer);
    d.line = p.line;
    d.column = p.column;
  }
}

}  // namespace mechkin
