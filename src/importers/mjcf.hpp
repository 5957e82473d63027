// Internal to src/importers: the MJCF reader's state shared by its two files
// (mjcf.cpp: compiler, defaults, the body tree; mjcf_equality.cpp: the equality
// constraints that close loops and couple joints).
#pragma once

#include <map>
#include <string>

#include "importers/readers.hpp"

namespace mechkin::importers::mjcf {

struct Site {
  std::string link;
  Vec3 pos = Vec3::Zero();  // in the link
};

struct JointInfo {
  std::string link;   // the body the joint moves (its child)
  double ref = 0;     // qpos0 (SI)
};

struct Reader {
  Graph* g = nullptr;
  bool degrees = true;            // <compiler angle>: MuJoCo's default is degrees
  std::string eulerseq = "xyz";   // <compiler eulerseq>
  bool autolimits = true;         // <compiler autolimits>
  // <default class>: its parent class and its <joint> element (either may be null).
  std::map<std::string, std::pair<std::string, const tinyxml2::XMLElement*>> classes;
  std::map<std::string, Site> sites;
  std::map<std::string, JointInfo> joints;
  int unnamed = 0;

  double Angle(double a) const { return degrees ? a * M_PI / 180 : a; }
  /// A joint attribute: the element's own, else its class chain's (`cls` the class in force).
  const char* JointAttribute(const tinyxml2::XMLElement* joint, const std::string& cls, const char* key) const;
};

/// <equality>: connect (spherical closure), weld (fixed), joint (coupling).
void ReadEquality(const tinyxml2::XMLElement* equality, Reader* r);

}  // namespace mechkin::importers::mjcf
