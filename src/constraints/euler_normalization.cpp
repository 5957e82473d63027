// §3.5 EUL: Φ = pᵀp − 1 (p version only).
#include "constraints/families.hpp"

namespace mechkin {

// RHS_k = −Σ_{m=1}^{k−1} binom(k,m) p^(m)·p^(k−m): 0, −2ṗᵀṗ, −6ṗᵀp̈, −6p̈ᵀp̈ − 8ṗᵀp⃛.
double EulerNormalization::Rhs(const Vec4* pd, int k) {
  double s = 0;
  for (int m = 1; m < k; ++m) s += kBinomial[k][m] * pd[m].dot(pd[k - m]);
  return -s;
}

}  // namespace mechkin
