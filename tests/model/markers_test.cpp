// Markers (issue "Describe mechanisms as designers do"): frames fixed in a body,
// named by joints and point outputs instead of global design coordinates.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "analysis/motion.hpp"
#include "analysis/load.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace markers_test {

using nlohmann::json;

std::string Errors(const LoadResult& r) {
  std::string s;
  for (const auto& e : r.errors) s += e.ToString() + "\n";
  return s;
}

// The bundled planar four-bar (bodies unrotated) with every joint on two markers:
// each body carries the joint's point in its own coordinates (point − position),
// ground its markers in the top-level "ground"; the coupler point named by a marker.
json FourBarWithMarkers() {
  json doc = testing_files::ReadJson("planar-four-bar.json");
  std::map<std::string, json> position = {{"ground", json::array({0, 0, 0})}};
  for (const auto& b : doc["bodies"]) position[b["name"]] = b["position"];
  std::map<std::string, json> markers;  // body → its markers
  auto add = [&](const std::string& body, const std::string& name, const json& origin, const json& axis) {
    json local = json::array();
    for (int k = 0; k < 3; ++k) local.push_back(origin[k].get<double>() - position[body][k].get<double>());
    markers[body][name] = {{"point", local}, {"axis", axis}};
  };
  for (auto& j : doc["joints"]) {
    const std::string name = j["name"];
    add(j["body1"], name + "1", j["origin"], j["axis"]);
    add(j["body2"], name + "2", j["origin"], j["axis"]);
    j.erase("origin");
    j.erase("axis");
    j["marker1"] = name + "1";
    j["marker2"] = name + "2";
  }
  for (auto& out : doc["outputs"])
    if (out["type"] == "point") {
      add(out["body"], out["name"].get<std::string>(), out["point"], json::array({0, 0, 1}));
      out.erase("point");
      out["marker"] = out["name"];
    }
  for (auto& b : doc["bodies"]) b["markers"] = markers[b["name"]];
  doc["ground"] = {{"markers", markers["ground"]}};
  return doc;
}

// Same joint points and axes in both bodies as the global form, and the same
// motion to the solver's tolerance: every column to 1e-9 of its largest magnitude
// (the joint frames' x axes differ — any perpendicular in the global form, the
// body's x for a marker — so the equations are the same up to a rotation, not bit
// for bit).
TEST(Markers, FourBarOnMarkersMatchesTheGlobalForm) {
  const Model global = testing_files::FromJson(testing_files::ReadJson("planar-four-bar.json"));
  const LoadResult r = LoadMechanismText(FourBarWithMarkers().dump(), "inline");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Model& m = *r.model;
  ASSERT_EQ(m.joints.size(), global.joints.size());
  for (size_t j = 0; j < m.joints.size(); ++j) {
    EXPECT_LT((m.joints[j].frame1.origin - global.joints[j].frame1.origin).norm(), 1e-15) << j;
    EXPECT_LT((m.joints[j].frame2.origin - global.joints[j].frame2.origin).norm(), 1e-15) << j;
    EXPECT_LT((m.joints[j].frame1.h - global.joints[j].frame1.h).norm(), 1e-15) << j;
    EXPECT_LT((m.joints[j].frame2.h - global.joints[j].frame2.h).norm(), 1e-15) << j;
  }
  const Motion a = RunMotion(global, AnalysisOptions{}, TableOptions{}), b = RunMotion(m, AnalysisOptions{}, TableOptions{});
  ASSERT_TRUE(a.complete && b.complete) << b.stop.message;
  ASSERT_EQ(a.cols(), b.cols());
  ASSERT_EQ(a.rows(), b.rows());
  for (int c = 0; c < a.cols(); ++c) {
    const std::string name = a.columns()[c].Header();
    if (name.rfind("newton_iterations", 0) == 0 || name.rfind("residual", 0) == 0 ||
        name.rfind("condition", 0) == 0 || name.rfind("error_bound", 0) == 0)
      continue;  // the solver's own diagnostics depend on the frames
    double scale = 0, worst = 0;
    for (int row = 0; row < a.rows(); ++row) {
      scale = std::max(scale, std::abs(a.at(row, c)));
      worst = std::max(worst, std::abs(a.at(row, c) - b.at(row, c)));
    }
    EXPECT_LE(worst, 1e-9 * std::max(scale, 1.0)) << a.columns()[c].Header();
  }
}

// The coupler replaced by a distance link of length 120 mm between a pin marker on
// the crank and one on the rocker: the rocker turns as in the four-bar.
TEST(Markers, DistanceLinkBetweenMarkersActsAsTheCoupler) {
  const Model four_bar = testing_files::FromJson(testing_files::ReadJson("planar-four-bar.json"));
  json doc = FourBarWithMarkers();
  doc["bodies"].erase(1);  // the coupler
  json joints = json::array();
  for (const auto& j : doc["joints"])
    if (j["body1"] != "coupler" && j["body2"] != "coupler") joints.push_back(j);
  doc["bodies"][0]["markers"]["pin"] = {{"point", {10, 17.320508075689, 0}}};           // B − crank position
  doc["bodies"][1]["markers"]["pin"] = {{"point", {16.940482998025, 36.235618330499, 0}}};  // C − rocker position
  joints.push_back({{"name", "link"}, {"type", "distance"}, {"body1", "crank"}, {"body2", "rocker"},
                    {"marker1", "pin"}, {"marker2", "pin"}, {"length", 120}});
  doc["joints"] = joints;
  doc["outputs"] = json::array({{{"name", "rocker_angle"}, {"type", "joint"}, {"joint", "D"}}});
  doc.erase("expect");
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_TRUE(r.ok()) << Errors(r);
  EXPECT_EQ(r.model->joints.back().length, 0.120);
  const Motion a = RunMotion(four_bar, AnalysisOptions{}, TableOptions{});
  const Motion b = RunMotion(*r.model, AnalysisOptions{}, TableOptions{});
  ASSERT_TRUE(a.complete && b.complete) << b.stop.message;
  const int ca = a.layout().Find("rocker_angle"), cb = b.layout().Find("rocker_angle");
  ASSERT_GE(ca, 0);
  ASSERT_GE(cb, 0);
  for (int row = 0; row < a.rows(); ++row) EXPECT_NEAR(a.at(row, ca), b.at(row, cb), 1e-9) << row;
}

TEST(Markers, AnUnknownMarkerIsNamedWithTheBodysMarkers) {
  json doc = FourBarWithMarkers();
  doc["joints"][1]["marker2"] = "B3";
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors[0].pointer, "/joints/1/marker2");
  EXPECT_EQ(r.errors[0].message, "unknown marker 'B3' on body 'coupler'");
  EXPECT_EQ(r.errors[0].fix, "did you mean 'B2'?");
}

TEST(Markers, AMarkerJointTakesNoGlobalGeometry) {
  json doc = FourBarWithMarkers();
  doc["joints"][0]["origin"] = {0, 0, 0};
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors[0].pointer, "/joints/0/origin");
  EXPECT_EQ(r.errors[0].message, "unknown key 'origin' in a revolute joint");
}

}  // namespace
}  // namespace mechkin
