#include "analysis/check_report.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/assemble_model.hpp"
#include "analysis/joint_limits.hpp"
#include "mobility/grubler.hpp"

namespace mechkin {

bool CheckReport::ok() const {
  return valid && std::all_of(expectations.begin(), expectations.end(), [](const ExpectationResult& e) { return e.held; });
}

namespace {

void AddExpectations(const Model& m, CheckReport* r) {
  const MobilityReport& mob = *r->mobility;
  auto expect = [&](const char* key, const ExpectValue& expected, const ExpectValue& actual) {
    r->expectations.push_back({key, expected, actual, expected == actual, ""});
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

struct JointPoint {
  std::string joint;
  Vec3 point, axis;  // global, at the design pose (SI)
  bool has_axis;
};

// The joints (and distance-link ends) attached to body b, with their design
// points; joints_on[b] lists b's joints in file order.
std::vector<JointPoint> JointPointsOf(const Model& m, BodyIndex b, const std::vector<std::vector<size_t>>& joints_on) {
  std::vector<JointPoint> out;
  const Body& body = m.bodies[b];
  const Mat3 A = CalcA(body.euler);
  for (size_t index : joints_on[b]) {
    const Joint& j = m.joints[index];
    const JointFrame& f = j.body1 == b ? j.frame1 : j.frame2;
    const bool axis = j.type->frames != JointFrameRule::Point && j.type->frames != JointFrameRule::TwoPoints;
    out.push_back({j.name, body.position + A * f.origin, A * f.h, axis});
  }
  return out;
}

// Link lengths and axis angles per body (at most 8 joints a body: 28 pairs).
void AddGeometry(const Model& m, CheckReport* r) {
  const double len = 1 / m.units.length_to_si, ang = 1 / m.units.angle_to_si;
  std::vector<std::vector<size_t>> joints_on(m.num_bodies());
  for (size_t j = 0; j < m.joints.size(); ++j) {
    const Joint& jt = m.joints[j];
    if (jt.body1 != kGround) joints_on[jt.body1].push_back(j);
    if (jt.body2 != kGround && jt.body2 != jt.body1) joints_on[jt.body2].push_back(j);
  }
  for (int b = 0; b < m.num_bodies(); ++b) {
    const std::vector<JointPoint> pts = JointPointsOf(m, b, joints_on);
    if (pts.size() < 2) continue;
    BodyGeometry g;
    g.body = m.bodies[b].name;
    for (size_t i = 0; i < pts.size() && i < 8; ++i)
      for (size_t k = i + 1; k < pts.size() && k < 8; ++k) {
        g.lengths.push_back({pts[i].joint, pts[k].joint, (pts[i].point - pts[k].point).norm() * len});
        if (pts[i].has_axis && pts[k].has_axis) {
          // acos as always; below 1e-6 rad atan2(|a×b|, a·b), since acos turns the
          // round-off of an assembled pose (1e-16 in a·b) into 1e-8 rad
          const Vec3& a = pts[i].axis;
          const Vec3& b = pts[k].axis;
          double angle = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
          if (angle < 1e-6) angle = std::atan2(a.cross(b).norm(), a.dot(b));
          g.angles.push_back({pts[i].joint, pts[k].joint, angle * ang});
        }
      }
    r->geometry.push_back(std::move(g));
  }
  r->parameters = m.parameters;
  r->length_unit = m.units.length_name;
  r->angle_unit = m.units.angle_name;
}

void AddAssembly(const Model& m, CheckReport* r) {
  if (!m.assembly || !m.assembly->assembled) return;
  const AssemblyRecord& rec = *m.assembly;
  const double len = 1 / m.units.length_to_si, ang = 1 / m.units.angle_to_si;
  AssemblySection a;
  a.iterations = rec.iterations;
  for (const AssemblyLoop& loop : rec.loops) {
    AssemblySection::Loop l{m.joints[loop.joint].name, LoopName(m, loop), {}, loop.error_before * len,
                            loop.error_after * len};
    for (int j : loop.path) l.path.push_back(m.joints[j].name);
    a.loops.push_back(std::move(l));
  }
  for (int b = 0; b < m.num_bodies(); ++b) {
    const double turn = 2 * std::acos(std::min(1.0, std::abs(m.bodies[b].euler.dot(rec.guess_euler[b]))));
    a.moves.push_back({m.bodies[b].name, rec.sketched[b], (m.bodies[b].position - rec.guess_position[b]).norm() * len,
                       turn * ang});
  }
  r->assembly = std::move(a);
}

}  // namespace

namespace {

// A joint whose design pose (or markers' coincidence, assembled) lies outside its
// "limits": a run from there stops at its first row.
void WarnLimitsAtDesignPose(const Model& m, CheckReport* r) {
  const ConstraintSystem sys(m, false);
  const SystemState s(sys);
  for (size_t k = 0; k < m.joints.size(); ++k) {
    const Joint& j = m.joints[k];
    if (!j.limits) continue;
    const double q = LimitedCoordinate(j, s, 0.0);
    if (q >= j.limits->first && q <= j.limits->second) continue;
    const bool rot = LimitOnRotation(j.type);
    const double unit = rot ? m.units.angle_to_si : m.units.length_to_si;
    const std::string u = rot ? m.units.angle_name : m.units.length_name;
    r->warnings.push_back({"/joints/" + std::to_string(k) + "/limits",
                           "the design pose puts joint `" + j.name + "` at " + FormatNumber(q / unit) + " " + u +
                               ", outside its limits [" + FormatNumber(j.limits->first / unit) + ", " +
                               FormatNumber(j.limits->second / unit) + "] " + u,
                           "widen the limits or change the design pose; a run from it stops at its first row"});
  }
}

}  // namespace

void StopPoint(const InterruptPoll& stop, const char* stage) {
  if (stop && stop()) throw CheckStopped{stage};
}

CheckReport CheckLoaded(const std::string& file, const LoadResult& loaded) { return CheckLoaded(file, loaded, {}); }

CheckReport CheckLoaded(const std::string& file, const LoadResult& loaded, const InterruptPoll& stop) {
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
    const std::string& type = j.type->name;
    auto it = std::find_if(r.joints.begin(), r.joints.end(), [&](const auto& kv) { return kv.first == type; });
    if (it == r.joints.end()) r.joints.emplace_back(type, 1);
    else ++it->second;
  }
  std::sort(r.joints.begin(), r.joints.end());  // the JSON object's key order
  r.grubler = CalcGrublerCount(m);
  r.couplers = static_cast<int>(m.couplers.size());
  for (const auto& j : m.joints) r.joint_equations += j.type->Rows();
  r.dof_after_drivers_count = r.grubler - r.drivers;
  r.planar = FindPlanarStructure(m);
  StopPoint(stop, "the counts");
  r.mobility = CalcMobility(m);
  StopPoint(stop, "the mobility analysis (the rank of the joint equations)");
  if (r.mobility->singular_lost > 0)
    r.warnings.push_back({"/drivers",
                          "the design pose is a singular position of the driven mechanism: the drivers control " +
                              std::to_string(r.mobility->singular_lost) +
                              " fewer direction(s) there than at nearby poses, so `run` cannot start there",
                          "move the design pose off it (change a joint angle or a leg length slightly)"});
  if (r.mobility->locked)
    r.warnings.push_back({"/joints", r.mobility->verdict, "fix the joints before adding or removing drivers"});
  AddExpectations(m, &r);
  if (m.expect.min_clearance) AddClearanceCheck(m, &r, stop);
  if (!m.expect.bounds.empty()) AddMotionBoundCheck(m, &r, stop);
  StopPoint(stop, "the clearance sweep");
  AddGeometry(m, &r);
  AddAssembly(m, &r);
  WarnLimitsAtDesignPose(m, &r);
  return r;
}

CheckReport CheckFile(const std::string& path) { return CheckLoaded(path, LoadMechanismFile(path)); }

}  // namespace mechkin
