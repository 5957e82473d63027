#include <gtest/gtest.h>

#include "model/loader.hpp"

namespace mechkin {
namespace {

bool HasPointer(const LoadResult& r, const std::string& p) {
  for (const auto& e : r.errors)
    if (e.pointer == p) return true;
  return false;
}

TEST(Loader, ReportsAllErrorsAtOnce) {
  const std::string text = R"({"mechkin": 1,
    "bodies": [{"name": "a", "position": [0, 0]}, {"name": "a", "position": [1, 0, 0]}],
    "joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "b", "origin": [0, 0, 0], "axis": [0, 0, 0]}],
    "analysis": {"start": 1, "end": 0, "steps": 0}})";
  const LoadResult r = LoadMechanismText(text, "inline");
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(HasPointer(r, "/bodies/0/position"));
  EXPECT_TRUE(HasPointer(r, "/bodies/1/name"));
  EXPECT_TRUE(HasPointer(r, "/joints/0/body2"));
  EXPECT_TRUE(HasPointer(r, "/joints/0/axis"));
  EXPECT_TRUE(HasPointer(r, "/analysis/end"));
  EXPECT_TRUE(HasPointer(r, "/analysis/steps"));
}

TEST(Loader, DidYouMeanForKeysAndNames) {
  const std::string text = R"({"mechkin": 1, "bodies": [{"name": "crank", "position": [0, 0, 0]}],
    "joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "crnak", "origin": [0, 0, 0], "axsi": [0, 0, 1]}]})";
  const LoadResult r = LoadMechanismText(text, "inline");
  ASSERT_FALSE(r.ok());
  bool key = false, name = false;
  for (const auto& e : r.errors) {
    if (e.pointer == "/joints/0/axsi") key = e.fix.find("did you mean 'axis'") != std::string::npos;
    if (e.pointer == "/joints/0/body2") name = e.fix.find("did you mean 'crank'") != std::string::npos;
  }
  EXPECT_TRUE(key);
  EXPECT_TRUE(name);
}

TEST(Loader, SyntaxErrorHasLineAndColumn) {
  const LoadResult r = LoadMechanismText("{\n  \"mechkin\": 1,\n  \"bodies\": [,]\n}", "inline");
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_NE(r.errors[0].message.find("line 3, column 14"), std::string::npos) << r.errors[0].message;
}

TEST(Loader, HostileInputsDoNotThrow) {
  for (const std::string& text : {std::string(""), std::string("\0\1\2", 3), std::string(200000, '['),
                                  std::string("{\"mechkin\": 1e999}"), std::string("nul"), std::string("\"x\""),
                                  std::string("{\"mechkin\": 1, \"bodies\": [{\"name\": \"b\", \"position\": [\"Infinity\", 0, 0]}], \"joints\": []}")}) {
    LoadResult r;
    EXPECT_NO_THROW(r = LoadMechanismText(text, "inline"));
    EXPECT_FALSE(r.ok());
  }
}

TEST(Loader, MissingFileIsAnError) {
  const LoadResult r = LoadMechanismFile("/nonexistent/file.json");
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_NE(r.errors[0].message.find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace mechkin
