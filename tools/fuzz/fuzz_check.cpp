// libFuzzer target: `check` end to end — loader, mobility (rank, redundancy,
// idle freedoms, driving status) and the JSON and text reports — must never
// crash, hang or throw for any input.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "analysis/check_report.hpp"
#include "io/check_report_writer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const mechkin::LoadResult loaded = mechkin::LoadMechanismText(text, "fuzz");
  // Keep each input cheap: the dense rank analysis of big models is measured elsewhere.
  if (loaded.ok() && loaded.model->num_bodies() > 40) return 0;
  const mechkin::CheckReport report = mechkin::CheckLoaded("fuzz", loaded);
  std::ostringstream out;
  mechkin::PrintCheckReport(report, out);
  (void)mechkin::CheckReportJson(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
  return 0;
}
