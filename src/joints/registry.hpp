// The joint types a file may name: the built-in ones (one file each in src/joints,
// one line each in registry.cpp) and any a program registers before it reads files
// (docs/joints.md). Lookups by name happen while a file is read and compiled; a
// model's joints keep a pointer to their descriptor, which lives as long as the
// program.
#pragma once

#include <string>
#include <vector>

#include "joints/descriptor.hpp"

namespace mechkin {

/// Adds a joint type; returns the registry's copy (stable for the program's life).
/// Throws std::invalid_argument for an empty or taken name or a relaxation naming
/// no registered type. Call it before reading files that use the type (not from a
/// static initializer: the built-in types may not be constructed yet).
const JointDescriptor& RegisterJointType(const JointDescriptor& descriptor);

/// The type named `name`, or nullptr.
const JointDescriptor* FindJointType(const std::string& name);
/// The type named `name`; throws std::invalid_argument when there is none.
const JointDescriptor& JointTypeNamed(const std::string& name);

/// Every registered type, built-in ones first in docs/format.md's order.
std::vector<const JointDescriptor*> JointTypes();
std::vector<std::string> JointTypeNames();

}  // namespace mechkin
