// Writers of `mechkin bench` results: the grid as CSV, the front as SVG and as text.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "analysis/speed_accuracy.hpp"

namespace mechkin {

void WriteBenchCsv(const std::vector<BenchResult>& results, std::ostream& out);
/// `title` is escaped for SVG.
void WriteBenchSvg(const std::vector<BenchResult>& results, const std::string& title, std::ostream& out);
/// The front as a table and one recommendation line per need.
void PrintFront(const std::vector<BenchResult>& results, std::ostream& out);

}  // namespace mechkin
