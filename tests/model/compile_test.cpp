// The spec layer and the compile step (issue "Describe mechanisms as designers do"):
// specs built in C++ without JSON, parameters resolved in dependency order, every
// variant compiled from the spec, and the model keeping no file text.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <type_traits>

#include "analysis/motion.hpp"
#include "model/compile.hpp"
#include "analysis/load.hpp"
#include "spec/reader.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace compile_test {

using nlohmann::json;

// Model and MechanismSpec keep no document text (the member the loader used to carry).
template <typename T, typename = void>
struct HasDocument : std::false_type {};
template <typename T>
struct HasDocument<T, std::void_t<decltype(std::declval<T>().document)>> : std::true_type {};
static_assert(!HasDocument<Model>::value, "Model must not keep the file text");
static_assert(!HasDocument<MechanismSpec>::value, "a spec is structs, not text");
static_assert(std::is_same_v<decltype(Model::spec), std::shared_ptr<const MechanismSpec>>);

Vector3Spec Vec(Scalar x, Scalar y, Scalar z, const std::string& key, const std::string& ptr) {
  Vector3Spec v;
  v.c = {std::move(x), std::move(y), std::move(z)};
  v.key = key;
  v.pointer = ptr;
  return v;
}

// A crank of length L (mm), its centre at L/2 on x, turned 90° about z at the design
// pose; revolute A at the origin, driven 360°/s. Built without JSON.
MechanismSpec CrankSpec() {
  MechanismSpec s;
  s.version = Scalar::Of(1);
  s.name = "crank";
  s.source = "built in C++";
  s.units = UnitsSpec{std::string("mm"), std::string("deg"), std::nullopt, std::nullopt, std::nullopt};
  s.parameters.push_back({"half", Scalar::Expr("L/2", "/parameters/half"), std::nullopt, std::nullopt, std::nullopt});
  s.parameters.push_back({"L", Scalar::Of(40, "/parameters/L"), 0.1, std::nullopt, std::nullopt});
  BodySpec b;
  b.name = "crank";
  b.pointer = "/bodies/0";
  b.position = Vec(Scalar::Expr("half"), Scalar::Of(0), Scalar::Of(0), "position", "/bodies/0/position");
  OrientationSpec o;
  o.axis = Vector3Spec::Of(0, 0, 1, "axis", "/bodies/0/orientation/axis");
  o.angle = Scalar::Of(90);
  b.orientation = o;
  s.bodies.push_back(b);
  JointSpec j;
  j.name = "A";
  j.type = "revolute";
  j.body1 = "ground";
  j.body2 = "crank";
  j.origin = Vector3Spec::Of(0, 0, 0, "origin", "/joints/0/origin");
  j.axis = Vector3Spec::Of(0, 0, 1, "axis", "/joints/0/axis");
  j.pointer = "/joints/0";
  s.joints.push_back(j);
  DriverSpec d;
  d.name = "motor";
  d.type = "rotation";
  d.joint = "A";
  d.function = FunctionSpec{FunctionSpec::Kind::Expression, "360*t", {}, {}, "quintic", "/drivers/0/function"};
  d.pointer = "/drivers/0";
  s.drivers.push_back(d);
  s.analysis = AnalysisSpec{Scalar::Of(0), Scalar::Of(1), Scalar::Of(4), std::nullopt, true};
  return s;
}

TEST(Compile, ASpecBuiltInCppCompilesToSi) {
  const LoadResult r = Compile(CrankSpec());
  ASSERT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  const Model& m = *r.model;
  ASSERT_EQ(m.bodies.size(), 1u);
  EXPECT_NEAR(m.bodies[0].position.x(), 0.020, 1e-15);  // L/2 = 20 mm
  EXPECT_NEAR(m.bodies[0].euler[0], std::sqrt(0.5), 1e-15);  // 90° about z
  EXPECT_NEAR(m.bodies[0].euler[3], std::sqrt(0.5), 1e-15);
  // Joint A's origin in the crank's axes: Aᵀ(0 − r) = Rz(−90°)(−0.02, 0, 0) = (0, 0.02, 0).
  const Joint& a = m.joints[0];
  EXPECT_EQ(a.body1, kGround);
  EXPECT_EQ(a.body2, 0);
  EXPECT_NEAR(a.frame2.origin.x(), 0, 1e-15);
  EXPECT_NEAR(a.frame2.origin.y(), 0.020, 1e-15);
  EXPECT_NEAR(a.frame2.h.z(), 1, 1e-15);
  EXPECT_NEAR(m.drivers[0].function.Eval(0.25).c[0], M_PI / 2, 1e-15);  // 90° in rad
  EXPECT_NEAR(m.drivers[0].function.Eval(0.25).c[1], 2 * M_PI, 1e-14);
  EXPECT_EQ(m.FindParameter("half")->value, 20);
  EXPECT_EQ(*m.FindParameter("L")->tolerance, 0.1);
  EXPECT_EQ(m.FindParameter("half")->expression, "L/2");
  ASSERT_TRUE(m.spec);
  EXPECT_EQ(m.spec->source, "built in C++");
}

TEST(Compile, OverridesRecompileTheSameSpec) {
  auto spec = std::make_shared<const MechanismSpec>(CrankSpec());
  const LoadResult r = Compile(spec, {{"L", 60}});
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.model->bodies[0].position.x(), 0.030, 1e-15);
  EXPECT_TRUE(r.model->FindParameter("L")->overridden);
  EXPECT_EQ(r.model->spec, spec);  // shared, not copied
  const LoadResult again = WithParameters(*r.model, {{"L", 80}});
  ASSERT_TRUE(again.ok());
  EXPECT_NEAR(again.model->bodies[0].position.x(), 0.040, 1e-15);
  const LoadResult unknown = Compile(spec, {{"Lx", 1}});
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.errors[0].fix, "did you mean 'L'?");
}

// 3000 parameters, each defined from the one before and declared last-first (the
// worst order for repeated passes): all resolved, each to its closed form k + 1.
// By hand (Release, under load): well under the 0.2 s the issue asks.
TEST(Compile, ChainedParametersResolveInDependencyOrder) {
  MechanismSpec s = CrankSpec();
  constexpr int kChain = 3000;
  for (int k = kChain - 1; k >= 0; --k) {
    const std::string name = "p" + std::to_string(k);
    s.parameters.push_back({name, k == 0 ? Scalar::Of(1) : Scalar::Expr("p" + std::to_string(k - 1) + "+1"),
                            std::nullopt, std::nullopt, std::nullopt});
  }
  s.bodies[0].position->c[1] = Scalar::Expr("p2999 - 3000");  // 0 when the chain is right
  const LoadResult r = Compile(s);
  ASSERT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors[0].ToString());
  for (int k = 0; k < kChain; ++k) ASSERT_EQ(r.model->FindParameter("p" + std::to_string(k))->value, k + 1) << k;
  EXPECT_EQ(r.model->bodies[0].position.y(), 0);
}

bool Mentions(const LoadResult& r, const std::string& words) {
  for (const auto& e : r.errors)
    if ((e.message + " " + e.fix).find(words) != std::string::npos) return true;
  return false;
}

std::string AllErrors(const LoadResult& r) {
  std::string s;
  for (const auto& e : r.errors) s += e.ToString() + "\n";
  return s;
}

TEST(Compile, ACycleNamesOnlyItsMembers) {
  json doc = testing_files::ReadJson("parametric-four-bar.json");
  doc["parameters"]["a"] = "b2 + 1";
  doc["parameters"]["b2"] = "a - 1";  // a ↔ b2; xb, yb, e, ... only use a
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_EQ(r.errors.size(), 1u) << AllErrors(r);
  EXPECT_EQ(r.errors[0].pointer, "/parameters/a");
  EXPECT_EQ(r.errors[0].message, "parameters defined in terms of each other: a, b2");
  EXPECT_FALSE(Mentions(r, "unknown name"));
}

TEST(Compile, AFailingParameterDoesNotMakeItsUsersUnknown) {
  json doc = testing_files::ReadJson("parametric-four-bar.json");
  doc["parameters"]["c"] = 5;  // the rocker cannot reach: acos out of its domain in psi
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_EQ(r.errors.size(), 1u) << AllErrors(r);
  EXPECT_EQ(r.errors[0].pointer, "/parameters/psi");
  EXPECT_TRUE(Mentions(r, "cannot be evaluated"));
  EXPECT_FALSE(Mentions(r, "unknown name"));  // xc, yc and the geometry using them stay quiet
}

// A variant compiled from the spec equals a fresh load of the file with --set,
// number for number, and runs to the same table.
TEST(Compile, WithParametersEqualsAFreshLoadWithSet) {
  const std::string path = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json";
  const LoadResult base = LoadMechanismFile(path);
  ASSERT_TRUE(base.ok());
  const ParameterOverrides set = {{"a", 45}, {"start", 75}};
  const LoadResult variant = WithParameters(*base.model, set), fresh = LoadMechanismFile(path, set);
  ASSERT_TRUE(variant.ok() && fresh.ok());
  const Model &v = *variant.model, &f = *fresh.model;
  ASSERT_EQ(v.bodies.size(), f.bodies.size());
  for (size_t b = 0; b < v.bodies.size(); ++b) {
    EXPECT_EQ(v.bodies[b].position, f.bodies[b].position);
    EXPECT_EQ(v.bodies[b].euler, f.bodies[b].euler);
  }
  for (size_t j = 0; j < v.joints.size(); ++j) {
    EXPECT_EQ(v.joints[j].frame1.origin, f.joints[j].frame1.origin);
    EXPECT_EQ(v.joints[j].frame2.origin, f.joints[j].frame2.origin);
  }
  EXPECT_NE(v.bodies[0].position, base.model->bodies[0].position);  // the override took effect
  const Motion mv = RunMotion(v, AnalysisOptions{}, TableOptions{}), mf = RunMotion(f, AnalysisOptions{}, TableOptions{});
  ASSERT_TRUE(mv.complete && mf.complete);
  EXPECT_EQ(mv.values(), mf.values());
}

// Variants evaluate the spec's expressions parsed once (model/expression_cache.hpp):
// they share the base model's cache, and an override that breaks an expression gets
// the diagnostic a fresh load with --set gets.
TEST(Compile, VariantsShareTheParsedExpressionsAndKeepTheirDiagnostics) {
  const std::string path = std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-slider-crank.json";
  const LoadResult base = LoadMechanismFile(path);
  ASSERT_TRUE(base.ok());
  ASSERT_NE(base.model->expressions, nullptr);
  const LoadResult variant = WithParameters(*base.model, {{"rod", 125}});
  ASSERT_TRUE(variant.ok());
  EXPECT_EQ(variant.model->expressions, base.model->expressions);
  // rod shorter than the offset: slider_x = pin_x + sqrt(rod^2 - (offset - pin_y)^2) is sqrt of < 0
  const ParameterOverrides broken = {{"rod", 5}};
  const LoadResult bad = WithParameters(*base.model, broken), fresh = LoadMechanismFile(path, broken);
  ASSERT_FALSE(bad.ok());
  ASSERT_EQ(bad.errors.size(), fresh.errors.size());
  for (size_t k = 0; k < bad.errors.size(); ++k) {
    EXPECT_EQ(bad.errors[k].pointer, fresh.errors[k].pointer);
    EXPECT_EQ(bad.errors[k].message, fresh.errors[k].message);
  }
  EXPECT_NE(bad.errors.front().pointer.find("/parameters/slider_x"), std::string::npos) << bad.errors.front().pointer;
}

TEST(SpecReader, ElementsKeepTheirPointersAndExpressions) {
  std::ifstream in(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/parametric-four-bar.json");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const SpecReadResult r = ReadMechanismSpec(text, "four-bar");
  ASSERT_TRUE(r.spec && r.spec->valid);
  const JointSpec& b = r.spec->joints[1];
  EXPECT_EQ(*b.name, "B");
  ASSERT_TRUE(b.origin);
  EXPECT_EQ(b.origin->c[0].kind, Scalar::Kind::Expression);
  EXPECT_EQ(b.origin->c[0].text, "xb");
  EXPECT_EQ(b.origin->c[0].pointer, "/joints/1/origin/0");
  EXPECT_EQ(r.spec->parameters.size(), 12u);
  EXPECT_EQ(*r.spec->parameters[0].tolerance, 0.05);  // "a", the first key in order
}

// The reader's structural errors and compile's value errors come in file order.
TEST(SpecReader, DiagnosticsKeepTheFileOrder) {
  json doc = testing_files::ReadJson("parametric-four-bar.json");
  doc["bodies"][0]["position"][0] = "xbb/2";  // compile: unknown name (body 0)
  doc["bodies"][1]["colour"] = "red";          // reader: unknown key (body 1)
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_GE(r.errors.size(), 2u);
  EXPECT_EQ(r.errors[0].pointer, "/bodies/0/position/0");
  EXPECT_EQ(r.errors[0].fix, "did you mean 'xb'?");
  EXPECT_EQ(r.errors[1].pointer, "/bodies/1/colour");
}

TEST(SpecReader, ASchemaKeyIsAcceptedAndIgnored) {
  json doc = testing_files::ReadJson("planar-four-bar.json");
  doc["$schema"] = "../schema/mechkin-format-v1.schema.json";
  EXPECT_TRUE(LoadMechanismText(doc.dump(), "inline").ok());
  doc["$schema"] = 3;
  const LoadResult r = LoadMechanismText(doc.dump(), "inline");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors[0].pointer, "/$schema");
  EXPECT_EQ(r.errors[0].message, "'$schema' must be a string, not a number");
}

// nlohmann_json stays in the spec layer (and io above the core).
TEST(SpecLayer, NoJsonHeaderBelowTheSpecReader) {
  namespace fs = std::filesystem;
  int scanned = 0;
  for (const char* dir : {"math", "model", "constraints", "kinematics", "mobility", "analysis"})
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(MECHKIN_SOURCE_DIR) / "src" / dir)) {
      std::ifstream f(entry.path());
      const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
      EXPECT_EQ(text.find("nlohmann"), std::string::npos) << entry.path();
      ++scanned;
    }
  EXPECT_GT(scanned, 40);
}

}  // namespace
}  // namespace mechkin
