#include "analysis/check_report.hpp"

#include <algorithm>

#include "mobility/grubler.hpp"

namespace mechkin {

bool CheckReport::ok() const {
  return valid && std::all_of(expectations.begin(), expectations.end(), [](const ExpectationResult& e) { return e.held; });
}

namespace {

void AddExpectations(const Model& m, CheckReport* r) {
  const MobilityReport& mob = *r->mobility;
  auto expect = [&](const char* key, const ExpectValue& expected, const ExpectValue& actual) {
    r->expectations.push_back({key, expected, actual, expected == actual});
  };
  auto when_assembled = [&](const ExpectValue& v) { return mob.assembled ? v : ExpectValue{}; };
  if (m.expect.grubler) expect("grubler", ExpectValue::Of(*m.expect.grubler), ExpectValue::Of(r->grubler));
  if (m.expect.mobility) expect("mobility", ExpectValue::Of(*m.expect.mobility), when_assembled(ExpectValue::Of(mob.mobility)));
  if (m.expect.redundant)
    expect("redundant", ExpectValue::Of(*m.expect.redundant), when_assembled(ExpectValue::Of(mob.redundant)));
  if (m.expect.idle)
    expect("idle", ExpectValue::Of(*m.expect.idle), when_assembled(ExpectValue::Of(static_cast<int>(mob.idle.size()))));
  if (m.expect.driven)
    expect("driven", ExpectValue::Of(*m.expect.driven),
           when_assembled(ExpectValue::Of(std::string(DrivingStatusName(mob.driving_status)))));
}

}  // namespace

CheckReport CheckLoaded(const std::string& file, const LoadResult& loaded) {
  CheckReport r;
  r.file = file;
  r.errors = loaded.errors;
  r.warnings = loaded.warnings;
  r.valid = loaded.ok();
  if (!r.valid) return r;
  const Model& m = *loaded.model;
  r.name = m.name;
  r.bodies = m.num_bodies();
  r.drivers = static_cast<int>(m.drivers.size());
  for (const auto& j : m.joints) {
    const std::string type = JointTypeName(j.type);
    auto it = std::find_if(r.joints.begin(), r.joints.end(), [&](const auto& kv) { return kv.first == type; });
    if (it == r.joints.end()) r.joints.emplace_back(type, 1);
    else ++it->second;
  }
  std::sort(r.joints.begin(), r.joints.end());  // the JSON object's key order
  r.grubler = CalcGrublerCount(m);
  r.dof_after_drivers_count = r.grubler - r.drivers;
  r.mobility = CalcMobility(m);
  if (r.mobility->singular_lost > 0)
    r.warnings.push_back({"/drivers",
                          "the design pose is a singular position of the driven mechanism: the drivers control " +
                              std::to_string(r.mobility->singular_lost) +
                              " fewer direction(s) there than at nearby poses, so `run` cannot start there",
                          "move the design pose off it (change a joint angle or a leg length slightly)"});
  if (r.mobility->locked)
    r.warnings.push_back({"/joints", r.mobility->verdict, "fix the joints before adding or removing drivers"});
  AddExpectations(m, &r);
  return r;
}

CheckReport CheckFile(const std::string& path) { return CheckLoaded(path, LoadMechanismFile(path)); }

}  // namespace mechkin
