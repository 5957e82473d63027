// Force units a file may name (issue "Describe mechanisms as designers do"):
// "units": {"force": "N", "torque": "N*m"} in a mm/kg file. Loads, spring stiffness
// (force / length), damping and preload are read in them, and the effort, reaction
// and energy columns are written in them; the same mechanism typed in the derived
// unit (kg·mm/s², kg·mm²/s²) gives the same forces, converted.
#include <gtest/gtest.h>

#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace force_units_test {

using nlohmann::json;
using testing_files::FromJson;
using testing_files::ReadJson;

// The bundled four-bar (mm, deg) with mass, gravity, a torque on the rocker, a force on
// the coupler and a spring-damper from ground to the rocker's pin, each number given
// in the unit `force_si` (N per file force unit) and `torque_si` (N·m per file torque unit).
json LoadedFourBar(const json& units, double force_si, double torque_si) {
  json doc = ReadJson("planar-four-bar.json");
  doc["units"] = units;
  doc["gravity"] = {0, -9810, 0};
  for (auto& b : doc["bodies"])
    b["inertia"] = {{"mass", 0.5}, {"center", b["position"]}, {"moments", {{400, 0, 0}, {0, 400, 0}, {0, 0, 400}}}};
  const double stiffness_si = force_si / 1e-3;  // N/m per file stiffness unit (force / mm)
  auto num = [](double v) { return json(v); };
  doc["loads"] = {
      {{"name", "brake"}, {"type", "torque"}, {"body", "rocker"},
       {"components", {0, 0, std::to_string(-3.0 / torque_si) + "*sin(2*pi*t)"}}},
      {{"name", "weight"}, {"type", "force"}, {"body", "coupler"}, {"point", doc["bodies"][1]["position"]},
       {"components", {num(20 / force_si), num(-200 / force_si), 0}}},
      {{"name", "spring"}, {"type", "spring"}, {"body1", "ground"}, {"point1", {150, 120, 0}}, {"body2", "rocker"},
       {"point2", doc["joints"][2]["origin"]}, {"stiffness", num(5000 / stiffness_si)},
       {"damping", num(20 / stiffness_si)}, {"preload", num(50 / force_si)}, {"free_length", 60}}};
  return doc;
}

Motion RunForces(const json& doc, bool si = false) {
  TableOptions table;
  table.order = 3;
  table.forces = true;
  table.si = si;
  return RunMotion(FromJson(doc), AnalysisOptions{}, table);
}

// Column `name` of m: its header unit and the values.
struct Column {
  std::string unit;
  std::vector<double> values;
};
Column Col(const Motion& m, const std::string& name) {
  const int c = m.layout().Find(name);
  EXPECT_GE(c, 0) << name;
  if (c < 0) return {};
  return {m.columns()[c].unit, m.Column(c)};
}

// Every value of `a` equals `ratio` × the value of `b` to 1e-10 of the column's scale.
void ExpectScaled(const Column& a, const Column& b, double ratio, const std::string& what) {
  ASSERT_EQ(a.values.size(), b.values.size()) << what;
  double scale = 0;
  for (double v : a.values) scale = std::max(scale, std::abs(v));
  ASSERT_GT(scale, 0) << what;
  for (size_t k = 0; k < a.values.size(); ++k) EXPECT_NEAR(a.values[k], ratio * b.values[k], 1e-10 * scale) << what << " row " << k;
}

TEST(ForceUnits, NamedUnitsGiveTheDerivedUnitsForcesConverted) {
  const json mm_kg = {{"length", "mm"}, {"angle", "deg"}, {"mass", "kg"}};
  json newton = mm_kg, newton_only = mm_kg;
  newton["force"] = "N", newton["torque"] = "N*m";
  newton_only["force"] = "N";
  // derived: force kg·mm/s² = 1e-3 N, torque kg·mm²/s² = 1e-6 N·m
  const Motion derived = RunForces(LoadedFourBar(mm_kg, 1e-3, 1e-6));
  const Motion named = RunForces(LoadedFourBar(newton, 1, 1));
  const Motion force_only = RunForces(LoadedFourBar(newton_only, 1, 1e-3));  // torque: N·mm
  ASSERT_TRUE(derived.complete && named.complete && force_only.complete);

  EXPECT_EQ(Col(derived, "motor.effort").unit, "kg*mm^2/s^2");  // unchanged without the keys
  EXPECT_EQ(Col(named, "motor.effort").unit, "N*m");
  EXPECT_EQ(Col(named, "motor.power").unit, "W");
  EXPECT_EQ(Col(named, "motor.effort_t").unit, "N*m/s");
  EXPECT_EQ(Col(named, "B.fx").unit, "N");
  EXPECT_EQ(Col(named, "B.mz").unit, "N*m");
  EXPECT_EQ(Col(named, "kinetic_energy").unit, "J");
  EXPECT_EQ(Col(named, "energy_balance").unit, "W");
  EXPECT_EQ(Col(force_only, "motor.effort").unit, "N*mm");
  EXPECT_EQ(Col(force_only, "B.fg").unit, "N");
  EXPECT_EQ(Col(force_only, "potential_energy").unit, "N*mm");
  EXPECT_EQ(Col(force_only, "motor.power").unit, "N*mm/s");

  // (the planar four-bar's reaction moments are round-off: the moment unit is checked on the table below)
  for (const char* torque : {"motor.effort", "motor.effort_t", "motor.power", "kinetic_energy", "potential_energy"}) {
    ExpectScaled(Col(derived, torque), Col(named, torque), 1e6, torque);
    ExpectScaled(Col(derived, torque), Col(force_only, torque), 1e3, torque);
  }
  for (const char* force : {"A.fx", "A.fy", "B.ff", "C.fg", "D.fx_t"}) {
    ExpectScaled(Col(derived, force), Col(named, force), 1e3, force);
    ExpectScaled(Col(derived, force), Col(force_only, force), 1e3, force);
  }
  // --si: the same SI table from either file.
  const Motion derived_si = RunForces(LoadedFourBar(mm_kg, 1e-3, 1e-6), true);
  const Motion named_si = RunForces(LoadedFourBar(newton, 1, 1), true);
  EXPECT_EQ(Col(named_si, "motor.effort").unit, "N*m");
  EXPECT_EQ(Col(named_si, "A.fx").unit, "N");
  for (const char* c : {"motor.effort", "A.fx", "kinetic_energy"}) ExpectScaled(Col(derived_si, c), Col(named_si, c), 1, c);
}

// The effort of a distance driver (a force) follows the named force unit too, a
// rotation driver's the torque unit: lbf and lbf*in against N and N*m.
TEST(ForceUnits, DistanceDriverEffortAndImperialUnits) {
  auto table = [](const json& units, double force) {
    json doc = ReadJson("planar-xy-table.json");
    doc["units"] = units;
    doc["gravity"] = {0, 0, -9810};
    // the centre of mass 20 mm off the joint: the planar joint carries a moment
    doc["bodies"][0]["inertia"] = {{"mass", 2}, {"center", {120, 100, 10}}, {"moments", {{1e3, 0, 0}, {0, 1e3, 0}, {0, 0, 1e3}}}};
    doc["loads"] = {{{"name", "push"}, {"type", "force"}, {"body", "block"}, {"point", {110, 100, 0}},
                     {"components", {force, force / 2, 0}}}};
    return RunForces(doc);
  };
  const Motion si = table({{"length", "mm"}, {"angle", "deg"}, {"force", "N"}, {"torque", "N*m"}}, 10);
  const Motion imperial =
      table({{"length", "mm"}, {"angle", "deg"}, {"force", "lbf"}, {"torque", "lbf*in"}}, 10 / 4.4482216152605);
  ASSERT_TRUE(si.complete && imperial.complete);
  EXPECT_EQ(Col(imperial, "cable_x.effort").unit, "lbf");
  ExpectScaled(Col(si, "cable_x.effort"), Col(imperial, "cable_x.effort"), 4.4482216152605, "cable_x.effort");
  ExpectScaled(Col(si, "table.fz"), Col(imperial, "table.fz"), 4.4482216152605, "table.fz");
  EXPECT_EQ(Col(imperial, "table.my").unit, "lbf*in");
  ExpectScaled(Col(si, "table.my"), Col(imperial, "table.my"), 4.4482216152605 * 0.0254, "table.my");
  EXPECT_EQ(Col(imperial, "turn.effort").unit, "lbf*in");
  ExpectScaled(Col(si, "turn.effort"), Col(imperial, "turn.effort"), 4.4482216152605 * 0.0254, "turn.effort");
  EXPECT_EQ(Col(imperial, "kinetic_energy").unit, "lbf*in");
}

// Unknown names: the pointer, the problem and a did-you-mean with the accepted names.
TEST(ForceUnits, BadUnitNamesAreNamedWithAFix) {
  json doc = ReadJson("planar-four-bar.json");
  doc["units"]["force"] = "kn";
  doc["units"]["torque"] = "Nm";
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.errors.size(), 2u);
  EXPECT_EQ(r.errors[0].pointer, "/units/force");
  EXPECT_EQ(r.errors[0].message, "unknown force unit 'kn'");
  EXPECT_EQ(r.errors[0].fix, "did you mean 'kN'? use one of N, kN, mN, lbf");
  EXPECT_EQ(r.errors[1].pointer, "/units/torque");
  EXPECT_EQ(r.errors[1].message, "unknown torque unit 'Nm'");
  EXPECT_EQ(r.errors[1].fix, "did you mean 'N*m'? use one of N*m, N*mm, N*cm, kN*m, lbf*in, lbf*ft");
  doc["units"] = {{"length", "mm"}, {"torque", "Nmm"}};  // N*m is one edit away too: the spelling wins
  const LoadResult spelled = LoadMechanismText(doc.dump(), "inline");
  ASSERT_FALSE(spelled.ok());
  EXPECT_EQ(spelled.errors[0].fix, "did you mean 'N*mm'? use one of N*m, N*mm, N*cm, kN*m, lbf*in, lbf*ft");
  doc["units"] = {{"length", "mm"}, {"force", 5}};
  const LoadResult typed = LoadMechanismText(doc.dump(), "inline");
  ASSERT_FALSE(typed.ok());
  EXPECT_EQ(typed.errors[0].pointer, "/units/force");
}

}  // namespace
}  // namespace mechkin
