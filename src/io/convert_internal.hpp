// Internal to src/io: the pieces of `mechkin convert` (io/convert.hpp) — the
// JSON document edited in place (ordered, so the file's key order survives),
// exact expression texts where the geometry depends on parameters, and tidy numbers.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

#include "io/convert.hpp"

namespace mechkin::convert {

using Json = nlohmann::ordered_json;

struct Context {
  const Model& model;
  const MechanismSpec& spec;
  double unit = 1;   // metres per file length unit
  double scale = 1;  // the mechanism's size in file units (round-off below 1e-13 of it is 0)
  std::vector<std::string>* notes;
  std::map<std::string, BodyIndex> body_index;  // "ground" included
  std::map<std::string, int> joint_index, output_index;

  const BodySpec* Body(BodyIndex b) const;  // nullptr for ground
  /// The design pose of body b (ground: identity).
  std::pair<Vec3, Mat3> Pose(BodyIndex b) const;
  void Note(const std::string& pointer, const std::string& what) const;
};

Context MakeContext(const Model& model, std::vector<std::string>* notes);

/// A number of the file as JSON: integral values as integers, the rest in the
/// shortest form; within 2 ulp of a 15-digit decimal it is that decimal, and
/// below 1e-13 of `scale` it is 0 (round-off of a subtraction, never data).
Json Number(double v, double scale);
Json NumberVector(const Vec3& v, double scale);
Json ScalarJson(const Scalar& s);
Json VectorJson(const Vector3Spec& v);
/// a − b and a + b, exact: a number when both are numbers, else an expression text.
Json Difference(const Scalar& a, const Scalar& b, double scale);
Json Sum(const Scalar& a, const Scalar& b, double scale);

bool UsesParameters(const Scalar& s);
bool UsesParameters(const std::optional<Vector3Spec>& v);
bool UsesParameters(const std::optional<OrientationSpec>& o);
/// The body's orientation is the identity, written with literal numbers (or absent).
bool LiteralIdentity(const std::optional<OrientationSpec>& o);

/// An object with `key` put before `before` (or at the end when `before` is absent).
void InsertBefore(Json* object, const std::string& before, const std::string& key, Json value);

/// The document, indented by 2, short arrays and objects on one line.
std::string Dump(const Json& doc);

/// The two directions; false with *error when the file cannot be converted exactly.
bool ToMarkers(const Context& ctx, Json* doc, std::string* error);
bool ToGlobal(const Context& ctx, Json* doc, std::string* error);

}  // namespace mechkin::convert
