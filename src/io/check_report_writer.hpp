// `mechkin check` reports rendered as text and as JSON, from the typed CheckReport.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <vector>

#include "analysis/check_report.hpp"

namespace mechkin {

/// One file's report as the JSON object of format "mechkin_check": 1.
nlohmann::json CheckReportJson(const CheckReport& report);
/// The whole `--format json` document for several files.
nlohmann::json CheckReportsJson(const std::vector<CheckReport>& reports);
/// The JSON texts as `check --format json` writes them (invalid UTF-8 replaced), so the
/// CLI and the Python binding never handle JSON themselves.
std::string CheckReportJsonText(const CheckReport& report);
std::string CheckReportsJsonText(const std::vector<CheckReport>& reports);
/// The human-readable report of one file.
void PrintCheckReport(const CheckReport& report, std::ostream& out);

/// "expect mobility = 1: held", "expect min/mu = 40.0: FAILED (actual 26.4): where":
/// one expectation as `check` prints it (and `run` its motion bounds).
std::string ExpectationLine(const ExpectationResult& e);

}  // namespace mechkin
