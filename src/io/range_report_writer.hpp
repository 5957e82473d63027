// `mechkin range` reports as text and JSON, from the typed RangeReport.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>

#include "analysis/range.hpp"

namespace mechkin {

nlohmann::json RangeReportJson(const RangeReport& report);
/// The JSON text `range --format json` writes (without the final newline).
std::string RangeReportJsonText(const RangeReport& report);
void PrintRangeReport(const RangeReport& report, std::ostream& out);

}  // namespace mechkin
