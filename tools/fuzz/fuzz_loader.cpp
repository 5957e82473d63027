// libFuzzer target: the mechanism loader must never crash, hang or throw.
#include <cstddef>
#include <cstdint>
#include <string>

#include "analysis/load.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const mechkin::LoadResult r = mechkin::LoadMechanismText(text, "fuzz");
  if (r.ok() && !r.model->drivers.empty()) {
    // Evaluate every driver function a little: domain errors must be exceptions of
    // the documented kinds, never crashes.
    for (const auto& d : r.model->drivers)
      for (double t : {0.0, 0.5, 1.0}) {
        try {
          (void)d.function.Eval(t);
        } catch (const mechkin::JetDomainError&) {
        } catch (const std::out_of_range&) {
        }
      }
  }
  return 0;
}
