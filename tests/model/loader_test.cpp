#include <gtest/gtest.h>

#include "analysis/load.hpp"

namespace mechkin {
namespace loader_test {

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

// The optional drawing shape: read in body coordinates and scaled by the file's length unit;
// a bad shape names its place in the file.
TEST(Loader, BodyShapeIsScaledAndChecked) {
  const std::string ok = R"({"mechkin": 1, "units": {"length": "mm"},
    "bodies": [{"name": "crank", "position": [0, 0, 0],
                "shape": {"type": "cylinder", "radius": 5, "length": 40, "axis": [0, 0, 2], "center": [10, 0, 0]}}],
    "joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "crank", "origin": [0, 0, 0], "axis": [0, 0, 1]}]})";
  const LoadResult r = LoadMechanismText(ok, "inline");
  ASSERT_TRUE(r.ok());
  const auto& shape = r.model->bodies[0].shape;
  ASSERT_TRUE(shape.has_value());
  EXPECT_EQ(shape->kind, Shape::Kind::Cylinder);
  EXPECT_DOUBLE_EQ(shape->radius, 0.005);
  EXPECT_DOUBLE_EQ(shape->length, 0.040);
  EXPECT_DOUBLE_EQ(shape->center.x(), 0.010);
  EXPECT_DOUBLE_EQ(shape->axis.z(), 1.0);

  const std::string bad = R"({"mechkin": 1,
    "bodies": [{"name": "a", "position": [0, 0, 0], "shape": {"type": "cone", "radius": 1}},
               {"name": "b", "position": [0, 0, 0], "shape": {"type": "cylinder", "radius": -1, "length": 1, "axis": [0, 0, 0]}}],
    "joints": []})";
  const LoadResult e = LoadMechanismText(bad, "inline");
  EXPECT_FALSE(e.ok());
  EXPECT_TRUE(HasPointer(e, "/bodies/0/shape/type"));
  EXPECT_TRUE(HasPointer(e, "/bodies/1/shape/radius"));
  EXPECT_TRUE(HasPointer(e, "/bodies/1/shape/axis"));
}

TEST(Loader, MissingFileIsAnError) {
  const LoadResult r = LoadMechanismFile("/nonexistent/file.json");
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_NE(r.errors[0].message.find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace mechkin
