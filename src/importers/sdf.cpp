// SDFormat: not read yet (docs/import.md says what is missing).
#include "importers/readers.hpp"

namespace mechkin::importers {

void ReadSdf(const tinyxml2::XMLElement* sdf, Graph* g) {
  g->Error(sdf, "SDFormat files are not read yet", "convert the model to URDF or MJCF, or write the mechanism file");
}

}  // namespace mechkin::importers
