#include "joints/registry.hpp"

#include <deque>
#include <mutex>
#include <stdexcept>

namespace mechkin {

// The built-in joints, one line each: src/joints/<name>.cpp defines the function.
JointDescriptor RevoluteJoint();
JointDescriptor PrismaticJoint();
JointDescriptor ScrewJoint();
JointDescriptor CylindricalJoint();
JointDescriptor UniversalJoint();
JointDescriptor SphericalJoint();
JointDescriptor PlanarJoint();
JointDescriptor DistanceJoint();

namespace {

constexpr JointDescriptor (*kBuiltIn[])() = {RevoluteJoint,  PrismaticJoint, ScrewJoint,  CylindricalJoint,
                                             UniversalJoint, SphericalJoint, PlanarJoint, DistanceJoint};

struct Registry {
  std::mutex mutex;
  std::deque<JointDescriptor> types;  // a deque: adding keeps the addresses handed out

  const JointDescriptor* Find(const std::string& name) const {
    for (const JointDescriptor& d : types)
      if (d.name == name) return &d;
    return nullptr;
  }

  const JointDescriptor& Add(const JointDescriptor& d) {
    if (d.name.empty()) throw std::invalid_argument("a joint type needs a name");
    if (Find(d.name)) throw std::invalid_argument("joint type '" + d.name + "' is already registered");
    for (const JointEquation& e : d.equations)
      if (e.rows.size() != (e.primitive == JointPrimitive::Spherical ? 3u : 1u))
        throw std::invalid_argument("joint type '" + d.name + "': a primitive's rows need one description each");
    for (const std::string& r : d.relaxations)
      if (!Find(r) && r != d.name)
        throw std::invalid_argument("joint type '" + d.name + "' relaxes to unknown type '" + r + "'");
    types.push_back(d);
    return types.back();
  }
};

Registry& Instance() {
  static Registry* registry = [] {
    auto* r = new Registry;  // never destroyed: models may outlive static destruction
    for (auto make : kBuiltIn) r->types.push_back(make());
    return r;
  }();
  return *registry;
}

}  // namespace

const JointDescriptor& RegisterJointType(const JointDescriptor& descriptor) {
  Registry& r = Instance();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.Add(descriptor);
}

const JointDescriptor* FindJointType(const std::string& name) {
  Registry& r = Instance();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.Find(name);
}

const JointDescriptor& JointTypeNamed(const std::string& name) {
  if (const JointDescriptor* d = FindJointType(name)) return *d;
  throw std::invalid_argument("unknown joint type '" + name + "'");
}

std::vector<const JointDescriptor*> JointTypes() {
  Registry& r = Instance();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<const JointDescriptor*> out;
  for (const JointDescriptor& d : r.types) out.push_back(&d);
  return out;
}

std::vector<std::string> JointTypeNames() {
  std::vector<std::string> names;
  for (const JointDescriptor* d : JointTypes()) names.push_back(d->name);
  return names;
}

}  // namespace mechkin
