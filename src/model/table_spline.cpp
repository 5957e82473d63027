#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "model/time_function.hpp"

namespace mechkin {
namespace {

// On an interval of length h with end data (y0,d0,m0) and (y1,d1,m1), the quintic
// p(x) = y0 + d0 x + m0 x²/2 + c3 x³ + c4 x⁴ + c5 x⁵ has
//   c3 = (10A − 4Bh + Ch²/2)/h³, c4 = (−15A + 7Bh − Ch²)/h⁴, c5 = (6A − 3Bh + Ch²/2)/h⁵
// with A = y1 − y0 − d0 h − m0 h²/2, B = d1 − d0 − m0 h, C = m1 − m0.
struct Quintic { double c[6]; };

Quintic MakeQuintic(double h, double y0, double d0, double m0, double y1, double d1, double m1) {
  const double A = y1 - y0 - d0 * h - m0 * h * h / 2, B = d1 - d0 - m0 * h, C = m1 - m0;
  Quintic q;
  q.c[0] = y0; q.c[1] = d0; q.c[2] = m0 / 2;
  q.c[3] = (10 * A - 4 * B * h + C * h * h / 2) / (h * h * h);
  q.c[4] = (-15 * A + 7 * B * h - C * h * h) / (h * h * h * h);
  q.c[5] = (6 * A - 3 * B * h + C * h * h / 2) / (h * h * h * h * h);
  return q;
}

// Third and fourth derivative of the quintic at x.
void D34(const Quintic& q, double x, double* d3, double* d4) {
  *d3 = 6 * q.c[3] + 24 * q.c[4] * x + 60 * q.c[5] * x * x;
  *d4 = 24 * q.c[4] + 120 * q.c[5] * x;
}

}  // namespace

TableSpline::TableSpline(std::vector<double> t, std::vector<double> v, Interpolation how)
    : t_(std::move(t)), v_(std::move(v)) {
  const int n = static_cast<int>(t_.size());
  if (n < 2 || v_.size() != t_.size()) throw std::invalid_argument("a table needs at least 2 rows [t, value]");
  for (int k = 0; k < n; ++k) {
    if (!std::isfinite(t_[k]) || !std::isfinite(v_[k])) throw std::invalid_argument("table values must be finite numbers");
    if (k > 0 && !(t_[k] > t_[k - 1]))
      throw std::invalid_argument("table times must increase strictly (row " + std::to_string(k) + ")");
  }
  if (n == 2 || how == Interpolation::Linear) BuildLinear();
  else if (how == Interpolation::Cubic) BuildCubic();
  else BuildQuintic();
}

void TableSpline::BuildLinear() {
  for (size_t k = 0; k + 1 < t_.size(); ++k)
    poly_.push_back({v_[k], (v_[k + 1] - v_[k]) / (t_[k + 1] - t_[k]), 0, 0, 0, 0});
}

// Natural cubic spline: second derivatives M_k from the tridiagonal system
// h_{k-1} M_{k-1} + 2 (h_{k-1} + h_k) M_k + h_k M_{k+1} = 6 (s_k - s_{k-1}), M_0 = M_{n-1} = 0
// (s_k the slope of interval k), solved by the Thomas algorithm (diagonally dominant).
void TableSpline::BuildCubic() {
  const int n = static_cast<int>(t_.size());
  std::vector<double> h(n - 1), slope(n - 1), M(n, 0.0), diag(n, 1.0), rhs(n, 0.0), upper(n, 0.0), lower(n, 0.0);
  for (int k = 0; k + 1 < n; ++k) {
    h[k] = t_[k + 1] - t_[k];
    slope[k] = (v_[k + 1] - v_[k]) / h[k];
  }
  for (int k = 1; k + 1 < n; ++k) {
    lower[k] = h[k - 1];
    diag[k] = 2 * (h[k - 1] + h[k]);
    upper[k] = h[k];
    rhs[k] = 6 * (slope[k] - slope[k - 1]);
  }
  for (int k = 1; k < n; ++k) {
    const double w = lower[k] / diag[k - 1];
    diag[k] -= w * upper[k - 1];
    rhs[k] -= w * rhs[k - 1];
  }
  M[n - 1] = rhs[n - 1] / diag[n - 1];
  for (int k = n - 2; k >= 0; --k) M[k] = (rhs[k] - upper[k] * M[k + 1]) / diag[k];
  for (int k = 0; k + 1 < n; ++k)
    poly_.push_back({v_[k], slope[k] - h[k] * (2 * M[k] + M[k + 1]) / 6, M[k] / 2, (M[k + 1] - M[k]) / (6 * h[k]), 0, 0});
}

void TableSpline::BuildQuintic() {
  const int n = static_cast<int>(t_.size());
  // Unknowns x = (d_0, m_0, …, d_{n−1}, m_{n−1}). Conditions: p''' and p'''' continuous
  // at interior knots, p''' = p'''' = 0 at both ends. Every condition is linear in x;
  // its coefficients are read off by evaluating with unit data (the map is affine).
  const int N = 2 * n;
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(N);
  auto interval_d34 = [&](int k, bool at_end, int which, const double* dm6, double* out) {
    // dm6 = (y0,d0,m0,y1,d1,m1) for interval k
    const double h = t_[k + 1] - t_[k];
    const Quintic q = MakeQuintic(h, dm6[0], dm6[1], dm6[2], dm6[3], dm6[4], dm6[5]);
    double d3, d4;
    D34(q, at_end ? h : 0.0, &d3, &d4);
    *out = which == 3 ? d3 : d4;
  };
  // Adds row `row`: sign * (derivative `which` of interval k at start/end).
  auto add_condition = [&](int row, int k, bool at_end, int which, double sign) {
    const double y[6] = {v_[k], 0, 0, v_[k + 1], 0, 0};
    double base;
    interval_d34(k, at_end, which, y, &base);
    rhs[row] -= sign * base;
    const int cols[4] = {2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3};
    const int slots[4] = {1, 2, 4, 5};
    for (int u = 0; u < 4; ++u) {
      double data[6] = {0, 0, 0, 0, 0, 0};
      data[slots[u]] = 1;
      double coeff;
      interval_d34(k, at_end, which, data, &coeff);
      if (coeff != 0) trip.emplace_back(row, cols[u], sign * coeff);
    }
  };
  int row = 0;
  for (int which : {3, 4}) add_condition(row++, 0, false, which, 1.0);
  for (int k = 1; k < n - 1; ++k)
    for (int which : {3, 4}) {
      add_condition(row, k - 1, true, which, 1.0);
      add_condition(row, k, false, which, -1.0);
      ++row;
    }
  for (int which : {3, 4}) add_condition(row++, n - 2, true, which, 1.0);
  Eigen::SparseMatrix<double> M(N, N);
  M.setFromTriplets(trip.begin(), trip.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(M);
  if (lu.info() != Eigen::Success) throw std::invalid_argument("table spline system is singular");
  const Eigen::VectorXd x = lu.solve(rhs);
  for (int k = 0; k + 1 < n; ++k) {
    const Quintic q = MakeQuintic(t_[k + 1] - t_[k], v_[k], x[2 * k], x[2 * k + 1], v_[k + 1], x[2 * k + 2], x[2 * k + 3]);
    poly_.push_back({q.c[0], q.c[1], q.c[2], q.c[3], q.c[4], q.c[5]});
  }
}

double TableSpline::MaxOvershoot(int* interval) const {
  double worst = 0;
  *interval = 0;
  for (size_t k = 0; k < poly_.size(); ++k) {
    const double lo = std::min(v_[k], v_[k + 1]), hi = std::max(v_[k], v_[k + 1]), h = t_[k + 1] - t_[k];
    for (int s = 1; s < 16; ++s) {
      const double x = h * s / 16;
      double p = 0;
      for (int i = 5; i >= 0; --i) p = p * x + poly_[k][i];
      const double over = std::max(p - hi, lo - p);
      if (over > worst) {
        worst = over;
        *interval = static_cast<int>(k);
      }
    }
  }
  return worst;
}

double TableSpline::ValueRange() const {
  const auto [lo, hi] = std::minmax_element(v_.begin(), v_.end());
  return *hi - *lo;
}

Jet TableSpline::Eval(double t) const {
  if (!(t >= t_.front() && t <= t_.back()))
    throw std::out_of_range("t = " + std::to_string(t) + " s is outside the table's range [" +
                            std::to_string(t_.front()) + ", " + std::to_string(t_.back()) + "] s");
  int k = static_cast<int>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
  k = std::clamp(k, 0, static_cast<int>(t_.size()) - 2);
  const auto& q = poly_[k];
  // Taylor coefficients of p around x: c_j(x) = Σ_{i≥j} binom(i,j) q_i x^{i−j}.
  const double x = t - t_[k];
  static constexpr double kBinom[6][6] = {{1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}, {1, 4, 6, 4, 1}, {1, 5, 10, 10, 5, 1}};
  Jet j;
  for (int jj = 0; jj <= kMaxOrder; ++jj) {
    double s = 0, xp = 1;
    for (int i = jj; i <= 5; ++i) { s += kBinom[i][jj] * q[i] * xp; xp *= x; }
    j.c[jj] = s;
  }
  return j;
}

}  // namespace mechkin
