#include "model/model.hpp"

#include <cmath>

namespace mechkin {

const char* CouplerKindName(CouplerKind kind) {
  switch (kind) {
    case CouplerKind::Gear: return "gear";
    case CouplerKind::Belt: return "belt";
    case CouplerKind::RackPinion: return "rack_pinion";
    case CouplerKind::ScrewCoupling: return "screw_coupling";
    case CouplerKind::Coupling: return "coupling";
  }
  return "?";
}

bool Model::HasForces() const {
  if (!loads.empty() || gravity.norm() > 0) return true;
  for (const auto& b : bodies)
    if (b.inertia) return true;
  return false;
}

const Parameter* Model::FindParameter(const std::string& name) const {
  for (const auto& p : parameters)
    if (p.name == name) return &p;
  return nullptr;
}

std::string SpanProblem(double start, double end, double steps) {
  if (!std::isfinite(start) || !std::isfinite(end)) return "'start' and 'end' must be finite times in seconds";
  if (!(end > start)) return "'end' must be greater than 'start'";
  if (!(steps >= 1)) return "'steps' must be at least 1";
  if (steps > kMaxSteps) return "'steps' is larger than 10,000,000";
  return "";
}

}  // namespace mechkin
