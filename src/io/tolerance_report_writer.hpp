// `mechkin tolerance` reports as text and JSON, from the typed ToleranceReport.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "analysis/tolerance.hpp"

namespace mechkin {

nlohmann::json ToleranceReportJson(const ToleranceReport& report);
/// The JSON text `tolerance --format json` writes (without the final newline).
std::string ToleranceReportJsonText(const ToleranceReport& report);
void PrintToleranceReport(const ToleranceReport& report, std::ostream& out);

}  // namespace mechkin
