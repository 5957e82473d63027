#include "io/check_report_writer.hpp"

#include <cstdio>

namespace mechkin {
namespace {

using nlohmann::json;

json DiagnosticsJson(const std::vector<Diagnostic>& ds) {
  json a = json::array();
  for (const auto& d : ds) a.push_back({{"pointer", d.pointer}, {"message", d.message}, {"fix", d.fix}});
  return a;
}

json ValueJson(const ExpectValue& v) {
  switch (v.kind) {
    case ExpectValue::Kind::Count: return v.count;
    case ExpectValue::Kind::Word: return v.word;
    case ExpectValue::Kind::Number: return v.number;
    case ExpectValue::Kind::Absent: break;
  }
  return nullptr;
}

// `check --clearance`: each pair's smallest clearance and where; the tightest first.
json ClearanceJson(const ClearanceSection& c) {
  json pairs = json::array();
  for (const auto& p : c.pairs)
    pairs.push_back({{"body1", p.body1}, {"body2", p.body2}, {"output", p.output}, {"min_clearance", p.clearance},
                     {"t", p.t}, {"where", p.where}});
  json j = {{"pairs", pairs}, {"unit", c.length_unit}, {"rows", c.rows}, {"complete", c.complete}};
  if (c.tightest >= 0) j["tightest"] = pairs[c.tightest];
  if (!c.note.empty()) j["note"] = c.note;
  return j;
}

void PrintClearance(const ClearanceSection& c, std::ostream& out) {
  if (c.tightest < 0) {
    out << "  clearance: " << (c.pairs.empty() ? "no pair of bodies with shapes to measure" : "no row: " + c.note) << "\n";
    return;
  }
  out << "  clearance: tightest " << c.pairs[c.tightest].where << " (" << c.rows << " rows swept"
      << (c.complete ? "" : "; stopped early: " + c.note) << ")\n";
  for (size_t k = 0; k < c.pairs.size() && c.pairs.size() > 1; ++k)
    out << "    " << c.pairs[k].where << "\n";
}

json MobilityJson(const MobilityReport& r, int drivers) {
  json j;
  j["assembled"] = r.assembled;
  j["assembly"] = r.assembly_message;
  if (!r.assembled) return j;
  j["equations"] = r.equations;
  j["rank"] = r.rank;
  j["mobility"] = r.mobility;
  j["redundant"] = r.redundant;
  j["rank_threshold"] = kRankThreshold;
  j["rank_method"] = r.rank_method;
  j["sigma_min_kept"] = r.sigma_min_kept;
  j["sigma_max_dropped"] = r.sigma_max_dropped;
  j["redundant_equations"] = json::array();
  for (const auto& e : r.redundant_equations) j["redundant_equations"].push_back({{"equation", e.description}, {"fixed_by", e.fixed_by}});
  j["idle"] = json::array();
  for (const auto& f : r.idle)
    j["idle"].push_back({{"bodies", f.body}, {"axis", {f.axis.x(), f.axis.y(), f.axis.z()}}, {"description", f.description}});
  // format v1: DOF after drivers = mobility − number of drivers (negative: over-driven).
  j["dof_after_drivers"] = r.mobility - drivers;
  // Rank of joints + drivers together: the freedoms actually left (never negative).
  j["free_after_drivers"] = r.dof_after_drivers;
  j["driven"] = DrivingStatusName(r.driving_status);
  j["conflicting_drivers"] = r.conflicting_drivers;
  if (!r.conflicting_couplers.empty()) j["conflicting_couplers"] = r.conflicting_couplers;
  j["remaining_freedoms"] = r.remaining_freedoms;
  j["verdict"] = r.verdict;
  j["suggestions"] = r.suggestions;
  j["locked"] = r.locked;
  j["locking_joints"] = r.locking_joints;
  j["singular_design_pose"] = r.singular_lost > 0;
  j["singular_directions"] = r.singular_directions;
  return j;
}

void PrintMobility(const MobilityReport& m, int drivers, std::ostream& out) {
  if (!m.assembled) {
    out << "  mobility: not computed — " << m.assembly_message << "\n";
    return;
  }
  char buf[200];
  const bool qr = m.rank_method == "sparse-qr";
  std::snprintf(buf, sizeof buf, "  mobility (rank): %d  [rank %d of %d equations%s; margin: smallest kept %s %.2e, largest dropped %s %.2e]\n",
                m.mobility, m.rank, m.equations, qr ? ", sparse QR" : "", qr ? "pivot" : "σ", m.sigma_min_kept,
                qr ? "norm" : "σ", m.sigma_max_dropped);
  out << buf << "  redundant equations: " << m.redundant << "\n";
  for (const auto& e : m.redundant_equations) {
    out << "    - " << e.description;
    if (!e.fixed_by.empty()) {
      out << (e.couplers_in_fixed_by ? " is already fixed by joints and couplers " : " is already fixed by joints ");
      for (size_t k = 0; k < e.fixed_by.size(); ++k) out << (k ? ", " : "") << e.fixed_by[k];
    }
    out << "\n";
  }
  if (!m.verdict.empty()) out << "  verdict: " << m.verdict << "\n";
  for (const auto& s : m.suggestions) out << "  suggestion: " << s << "\n";
  out << "  idle freedoms: " << m.idle.size() << "\n";
  for (const auto& f : m.idle) out << "    - " << f.description << "\n";
  out << "  DOF after drivers: " << m.mobility - drivers << " (mobility − drivers; freedoms left by rank: "
      << m.dof_after_drivers << ") — driven: " << DrivingStatusName(m.driving_status);
  if (!m.conflicting_drivers.empty()) {
    out << " (conflicting drivers: ";
    for (size_t k = 0; k < m.conflicting_drivers.size(); ++k) out << (k ? ", " : "") << m.conflicting_drivers[k];
    if (!m.conflicting_couplers.empty()) out << "; against couplers: ";
    for (size_t k = 0; k < m.conflicting_couplers.size(); ++k) out << (k ? ", " : "") << m.conflicting_couplers[k];
    out << ")";
  }
  if (m.locked && !m.conflicting_drivers.empty()) out << " — a consequence: the joints already lock the mechanism";
  out << "\n";
  for (const auto& f : m.remaining_freedoms) out << "    - " << f << "\n";
  if (m.singular_lost > 0) {
    out << "  design pose: a singular position of the driven mechanism — the drivers control " << m.singular_lost
        << " fewer direction" << (m.singular_lost == 1 ? "" : "s") << " here than at nearby poses (the driving status above is "
        << "that of a nearby pose):\n";
    for (const auto& d : m.singular_directions) out << "    - " << d << "\n";
    out << "  The run starts at the design pose: move it off the singular position.\n";
  }
}

// A planar mechanism: the plane and the planar count next to the spatial one
// (whose excess redundancy is the out-of-plane equations every planar loop repeats).
void PrintPlanar(const PlanarStructure& p, int drivers, std::ostream& out) {
  char normal[96];
  std::snprintf(normal, sizeof normal, "[%.6g, %.6g, %.6g]", p.normal.x() + 0.0, p.normal.y() + 0.0, p.normal.z() + 0.0);
  out << "  planar: every body moves parallel to the plane normal to " << normal << "; planar count 3n − 2j₁ − j₂"
      << (p.couplers > 0 ? " − couplers" : "") << " = " << p.count << " (after drivers: " << p.count - drivers << ")\n";
}

json PlanarJson(const PlanarStructure& p, int drivers) {
  return {{"normal", {p.normal.x() + 0.0, p.normal.y() + 0.0, p.normal.z() + 0.0}},
          {"grubler", p.count},
          {"dof_after_drivers_count", p.count - drivers},
          {"lower_pairs", p.lower_pairs},
          {"higher_pairs", p.higher_pairs}};
}

void PrintErrors(const CheckReport& r, std::ostream& out) {
  out << "INVALID (" << r.errors.size() << (r.errors.size() == 1 ? " error)\n" : " errors)\n");
  for (const auto& e : r.errors) {
    out << "  error: " << (e.pointer.empty() ? "(file)" : e.pointer) << ": " << e.message;
    if (!e.fix.empty()) out << "\n         fix: " << e.fix;
    out << "\n";
  }
}

std::string Short(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.7g", v);
  return buf;
}

// "  crank: bearing–crankpin 40 mm" per body, axis angles only where not 0.
void PrintGeometry(const CheckReport& r, std::ostream& out) {
  if (!r.parameters.empty()) {
    out << "  parameters:";
    for (const auto& p : r.parameters) {
      out << " " << p.name << " = " << Short(p.value);
      if (p.tolerance) out << " ±" << Short(*p.tolerance);
      if (p.overridden) out << " (set)";
      else if (!p.expression.empty()) out << " (= " << p.expression << ")";
      out << (&p == &r.parameters.back() ? "\n" : ";");
    }
  }
  if (r.geometry.empty()) return;
  out << "  geometry (joint-point distances, " << r.length_unit << "; angles between joint axes, " << r.angle_unit
      << "):\n";
  for (const auto& g : r.geometry) {
    out << "    " << g.body << ":";
    for (const auto& l : g.lengths) out << " " << l.joint1 << "-" << l.joint2 << " " << Short(l.value) << ";";
    for (const auto& a : g.angles)
      if (a.value > 1e-9) out << " axes " << a.joint1 << "/" << a.joint2 << " " << Short(a.value) << ";";
    out << "\n";
  }
}

json GeometryJson(const CheckReport& r) {
  json bodies = json::array();
  for (const auto& g : r.geometry) {
    json lengths = json::array(), angles = json::array();
    for (const auto& l : g.lengths) lengths.push_back({{"joints", {l.joint1, l.joint2}}, {"distance", l.value}});
    for (const auto& a : g.angles) angles.push_back({{"joints", {a.joint1, a.joint2}}, {"angle", a.value}});
    bodies.push_back({{"body", g.body}, {"lengths", lengths}, {"axis_angles", angles}});
  }
  return {{"length_unit", r.length_unit}, {"angle_unit", r.angle_unit}, {"bodies", bodies}};
}

json ParametersJson(const std::vector<Parameter>& parameters) {
  json j = json::object();
  for (const auto& p : parameters) {
    json e = {{"value", p.value}};
    if (!p.expression.empty()) e["expression"] = p.expression;
    if (p.tolerance) e["tolerance"] = *p.tolerance;
    if (p.min) e["min"] = *p.min;
    if (p.max) e["max"] = *p.max;
    if (p.overridden) e["set"] = true;
    j[p.name] = e;
  }
  return j;
}

// "  assembly (from the markers, 7 Newton iterations):" then per loop and per body.
void PrintAssembly(const CheckReport& r, std::ostream& out) {
  if (!r.assembly) return;
  const AssemblySection& a = *r.assembly;
  out << "  assembly (from the markers; " << a.iterations << " Newton iterations, all loops at once):\n";
  for (const auto& l : a.loops)
    out << "    loop " << l.name << " closed by " << l.joint << ": error " << Short(l.error_before) << " -> "
        << Short(l.error_after) << " " << r.length_unit << "\n";
  for (const auto& m : a.moves)
    out << "    " << m.body << (m.sketched ? " (sketch)" : " (tree)") << ": moved " << Short(m.distance) << " "
        << r.length_unit << ", turned " << Short(m.angle) << " " << r.angle_unit << "\n";
}

json AssemblyJson(const CheckReport& r) {
  const AssemblySection& a = *r.assembly;
  json loops = json::array(), moves = json::array();
  for (const auto& l : a.loops)
    loops.push_back({{"joint", l.joint}, {"bodies", l.name}, {"path", l.path}, {"error_before", l.error_before},
                     {"error_after", l.error_after}});
  for (const auto& m : a.moves)
    moves.push_back({{"body", m.body}, {"guess", m.sketched ? "sketch" : "tree"}, {"moved", m.distance},
                     {"turned", m.angle}});
  return {{"iterations", a.iterations}, {"length_unit", r.length_unit}, {"angle_unit", r.angle_unit},
          {"loops", loops}, {"bodies", moves}};
}

void PrintSummary(const CheckReport& r, std::ostream& out) {
  out << (r.name.empty() ? "(unnamed)" : r.name) << "\n";
  out << "  bodies: " << r.bodies << " moving\n  joints: ";
  int total = 0;
  for (size_t k = 0; k < r.joints.size(); ++k) {
    out << (k ? ", " : "") << r.joints[k].second << " " << r.joints[k].first;
    total += r.joints[k].second;
  }
  out << (r.joints.empty() ? "none" : "") << " (" << total << " total)\n";
  if (r.couplers > 0) out << "  couplers: " << r.couplers << " (one equation each)\n";
  out << "  drivers: " << r.drivers << "\n";
  out << "  Grübler–Kutzbach count: " << r.grubler;
  if (r.couplers > 0)
    out << " (6n − joint equations − couplers = 6·" << r.bodies << " − " << r.joint_equations << " − " << r.couplers << ")";
  out << " (after drivers: " << r.dof_after_drivers_count << ")\n";
  if (r.planar) PrintPlanar(*r.planar, r.drivers, out);
  if (r.mobility) PrintMobility(*r.mobility, r.drivers, out);
  if (r.branches)
    out << "  assembly branches at the drivers' design values: " << r.branches->branches << " (from "
        << r.branches->restarts << " random restarts, " << r.branches->converged
        << " assembled; joints mounted backwards not counted)\n";
  PrintGeometry(r, out);
  PrintAssembly(r, out);
  if (r.clearance) PrintClearance(*r.clearance, out);
}

}  // namespace

json CheckReportJson(const CheckReport& r) {
  json j;
  j["file"] = r.file;
  j["errors"] = DiagnosticsJson(r.errors);
  j["warnings"] = DiagnosticsJson(r.warnings);
  j["valid"] = r.valid;
  j["expect"] = json::array();
  for (const auto& e : r.expectations)
    j["expect"].push_back({{"key", e.key}, {"expected", ValueJson(e.expected)}, {"actual", ValueJson(e.actual)}, {"held", e.held}});
  for (size_t k = 0; k < r.expectations.size(); ++k)
    if (!r.expectations[k].where.empty()) j["expect"][k]["where"] = r.expectations[k].where;
  if (!r.valid) return j;
  if (r.clearance) j["clearance"] = ClearanceJson(*r.clearance);
  j["name"] = r.name;
  j["bodies"] = r.bodies;
  json joints = json::object();
  for (const auto& [type, count] : r.joints) joints[type] = count;
  j["joints"] = joints;
  j["drivers"] = r.drivers;
  j["grubler"] = r.grubler;
  if (r.couplers > 0) j["couplers"] = r.couplers;
  j["dof_after_drivers_count"] = r.dof_after_drivers_count;
  if (r.planar) j["planar"] = PlanarJson(*r.planar, r.drivers);
  if (r.mobility) j["mobility"] = MobilityJson(*r.mobility, r.drivers);
  j["geometry"] = GeometryJson(r);
  if (r.branches)
    j["branches"] = {{"count", r.branches->branches}, {"restarts", r.branches->restarts},
                     {"converged", r.branches->converged}, {"distances_from_design", r.branches->distances}};
  j["parameters"] = ParametersJson(r.parameters);
  if (r.assembly) j["assembly"] = AssemblyJson(r);
  return j;
}

json CheckReportsJson(const std::vector<CheckReport>& reports) {
  json doc = {{"mechkin_check", 1}, {"files", json::array()}};
  bool ok = true;
  for (const auto& r : reports) {
    doc["files"].push_back(CheckReportJson(r));
    ok = ok && r.ok();
  }
  doc["ok"] = ok;
  return doc;
}

std::string CheckReportJsonText(const CheckReport& report) {
  return CheckReportJson(report).dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string CheckReportsJsonText(const std::vector<CheckReport>& reports) {
  return CheckReportsJson(reports).dump(2, ' ', false, json::error_handler_t::replace);
}

void PrintCheckReport(const CheckReport& r, std::ostream& out) {
  out << r.file << ": ";
  if (!r.valid) PrintErrors(r, out);
  else PrintSummary(r, out);
  for (const auto& w : r.warnings) out << "  warning: " << w.pointer << ": " << w.message << "\n";
  for (const auto& e : r.expectations) out << "  " << ExpectationLine(e) << "\n";
}

std::string ExpectationLine(const ExpectationResult& e) {
  return "expect " + e.key + " = " + ValueJson(e.expected).dump() + ": " +
         (e.held ? "held" : "FAILED (actual " + ValueJson(e.actual).dump() + ")") + (e.where.empty() ? "" : ": " + e.where);
}

}  // namespace mechkin
