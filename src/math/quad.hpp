// Quadruple precision (binary128, 113-bit significand) where the compiler has it:
// GCC's and Clang's __float128 on x86-64; long double where that is already binary128
// (WebAssembly) or is the widest there is. For the pose error of the measured error
// bounds (constraints.md §8, "Measured", step 1): near a singular position long
// double's round-off of Φ, solved through Φ_q, is as large as the pose error itself.
#pragma once

#include <Eigen/Core>

namespace mechkin {

#if defined(__SIZEOF_FLOAT128__) && !defined(__EMSCRIPTEN__)
using Quad = __float128;
#define MECHKIN_QUAD_IS_FLOAT128 1
#else
using Quad = long double;
#endif

/// √x in Quad for x ≥ 0: long double's root, then one Newton step (doubles its bits).
inline Quad QuadSqrt(Quad x) {
  if (!(x > 0)) return 0;
  const Quad r = static_cast<Quad>(__builtin_sqrtl(static_cast<long double>(x)));
  return (r + x / r) / 2;
}

}  // namespace mechkin

#ifdef MECHKIN_QUAD_IS_FLOAT128
namespace Eigen {
template <>
struct NumTraits<mechkin::Quad> : GenericNumTraits<long double> {
  using Real = mechkin::Quad;
  using NonInteger = mechkin::Quad;
  using Nested = mechkin::Quad;
  using Literal = mechkin::Quad;
  enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 0, ReadCost = 1, AddCost = 8, MulCost = 16 };
  static inline Real epsilon() { return Real(1) / (Real(1ULL << 56) * Real(1ULL << 56)); }  // 2^-112
  static inline Real dummy_precision() { return epsilon() * Real(1ULL << 40); }
  static inline int digits10() { return 33; }
};
}  // namespace Eigen
#endif
