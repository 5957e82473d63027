// Line and column of a JSON pointer in a file's text (spec/text_position.hpp): the
// walk follows the structure, so same-named keys elsewhere, string values equal to
// a key, escapes and nesting cannot mislead it. Each expectation is the place the
// test finds itself in the text (the marked substring), not a number copied from
// the function's output.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "analysis/check_file.hpp"
#include "analysis/load.hpp"
#include "spec/text_position.hpp"

namespace mechkin {
namespace text_position_test {

// The line and column (code points) of byte `at`, counted here independently.
TextPosition Expected(const std::string& text, size_t at) {
  TextPosition p{1, 1};
  for (size_t i = 0; i < at; ++i) {
    if (text[i] == '\n') p.line++, p.column = 1;
    else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) p.column++;
  }
  return p;
}

// The text from line:column on (columns in code points).
std::string TextAt(const std::string& text, int line, int column) {
  size_t i = 0;
  for (int l = 1; l < line && i < text.size(); ++i)
    if (text[i] == '\n') ++l;
  for (int c = 1; c < column && i < text.size(); ++c)
    do ++i; while (i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80);
  return text.substr(i);
}

void ExpectAt(const std::string& text, const std::string& pointer, size_t at) {
  const TextPosition got = LocateJsonPointer(text, pointer), want = Expected(text, at);
  EXPECT_EQ(got.line, want.line) << pointer;
  EXPECT_EQ(got.column, want.column) << pointer;
}

TEST(TextPosition, FollowsNestedArraysAndObjects) {
  const std::string text =
      "{\n  \"a\": [1, [2, 3], {\"b\": [4, {\"c\": 5}]}],\n  \"c\": {\"b\": 1}\n}\n";
  ExpectAt(text, "/a", text.find("\"a\""));
  ExpectAt(text, "/a/0", text.find("1,"));
  ExpectAt(text, "/a/1/1", text.find("3]"));
  ExpectAt(text, "/a/2/b/1/c", text.find("\"c\": 5"));
  ExpectAt(text, "/c/b", text.find("\"b\": 1}"));  // not the "b" inside /a/2
  ExpectAt(text, "/c", text.rfind("\"c\": {"));     // not the nested "c"
}

TEST(TextPosition, StringsWithEscapesAndKeysAsValues) {
  // A string value equal to the key, a key with an escaped quote and a \u escape,
  // brackets inside strings: none may be taken for structure.
  const std::string text = R"({"x": "\"axis\": [", "name": "axis", "q\"k": 1, "\u0061xis": [0, 0, 1]})";
  ExpectAt(text, "/axis", text.find("\"\\u0061xis\""));
  ExpectAt(text, "/q\"k", text.find("\"q\\\"k\""));
  ExpectAt(text, "/axis/2", text.find("1]"));
  const std::string pair = "{\"\xF0\x9F\x98\x80\": 1, \"\\ud83d\\ude00\": 2}";  // 😀 raw, then as a surrogate pair
  ExpectAt(pair, "/\xF0\x9F\x98\x80", pair.find("\"\\ud83d"));                 // the last occurrence wins
}

TEST(TextPosition, DuplicateKeysResolveToTheLastAndTokensUnescape) {
  const std::string text = "{\"k\": 1,\n \"k\": {\"a/b\": 1, \"m~n\": [7]}}";
  ExpectAt(text, "/k", text.rfind("\"k\""));
  ExpectAt(text, "/k/a~1b", text.find("\"a/b\""));
  ExpectAt(text, "/k/m~0n/0", text.find("7"));
}

TEST(TextPosition, ColumnsCountCodePointsAndMissingPartsFallBack) {
  const std::string text = "{\"name\": \"Kurbel–Schwinge ⚙\", \"joints\": [{\"type\": \"revolut\"}]}";
  ExpectAt(text, "/joints/0/type", text.find("\"type\""));
  EXPECT_LT(LocateJsonPointer(text, "/joints/0/type").column, static_cast<int>(text.find("\"type\"")) + 1);
  ExpectAt(text, "/joints/0/axis", text.find("{\"type\""));  // a missing key: its object
  ExpectAt(text, "/joints/3", text.find("\"joints\""));      // past the end: the array's key
  EXPECT_EQ(LocateJsonPointer(text, "").line, 0);
  EXPECT_EQ(LocateJsonPointer("not json", "/a").line, 1);    // the root value's place
}

// Through the check of a file: every error with a pointer is located, and the text
// at its place starts with the key's quoted name (or the element's value).
TEST(TextPosition, CheckLocatesEveryDiagnostic) {
  const std::string path = ::testing::TempDir() + "/three_errors.json";
  const std::string text =
      "{\"mechkin\": 1, \"name\": \"Gelenk–Test\",\n"
      " \"bodies\": [{\"name\": \"b\", \"position\": [0, 0, 0]}],\n"
      " \"joints\": [{\"name\": \"j\", \"type\": \"revolut\", \"body1\": \"ground\", \"body2\": \"b\",\n"
      "             \"origin\": [0, 0, 0], \"axsi\": [0, 0, 1]},\n"
      "            {\"name\": \"k\", \"type\": \"spherical\", \"body1\": \"ground\", \"body2\": \"bb\", \"origin\": [0, 0, 0]}]}\n";
  FILE* f = std::fopen(path.c_str(), "w");
  std::fputs(text.c_str(), f);
  std::fclose(f);
  const FileCheck c = CheckMechanismFile(path, CheckRequest{});
  EXPECT_EQ(c.verdict, CheckVerdict::Invalid);
  ASSERT_EQ(c.report.errors.size(), 3u);
  const std::map<std::string, int> line_of = {{"type", 3}, {"axsi", 4}, {"body2", 5}};
  for (const Diagnostic& d : c.report.errors) {
    const std::string key = d.pointer.substr(d.pointer.rfind('/') + 1);
    ASSERT_EQ(line_of.count(key), 1u) << d.pointer << ": " << d.message;
    EXPECT_EQ(d.line, line_of.at(key)) << d.pointer;
    EXPECT_EQ(TextAt(text, d.line, d.column).rfind("\"" + key + "\"", 0), 0u) << d.pointer;
  }
}

}  // namespace
}  // namespace mechkin
