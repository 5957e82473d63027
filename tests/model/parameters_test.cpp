// Parameters in the file format (issue "Parametric designs", item 1): values,
// expressions over them, overrides, and the errors a slip produces.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "analysis/load.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace parameters_test {

using nlohmann::json;

json ParametricSliderCrank() { return testing_files::ReadJson("parametric-slider-crank.json"); }

LoadResult Load(const json& doc, const ParameterOverrides& set = {}) {
  return LoadMechanismText(doc.dump(), "inline", set);
}

bool HasError(const LoadResult& r, const std::string& pointer, const std::string& words) {
  for (const auto& e : r.errors)
    if (e.pointer == pointer && (e.message + " " + e.fix).find(words) != std::string::npos) return true;
  return false;
}

// The parametric file describes the bundled offset slider-crank: same joint
// frames (local points) to round-off as the hand-typed coordinates.
TEST(Parameters, ExpressionsReproduceTheHandTypedFile) {
  const LoadResult p = Load(ParametricSliderCrank());
  ASSERT_TRUE(p.ok()) << p.errors[0].ToString();
  const Model hand = testing_files::FromJson(testing_files::ReadJson("offset-slider-crank.json"));
  ASSERT_EQ(p.model->joints.size(), hand.joints.size());
  for (size_t j = 0; j < hand.joints.size(); ++j) {
    EXPECT_LT((p.model->joints[j].frame1.origin - hand.joints[j].frame1.origin).norm(), 1e-14) << j;
    EXPECT_LT((p.model->joints[j].frame2.origin - hand.joints[j].frame2.origin).norm(), 1e-14) << j;
  }
  const Parameter* x = p.model->FindParameter("slider_x");
  ASSERT_NE(x, nullptr);
  EXPECT_NEAR(x->value, 20 * std::sqrt(3.0) + std::sqrt(120.0 * 120 - 100), 1e-12);
  EXPECT_EQ(x->expression, "pin_x + sqrt(rod^2 - (offset - pin_y)^2)");
  EXPECT_DOUBLE_EQ(*p.model->FindParameter("rod")->tolerance, 0.05);
}

TEST(Parameters, OverridesChangeTheDerivedGeometry) {
  const LoadResult p = Load(ParametricSliderCrank(), {{"crank", 50}});
  ASSERT_TRUE(p.ok());
  EXPECT_TRUE(p.model->FindParameter("crank")->overridden);
  EXPECT_NEAR(p.model->FindParameter("pin_x")->value, 25 * std::sqrt(3.0), 1e-12);
  // The crank pin on the crank body: at (pin_x, pin_y) − crank origin (pin_x/2, pin_y/2), in m.
  EXPECT_NEAR(p.model->joints[1].frame1.origin.x(), 12.5e-3 * std::sqrt(3.0), 1e-15);
  // WithParameters keeps earlier overrides and adds new ones.
  const LoadResult q = WithParameters(*p.model, {{"rod", 130}});
  ASSERT_TRUE(q.ok());
  EXPECT_EQ(q.model->FindParameter("crank")->value, 50);
  EXPECT_EQ(q.model->FindParameter("rod")->value, 130);
}

TEST(Parameters, UnknownNameGetsDidYouMeanAtItsPointer) {
  json doc = ParametricSliderCrank();
  doc["joints"][1]["origin"][0] = "pinx";
  const LoadResult r = Load(doc);
  EXPECT_TRUE(HasError(r, "/joints/1/origin/0", "did you mean 'pin_x'?")) << r.errors[0].ToString();
}

TEST(Parameters, CyclesAreNamed) {
  json doc = ParametricSliderCrank();
  doc["parameters"]["crank"] = "2*rod";
  doc["parameters"]["rod"] = "crank/2";
  const LoadResult r = Load(doc);
  ASSERT_FALSE(r.ok());
  bool found = false;
  for (const auto& e : r.errors)
    found |= e.message.find("defined in terms of each other") != std::string::npos &&
             e.message.find("crank") != std::string::npos && e.message.find("rod") != std::string::npos;
  EXPECT_TRUE(found) << r.errors[0].ToString();
}

TEST(Parameters, AValueThatBreaksTheGeometryNamesTheParameter) {
  // A rod shorter than the offset: the square root of a negative number.
  const LoadResult r = Load(ParametricSliderCrank(), {{"rod", 5}});
  EXPECT_TRUE(HasError(r, "/parameters/slider_x", "cannot be evaluated")) << r.errors[0].ToString();
}

TEST(Parameters, TimeIsRejectedInGeometry) {
  json doc = ParametricSliderCrank();
  doc["bodies"][0]["position"][2] = "t";
  EXPECT_TRUE(HasError(Load(doc), "/bodies/0/position/2", "'t' is not allowed here"));
}

TEST(Parameters, DriverFunctionsMayUseParameters) {
  json doc = ParametricSliderCrank();
  doc["parameters"]["speed"] = 720;
  doc["drivers"][0]["function"] = "speed*t";
  const LoadResult r = Load(doc);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.model->drivers[0].function.Eval(0.5).c[0], 360 * M_PI / 180, 1e-15);
}

TEST(Parameters, UnknownOverrideIsAnError) {
  const LoadResult r = Load(ParametricSliderCrank(), {{"crnk", 1}});
  EXPECT_TRUE(HasError(r, "/parameters", "did you mean 'crank'?"));
}

TEST(Parameters, BadDeclarations) {
  json doc = ParametricSliderCrank();
  doc["parameters"]["sin"] = 1;
  doc["parameters"]["rod"]["tolerance"] = -1;
  doc["parameters"]["offset"]["max"] = -5;
  const LoadResult r = Load(doc);
  EXPECT_TRUE(HasError(r, "/parameters/sin", "invalid parameter name"));
  EXPECT_TRUE(HasError(r, "/parameters/rod/tolerance", "must not be negative"));
  EXPECT_TRUE(HasError(r, "/parameters/offset/max", "greater than 'min'"));
}

}  // namespace
}  // namespace mechkin
