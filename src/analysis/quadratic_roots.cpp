#include "analysis/quadratic_roots.hpp"

#include <cmath>
#include <complex>

namespace mechkin {

using Complex = std::complex<double>;

Eigen::VectorXcd QuadraticSystem::Value(const Eigen::VectorXcd& x) const {
  Eigen::VectorXcd f(size());
  for (int j = 0; j < size(); ++j) {
    const Eigen::VectorXcd Ax = A[j].cast<Complex>() * x;
    f[j] = c[j] + 2.0 * (b.row(j).cast<Complex>() * x)(0) + (x.transpose() * Ax)(0);
  }
  return f;
}

Eigen::MatrixXcd QuadraticSystem::Jacobian(const Eigen::VectorXcd& x) const {
  Eigen::MatrixXcd J(size(), size());
  for (int j = 0; j < size(); ++j) J.row(j) = 2.0 * (b.row(j).cast<Complex>() + (A[j].cast<Complex>() * x).transpose());
  return J;
}

namespace {

// H(x, s) = (1 − s)·γ·G(x) + s·F(x), G_j = x_j² − 1.
const Complex kGamma = std::polar(1.0, 2.1098);
constexpr double kFarAway = 100;

Eigen::VectorXcd Homotopy(const QuadraticSystem& q, const Eigen::VectorXcd& x, double s) {
  Eigen::VectorXcd g = x.cwiseProduct(x) - Eigen::VectorXcd::Ones(x.size());
  return (1 - s) * kGamma * g + s * q.Value(x);
}

Eigen::MatrixXcd HomotopyJacobian(const QuadraticSystem& q, const Eigen::VectorXcd& x, double s) {
  Eigen::MatrixXcd dg = (2.0 * x).asDiagonal();
  return (1 - s) * kGamma * dg + s * q.Jacobian(x);
}

// Newton at fixed s: true when the correction falls below 1e-11 of |x| within 4 steps.
bool Correct(const QuadraticSystem& q, double s, Eigen::VectorXcd* x) {
  for (int it = 0; it < 4; ++it) {
    const Eigen::VectorXcd dx = HomotopyJacobian(q, *x, s).fullPivLu().solve(-Homotopy(q, *x, s));
    if (!dx.allFinite()) return false;
    *x += dx;
    if (dx.norm() <= 1e-11 * (1 + x->norm())) return true;
  }
  return false;
}

enum class PathEnd { Finite, Infinite, Lost };

// Euler predictor (dx/ds = −H_x⁻¹ H_s) and Newton corrector with step halving.
PathEnd Track(const QuadraticSystem& q, double infinity, Eigen::VectorXcd* x) {
  double s = 0, ds = 0.02;
  for (int steps = 0; steps < 20000 && s < 1; ++steps) {
    ds = std::min(ds, 1 - s);
    const Eigen::VectorXcd gx = x->cwiseProduct(*x) - Eigen::VectorXcd::Ones(x->size());
    const Eigen::VectorXcd hs = q.Value(*x) - kGamma * gx;
    Eigen::VectorXcd next = *x + ds * HomotopyJacobian(q, *x, s).fullPivLu().solve(-hs);
    if (next.allFinite() && Correct(q, s + ds, &next)) {
      s = (ds == 1 - s) ? 1 : s + ds;
      *x = next;
      ds = std::min(2 * ds, 0.05);
      if (x->norm() > infinity) return PathEnd::Infinite;
    } else {
      ds *= 0.5;
      // A path toward a multiple root at infinity slows down long before `infinity`;
      // the roots sought are of order 1 (the caller normalizes them).
      if (ds < 1e-14) return x->norm() > kFarAway ? PathEnd::Infinite : PathEnd::Lost;
    }
  }
  return s >= 1 ? PathEnd::Finite : x->norm() > kFarAway ? PathEnd::Infinite : PathEnd::Lost;
}

}  // namespace

QuadraticRoots RealRootsOfQuadratics(const QuadraticSystem& q, double infinity) {
  QuadraticRoots out;
  const int k = q.size();
  if (k < 1 || k > 8) {
    out.complete = false;
    return out;
  }
  for (int path = 0; path < (1 << k); ++path) {
    Eigen::VectorXcd x(k);
    for (int j = 0; j < k; ++j) x[j] = (path >> j & 1) ? -1.0 : 1.0;
    const PathEnd end = Track(q, infinity, &x);
    if (end == PathEnd::Infinite) continue;
    if (end == PathEnd::Lost) {
      out.complete = false;
      continue;
    }
    // A root where F_x is singular is multiple or not isolated: the count is uncertain.
    Eigen::JacobiSVD<Eigen::MatrixXcd> svd(q.Jacobian(x));
    const auto& sv = svd.singularValues();
    if (!(sv[k - 1] > 1e-8 * std::max(1.0, sv[0]))) out.complete = false;
    if (x.imag().norm() > 1e-7 * (1 + x.norm())) continue;
    const Eigen::VectorXd r = x.real();
    bool seen = false;
    for (const auto& other : out.real) seen = seen || (other - r).norm() <= 1e-6 * (1 + r.norm());
    if (!seen) out.real.push_back(r);
  }
  return out;
}

}  // namespace mechkin

