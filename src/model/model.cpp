#include "model/model.hpp"

#include <cmath>

namespace mechkin {

int EquationsRemoved(JointType type) {
  switch (type) {
    case JointType::Revolute: case JointType::Prismatic: case JointType::Screw: return 5;
    case JointType::Cylindrical: case JointType::Universal: return 4;
    case JointType::Spherical: case JointType::Planar: return 3;
    case JointType::Distance: return 1;
  }
  return 0;
}

const char* JointTypeName(JointType type) {
  switch (type) {
    case JointType::Revolute: return "revolute";
    case JointType::Prismatic: return "prismatic";
    case JointType::Screw: return "screw";
    case JointType::Cylindrical: return "cylindrical";
    case JointType::Universal: return "universal";
    case JointType::Spherical: return "spherical";
    case JointType::Planar: return "planar";
    case JointType::Distance: return "distance";
  }
  return "?";
}

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
