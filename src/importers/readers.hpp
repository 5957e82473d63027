// Internal to src/importers: one reader per format, each filling a Graph from a
// parsed document (messages into the graph; the caller builds the spec).
#pragma once

#include <tinyxml2.h>

#include "importers/graph.hpp"

namespace mechkin::importers {

void ReadUrdf(const tinyxml2::XMLElement* robot, Graph* graph);
void ReadMjcf(const tinyxml2::XMLElement* mujoco, Graph* graph);
void ReadSdf(const tinyxml2::XMLElement* sdf, Graph* graph);
/// FreeCAD: the parsed Document.xml of an .FCStd archive.
void ReadFreeCad(const tinyxml2::XMLElement* document, Graph* graph);
/// Document.xml of an .FCStd (zip) archive; false with the reason.
bool ReadFcstd(const std::string& path, std::string* document, std::string* why);

/// An <origin xyz rpy> (URDF) as a pose; identity when `e` is null.
bool ReadOrigin(const tinyxml2::XMLElement* e, Pose* pose, Graph* graph);

}  // namespace mechkin::importers
