#include "mobility/grubler.hpp"

namespace mechkin {

int CalcGrublerCount(const Model& model) {
  int m = 6 * model.num_bodies();
  for (const auto& j : model.joints) m -= EquationsRemoved(j.type);
  return m;
}

}  // namespace mechkin
