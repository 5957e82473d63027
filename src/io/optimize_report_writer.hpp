// `mechkin optimize` (analysis/optimize.hpp): the optimised file (the original
// document with the varied parameters' values replaced, everything else as written)
// and the report, as text and as JSON (README "Design by objective").
#pragma once

#include <map>
#include <ostream>
#include <string>

#include "analysis/optimize.hpp"

namespace mechkin {

/// `text` (a mechanism file) with each named parameter's value replaced by the number
/// (a plain entry becomes the number; an object's "value" is replaced, its min, max,
/// tolerance and description kept). False with *error when the text is not a JSON
/// object with those parameters.
bool WithParameterValues(const std::string& text, const std::map<std::string, double>& values, std::string* out,
                         std::string* error);

/// The report as a JSON object (one line).
std::string OptimizeReportJsonText(const OptimizeResult& r);
/// The report as text.
void PrintOptimizeReport(const OptimizeResult& r, std::ostream& out);

}  // namespace mechkin
