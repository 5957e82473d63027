// The motion table's clearance columns (docs/format.md "Clearance"): `C` and `C_t`
// (the distance and its rate, to the table's order but at most 1) and the closest
// points `C.point1.x` … `C.point2.z`, global, in the table's length unit.
#include "analysis/motion.hpp"

namespace mechkin {

void MotionLayout::AddClearance(const Output& out, int o, const std::string& L) {
  for (int k = 0; k <= std::min(options_.order, 1); ++k)
    columns_.push_back({out.name + (k ? "_t" : ""), k ? L + "/s" : L, out.name, Quantity::Clearance, o, -1, k});
  static const char* kAxes[] = {"x", "y", "z"};
  for (int c = 0; c < 6; ++c)
    columns_.push_back({out.name + ".point" + std::to_string(c / 3 + 1) + "." + kAxes[c % 3], L, out.name,
                        Quantity::ClearancePoint, o, c, 0});
}

// One evaluator for every clearance output of the model, made on the first row
// that needs it (outside the step loop's steady state).
double* RowEvaluator::ClearanceValues(const SystemState& s, int o, double* out) {
  if (!clearance_) {
    const std::vector<ClearancePair> pairs = ClearanceOutputPairs(model_);
    clearance_pair_.assign(model_.outputs.size(), -1);
    for (size_t k = 0; k < pairs.size(); ++k) clearance_pair_[pairs[k].output] = static_cast<int>(k);
    clearance_ = std::make_shared<ClearanceEvaluator>(model_, pairs);
  }
  const int order = layout_.options().order;
  const double len = layout_.length_factor();
  const ClearanceValue v = clearance_->Evaluate(s, clearance_pair_[o], order >= 1);
  *out++ = v.distance * len;
  if (order >= 1) *out++ = v.rate * len;
  for (int a = 0; a < 3; ++a) *out++ = v.point1[a] * len;
  for (int a = 0; a < 3; ++a) *out++ = v.point2[a] * len;
  return out;
}

}  // namespace mechkin
