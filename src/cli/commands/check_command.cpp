#include "cli/commands/check_command.hpp"

#include <map>
#include <nlohmann/json.hpp>

#include "mobility/grubler.hpp"
#include "mobility/mobility.hpp"
#include "model/loader.hpp"

namespace mechkin {

using nlohmann::json;

void SetupCheckCommand(CLI::App& app, CheckOptions* options) {
  CLI::App* cmd = app.add_subcommand("check", "Validate mechanism files; report degrees of freedom and expectations");
  cmd->add_option("files", options->files, "Mechanism files (format v1)")->required();
  cmd->add_option("--format", options->format, "Report format")
      ->check(CLI::IsMember({"text", "json"}))
      ->default_str("text");
}

namespace {

json DiagnosticsJson(const std::vector<Diagnostic>& ds) {
  json a = json::array();
  for (const auto& d : ds) a.push_back({{"pointer", d.pointer}, {"message", d.message}, {"fix", d.fix}});
  return a;
}

// Checks one file; returns its JSON report.
json CheckFile(const std::string& path) {
  json r;
  r["file"] = path;
  const LoadResult loaded = LoadMechanismFile(path);
  r["errors"] = DiagnosticsJson(loaded.errors);
  r["warnings"] = DiagnosticsJson(loaded.warnings);
  r["valid"] = loaded.ok();
  r["expect"] = json::array();
  if (!loaded.ok()) return r;
  const Model& m = *loaded.model;
  r["name"] = m.name;
  r["bodies"] = m.num_bodies();
  json joints = json::object();
  for (const auto& j : m.joints) joints[JointTypeName(j.type)] = joints.value(JointTypeName(j.type), 0) + 1;
  r["joints"] = joints;
  r["drivers"] = static_cast<int>(m.drivers.size());
  const int grubler = CalcGrublerCount(m);
  r["grubler"] = grubler;
  r["dof_after_drivers_count"] = grubler - static_cast<int>(m.drivers.size());

  const MobilityReport mob = CalcMobility(m);
  r["mobility"] = MobilityReportJson(m, mob);

  auto expect = [&](const char* key, const json& expected, const json& actual) {
    r["expect"].push_back({{"key", key}, {"expected", expected}, {"actual", actual}, {"held", expected == actual}});
  };
  if (m.expect.grubler) expect("grubler", *m.expect.grubler, grubler);
  if (m.expect.mobility) expect("mobility", *m.expect.mobility, mob.assembled ? json(mob.mobility) : json(nullptr));
  if (m.expect.redundant) expect("redundant", *m.expect.redundant, mob.assembled ? json(mob.redundant) : json(nullptr));
  if (m.expect.idle) expect("idle", *m.expect.idle, mob.assembled ? json(static_cast<int>(mob.idle.size())) : json(nullptr));
  if (m.expect.driven) expect("driven", *m.expect.driven, mob.assembled ? json(mob.driving_status) : json(nullptr));
  return r;
}

bool FileOk(const json& r) {
  if (!r["valid"].get<bool>()) return false;
  for (const auto& e : r["expect"]) if (!e["held"].get<bool>()) return false;
  return true;
}

void PrintText(const json& r, std::ostream& out) {
  out << r["file"].get<std::string>() << ": ";
  if (!r["valid"].get<bool>()) {
    out << "INVALID (" << r["errors"].size() << (r["errors"].size() == 1 ? " error)\n" : " errors)\n");
    for (const auto& e : r["errors"]) {
      out << "  error: " << (e["pointer"].get<std::string>().empty() ? "(file)" : e["pointer"].get<std::string>())
          << ": " << e["message"].get<std::string>();
      if (!e["fix"].get<std::string>().empty()) out << "\n         fix: " << e["fix"].get<std::string>();
      out << "\n";
    }
  } else {
    out << (r["name"].get<std::string>().empty() ? "(unnamed)" : r["name"].get<std::string>()) << "\n";
    out << "  bodies: " << r["bodies"] << " moving\n  joints: ";
    bool first = true;
    int total = 0;
    for (const auto& kv : r["joints"].items()) {
      out << (first ? "" : ", ") << kv.value().get<int>() << " " << kv.key();
      total += kv.value().get<int>();
      first = false;
    }
    out << (first ? "none" : "") << " (" << total << " total)\n";
    out << "  drivers: " << r["drivers"] << "\n";
    out << "  Grübler–Kutzbach count: " << r["grubler"] << " (after drivers: " << r["dof_after_drivers_count"] << ")\n";
    PrintMobilityText(r["mobility"], out);
  }
  for (const auto& w : r["warnings"])
    out << "  warning: " << w["pointer"].get<std::string>() << ": " << w["message"].get<std::string>() << "\n";
  for (const auto& e : r["expect"]) {
    out << "  expect " << e["key"].get<std::string>() << " = " << e["expected"].dump() << ": "
        << (e["held"].get<bool>() ? "held" : "FAILED (actual " + e["actual"].dump() + ")") << "\n";
  }
}

}  // namespace

int RunCheck(const CheckOptions& options, std::ostream& out, std::ostream& /*err*/) {
  json report = {{"mechkin_check", 1}, {"files", json::array()}};
  bool ok = true;
  for (const auto& f : options.files) {
    json r;
    try {
      r = CheckFile(f);
    } catch (const std::exception& e) {
      // Defensive: an internal failure on one file must not stop the others.
      r = {{"file", f}, {"valid", false}, {"expect", json::array()}, {"warnings", json::array()},
           {"errors", json::array({{{"pointer", ""}, {"message", std::string("internal error: ") + e.what()}, {"fix", "please report this file"}}})}};
    }
    ok = ok && FileOk(r);
    if (options.format == "text") PrintText(r, out);
    report["files"].push_back(std::move(r));
  }
  report["ok"] = ok;
  if (options.format == "json") out << report.dump(2) << "\n";
  return ok ? 0 : 1;
}

}  // namespace mechkin
