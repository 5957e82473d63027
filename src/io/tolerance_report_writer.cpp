#include "io/tolerance_report_writer.hpp"

#include <cstdio>

namespace mechkin {

namespace {

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::string Header(const ToleranceColumn& c) { return c.unit.empty() ? c.name : c.name + " [" + c.unit + "]"; }

}  // namespace

nlohmann::json ToleranceReportJson(const ToleranceReport& r) {
  using nlohmann::json;
  json j = {{"mechkin_tolerance", 1}, {"ok", r.ok}};
  if (r.interrupted) j["partial"] = true, j["note"] = "interrupted";
  if (!r.ok) {
    j["message"] = r.message;
    return j;
  }
  json params = json::object();
  for (size_t p = 0; p < r.parameters.size(); ++p) params[r.parameters[p]] = r.tolerances[p];
  j["tolerances"] = params;
  j["t"] = r.t;
  j["columns"] = json::array();
  for (const auto& c : r.columns) {
    if (!c.not_computed.empty()) {
      j["columns"].push_back({{"name", c.name}, {"unit", c.unit}, {"not_computed", c.not_computed}});
      continue;
    }
    json contributions = json::array();
    for (const auto& [name, value] : c.contributions) contributions.push_back({{"parameter", name}, {"contribution", value}});
    json col = {{"name", c.name}, {"unit", c.unit}, {"worst_case", c.worst_case}, {"rss", c.rss},
                {"max_worst_case", c.max_worst_case}, {"t_max_worst_case", c.t_worst_case},
                {"max_rss", c.max_rss}, {"t_max_rss", c.t_rss}, {"contributions", contributions}};
    if (r.samples > 0)
      col["monte_carlo"] = {{"max_deviation", c.mc_max_deviation}, {"t_max_deviation", c.t_mc_max},
                            {"max_std", c.mc_max_std}, {"t_max_std", c.t_mc_std}};
    j["columns"].push_back(col);
  }
  if (r.samples > 0 || r.failed_samples > 0)
    j["monte_carlo"] = {{"samples", r.samples}, {"failed", r.failed_samples}, {"seed", r.seed},
                        {"distribution", "uniform within the tolerances"}};
  return j;
}

void PrintToleranceReport(const ToleranceReport& r, std::ostream& out) {
  if (r.interrupted)
    out << "# PARTIAL REPORT: interrupted; " << r.samples + r.failed_samples << " Monte-Carlo samples finished\n";
  if (!r.ok) {
    out << "tolerance: " << r.message << "\n";
    return;
  }
  out << "tolerances:";
  for (size_t p = 0; p < r.parameters.size(); ++p) out << " " << r.parameters[p] << " ±" << Num(r.tolerances[p]);
  out << "  (" << r.t.size() << " rows)\n";
  out << "linear stack-up from the exact sensitivities (worst case = sum |d/dp|·tol; RSS = root-sum-square):\n";
  for (const auto& c : r.columns) {
    if (!c.not_computed.empty()) {
      out << "  " << Header(c) << ": " << c.not_computed << "\n";
      continue;
    }
    out << "  " << Header(c) << ": worst case " << Num(c.max_worst_case) << " at t = " << Num(c.t_worst_case)
        << " s; RSS " << Num(c.max_rss) << " at t = " << Num(c.t_rss) << " s; contributions:";
    for (const auto& [name, value] : c.contributions)
      out << " " << name << " " << Num(value) << " (" << Num(c.max_worst_case > 0 ? 100 * value / c.max_worst_case : 0)
          << " %)";
    out << "\n";
  }
  if (r.samples == 0 && r.failed_samples == 0) return;
  out << "Monte-Carlo: " << r.samples << " variants (uniform within the tolerances, seed " << r.seed << ")";
  if (r.failed_samples > 0) out << ", " << r.failed_samples << " did not complete";
  out << "; linear theory: largest deviation <= worst case, std = RSS/sqrt(3):\n";
  for (const auto& c : r.columns)
    if (c.not_computed.empty())
      out << "  " << Header(c) << ": largest deviation " << Num(c.mc_max_deviation) << " at t = " << Num(c.t_mc_max)
        << " s (worst case " << Num(c.max_worst_case) << "); largest std " << Num(c.mc_max_std) << " at t = "
        << Num(c.t_mc_std) << " s (RSS/sqrt(3) " << Num(c.max_rss / std::sqrt(3.0)) << ")\n";
}

std::string ToleranceReportJsonText(const ToleranceReport& x) { return ToleranceReportJson(x).dump(2); }

}  // namespace mechkin
