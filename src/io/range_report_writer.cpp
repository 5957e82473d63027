#include "io/range_report_writer.hpp"

#include <cmath>
#include <cstdio>

namespace mechkin {

namespace {

nlohmann::json EndJson(const RangeEnd& e) {
  return {{"kind", e.kind}, {"value", std::isfinite(e.value) ? nlohmann::json(e.value) : nlohmann::json(nullptr)},
          {"message", e.message}};
}

std::string NumberText(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

std::string EndText(const RangeEnd& e, const std::string& unit) {
  std::string s = NumberText(e.value) + " " + unit + " (" + e.kind + ")";
  if (e.kind == "failed") s += ": " + e.message;
  return s;
}

}  // namespace

nlohmann::json RangeReportJson(const RangeReport& r) {
  nlohmann::json j = {{"mechkin_range", 1}, {"ok", r.ok}};
  if (r.interrupted) j["partial"] = true, j["note"] = "interrupted";
  if (!r.ok) j["message"] = r.message;
  j["drivers"] = nlohmann::json::array();
  for (const auto& d : r.drivers)
    j["drivers"].push_back({{"driver", d.driver}, {"unit", d.unit}, {"design_value", d.design_value},
                            {"lower", EndJson(d.lower)}, {"upper", EndJson(d.upper)},
                            {"max_condition", d.max_condition}, {"value_at_max_condition", d.value_at_max_condition}});
  return j;
}

void PrintRangeReport(const RangeReport& r, std::ostream& out) {
  if (r.interrupted) out << "# PARTIAL REPORT: interrupted; " << r.drivers.size() << " drivers done\n";
  if (!r.ok) {
    out << "range: " << r.message << "\n";
    return;
  }
  for (const auto& d : r.drivers) {
    out << "driver `" << d.driver << "` (design value " << NumberText(d.design_value) << " " << d.unit << "): ";
    if (d.upper.kind == "full turn") out << "full turn";
    else out << "from " << EndText(d.lower, d.unit) << " to " << EndText(d.upper, d.unit);
    out << "; largest condition " << NumberText(d.max_condition) << " at " << NumberText(d.value_at_max_condition) << " " << d.unit
        << "\n";
  }
}

std::string RangeReportJsonText(const RangeReport& x) { return RangeReportJson(x).dump(2); }

}  // namespace mechkin
