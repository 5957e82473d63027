// libFuzzer target: the driver expression parser and its Taylor evaluation.
#include <cstddef>
#include <cstdint>
#include <string>

#include "model/time_function.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const mechkin::Expression e = mechkin::Expression::Parse(text);
    for (double t : {-1.0, 0.0, 0.25, 1.0, 1e6}) {
      try {
        (void)e.Eval(t);
      } catch (const mechkin::JetDomainError&) {
      }
    }
  } catch (const mechkin::ExpressionError&) {
  }
  return 0;
}
