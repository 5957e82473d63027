// Internal to src/importers: the kinematic graph every format reader fills (links
// with their poses as written, joints with their frames in both links, couplings)
// and the one builder that turns it into a MechanismSpec (build_spec.cpp).
#pragma once

#include <tinyxml2.h>

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "importers/importers.hpp"
#include "math/rotation.hpp"

namespace mechkin::importers {

/// A rigid transform: x_outer = R x_inner + p.
struct Pose {
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();
  Pose operator*(const Pose& b) const { return {R * b.R, R * b.p + p}; }
  Pose Inverse() const { return {R.transpose(), -(R.transpose() * p)}; }
};

/// Where an element is: its line and its description (<joint name="B">).
struct Place {
  int line = 0;
  std::string element;
};

struct LinkInertia {
  double mass = 0;
  Pose frame;                       // the inertial frame in the link
  Mat3 moments = Mat3::Zero();      // about the centre, in the inertial frame's axes
};

struct Link {
  std::string name;  // as in the file
  Pose world;        // as written (every joint at its reference value)
  std::optional<LinkInertia> inertia;
  Place place;
  bool ground = false;  // the fixed frame (URDF's root, MJCF's worldbody, SDF's world)
};

enum class Kind { Revolute, Prismatic, Cylindrical, Screw, Universal, Spherical, Planar, Fixed };

struct Joint {
  std::string name;  // as in the file
  Kind kind = Kind::Revolute;
  std::string parent, child;      // link names: mechkin's body1 and body2
  Pose in_parent, in_child;       // the joint frame in each link (equal in the written pose unless a loop)
  Vec3 axis = Vec3::UnitZ();      // in the joint frame (unit); planar: the normal
  Vec3 axis2 = Vec3::UnitY();     // universal: the child's axis, in the joint frame
  std::optional<std::array<double, 2>> limits;  // from the written pose (SI)
  double pitch = 0;               // screw: length per revolution
  Place place;
};

struct Coupling {
  std::string name;
  std::vector<std::string> joints;  // file joint names
  std::vector<double> coefficients;
  double constant = 0;
  Place place;
};

/// The graph of one file and its messages.
class Graph {
 public:
  Graph(std::string file, ImportResult* result) : file_(std::move(file)), result_(result) {}

  const std::string& file() const { return file_; }
  Place PlaceOf(const tinyxml2::XMLElement* e) const;
  void Error(const Place& at, const std::string& message, const std::string& fix = "");
  void Warn(const Place& at, const std::string& message, const std::string& fix = "");
  void Error(const tinyxml2::XMLElement* e, const std::string& message, const std::string& fix = "") {
    Error(PlaceOf(e), message, fix);
  }
  void Warn(const tinyxml2::XMLElement* e, const std::string& message, const std::string& fix = "") {
    Warn(PlaceOf(e), message, fix);
  }
  bool failed() const { return !result_->errors.empty(); }

  /// nullptr when there is no link of that name.
  Link* FindLink(const std::string& name);
  const Joint* FindJoint(const std::string& name) const;
  /// False (an error at `e`) when the name is taken.
  bool AddLink(Link link, const tinyxml2::XMLElement* e);
  bool AddJoint(Joint joint, const tinyxml2::XMLElement* e);

  std::string name, description;
  std::vector<Link> links;
  std::vector<Joint> joints;
  std::vector<Coupling> couplings;

 private:
  std::string file_;
  ImportResult* result_;
  std::map<std::string, size_t> link_index_, joint_index_;
};

/// The spec of a complete graph: fixed joints merge their links into one body,
/// every other joint is a joint on two markers at its frames; drives and span from
/// `options`. Errors go to `result`.
void BuildSpec(const Graph& graph, const ImportOptions& options, ImportResult* result);

// XML helpers shared by the readers.

/// The name of the first element of an XML text (after the declaration, comments, doctype).
std::string RootName(const std::string& head);
/// Parses the document (text after the root element skipped with a warning); false (an error with the line) when it is not well-formed XML.
bool ParseXml(const std::string& text, tinyxml2::XMLDocument* doc, Graph* graph);
/// <tag name="..."> for messages.
std::string Describe(const tinyxml2::XMLElement* e);
/// `count` numbers separated by spaces (or commas); false with an error when not.
bool ReadNumbers(const tinyxml2::XMLElement* e, const char* attribute, int count, double* out, Graph* graph);
/// The attribute's numbers when present; false with an error when malformed.
bool ReadOptionalNumbers(const tinyxml2::XMLElement* e, const char* attribute, int count, double* out,
                         Graph* graph);
/// Numbers of a text ("1 2 3"): all of them, false when a token is not a number.
bool ParseNumberList(const char* text, std::vector<double>* out);
/// A required attribute; nullptr with an error naming it when absent.
const char* RequiredAttribute(const tinyxml2::XMLElement* e, const char* attribute, Graph* graph);

/// Fixed-axis roll-pitch-yaw (URDF, SDFormat): Rz(yaw) Ry(pitch) Rx(roll).
Mat3 RollPitchYaw(double roll, double pitch, double yaw);
/// Rotation by `angle` about the unit axis.
Mat3 AxisAngle(const Vec3& unit_axis, double angle);
/// The rotation taking z to the unit `axis` (the identity for z, a half turn about x for −z).
Mat3 ZTo(const Vec3& axis);
/// A unit vector or, for a zero vector, an error at `e`.
std::optional<Vec3> UnitAxis(const Vec3& v, const tinyxml2::XMLElement* e, const std::string& what, Graph* graph);

}  // namespace mechkin::importers
