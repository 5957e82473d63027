#include "analysis/singular_points.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/assembly.hpp"
#include "analysis/quadratic_roots.hpp"
#include "math/numbers.hpp"

namespace mechkin {
namespace {

constexpr int kDenseColumns = 1200;  // 200 bodies: the dense SVDs
// The fit's sample spacing δ, as a fraction of the step (Locate, ClassifyAt).
constexpr double kFitSpacing = 0.005;

Eigen::MatrixXd ActiveScaledJacobian(const ConstraintSystem& sys, const SystemState& s, const std::vector<int>& rows) {
  const Eigen::MatrixXd J = ScaledJacobian(sys, s);
  Eigen::MatrixXd out(rows.size(), J.cols());
  for (size_t k = 0; k < rows.size(); ++k) out.row(k) = J.row(rows[k]);
  return out;
}

// W·RHS_k of the active rows at pose `at` (k = 1 without rates: ν = −Φ_t; k = 2 with
// the ω'-layout rates `rates`: γ, docs/constraints.md §1.6), W the row weights.
Eigen::VectorXd ScaledRhs(const ConstraintSystem& sys, SystemState s, const std::vector<int>& rows,
                          const Eigen::VectorXd& weights, const Eigen::VectorXd* rates) {
  for (auto& b : s.bodies) {
    for (int k = 1; k <= kMaxOrder; ++k) b.r[k].setZero();
    for (int k = 0; k < kMaxOrder; ++k) b.w[k].setZero();
    b.PrepareOrder(1);
  }
  int order = 1;
  if (rates) {
    for (size_t b = 0; b < s.bodies.size(); ++b) {
      s.bodies[b].r[1] = rates->segment<3>(6 * b);
      s.bodies[b].w[0] = rates->segment<3>(6 * b + 3);
      s.bodies[b].PrepareOrder(2);
    }
    order = 2;
  }
  Eigen::VectorXd rhs;
  CalcRhs(sys, s, order, Formulation::Omega, &rhs);
  Eigen::VectorXd out(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) out[k] = weights[k] * rhs[rows[k]];
  return out;
}

// The root of the cubic through (x_i, g_i), x = −2, −1, 1, 2, nearest 0 (Newton from 0).
double CubicRoot(const double g[4]) {
  const double xs[4] = {-2, -1, 1, 2};
  Eigen::Matrix4d V;
  Eigen::Vector4d rhs;
  for (int i = 0; i < 4; ++i) {
    V.row(i) << 1, xs[i], xs[i] * xs[i], xs[i] * xs[i] * xs[i];
    rhs[i] = g[i];
  }
  const Eigen::Vector4d a = V.fullPivLu().solve(rhs);
  double x = 0;
  for (int it = 0; it < 50; ++it) {
    const double p = a[0] + x * (a[1] + x * (a[2] + x * a[3])), dp = a[1] + x * (2 * a[2] + 3 * x * a[3]);
    if (dp == 0) return kNaN;
    const double dx = p / dp;
    x -= dx;
    if (std::abs(dx) < 1e-15) break;
  }
  return x;
}

}  // namespace

bool IsFold(const ConstraintSystem& sys, const std::vector<int>& rows, const SystemState& s) {
  if (6 * sys.num_bodies() > kDenseColumns || rows.empty()) return false;
  const Eigen::MatrixXd J = ActiveScaledJacobian(sys, s, rows);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullU);
  const Eigen::VectorXd& sv = svd.singularValues();
  const int n = static_cast<int>(sv.size());
  int small = 0;
  while (small < n && sv[n - 1 - small] < 1e-4 * sv[0]) ++small;
  if (small == 0) return false;
  // The left null space: the small singular values' vectors and, with more rows than
  // columns, the columns of U beyond the singular values (exact zeros).
  const Eigen::MatrixXd U0 = svd.matrixU().rightCols(J.rows() - n + small);
  const Eigen::VectorXd nu = ScaledRhs(sys, s, rows, RowScales(sys, rows), nullptr);
  return nu.norm() > 0 && (U0.transpose() * nu).norm() > 1e-2 * nu.norm();
}

SingularityClassifier::SingularityClassifier(const ConstraintSystem& sys, const std::vector<int>& active)
    : ws_(sys, active, WorkspaceOptions{}), pose_(sys) {}

Eigen::VectorXd SingularityClassifier::SingularValues(const SystemState& s) const {
  Eigen::BDCSVD<Eigen::MatrixXd> svd(ActiveScaledJacobian(ws_.system(), s, ws_.active()));
  return svd.singularValues().reverse();
}

const SystemState* SingularityClassifier::SolvedPast(double t_star, double t_end) const {
  const Sample* latest = nullptr;
  for (const Sample& s : samples_)
    if (s.s.t > t_star && s.s.t <= t_end && WellDetermined(s) && (!latest || s.s.t > latest->s.t)) latest = &s;
  return latest ? &latest->s : nullptr;
}

// A tight solve at t from the Taylor prediction off the nearest sample (the branch
// the run is on), with its derivatives for the next predictions and its singular values.
bool SingularityClassifier::Probe(double t, const Sample** out) {
  // The source: the nearest sample whose derivatives are meaningful (one almost on
  // the singular position predicts nothing: its velocities are amplified by 1/σ_min).
  const Sample* from = &samples_[0];
  for (const Sample& s : samples_) {
    if (s.s.t == t) { *out = &s; return true; }
    if (WellDetermined(s) && std::abs(s.s.t - t) < std::abs(from->s.t - t)) from = &s;
  }
  Sample next{from->s, Eigen::VectorXd()};
  PredictPose(t - from->s.t, 3, &next.s);
  EvalDriverFunctions(ws_.system().model(), t, &next.s);
  AimRotationDrivers(ws_.system(), &next.s);
  SolveOptions tight;
  tight.tolerance = 1e-14;
  tight.max_iterations = 60;
  tight.target = 1e-17;
  tight.extended_precision = true;
  const SolveSummary sum = SolvePosition(ws_, tight, &next.s, false);
  if (!sum.success) return false;
  if (PoseDistance(from->s, next.s, ws_.system().model().characteristic_length) > 0.1) return false;
  SolveDerivatives(ws_, 3, &next.s);
  next.sigma = SingularValues(next.s);
  samples_.push_back(std::move(next));
  *out = &samples_.back();
  return true;
}

// How many singular values vanish linearly at `center`: they double from δ to 2δ
// away, the others hardly change.
int SingularityClassifier::CountVanishing(double center, double delta, bool* ok) {
  const Sample *near = nullptr, *far = nullptr;
  *ok = Probe(center + delta, &near) && Probe(center + 2 * delta, &far);
  if (!*ok) return 0;
  const Eigen::VectorXd a = near->sigma, b = far->sigma;
  int k = 0;
  while (k < a.size() && a[k] > 0 && b[k] / a[k] > 1.6 && b[k] / a[k] < 2.5) ++k;
  return k;
}

// The zero of g = ±(σ_1 ⋯ σ_k)^(1/k) (− before the zero, + after): the product of
// the k vanishing singular values is |t − t*| times a smooth positive function, so
// the cubic through four samples at ±δ, ±2δ locates t* to O(δ⁴) from poses that are
// themselves well determined.
double SingularityClassifier::FitZero(double center, double delta, int corank, bool* ok) {
  double g[4];
  const double offsets[4] = {-2, -1, 1, 2};
  for (int i = 0; i < 4; ++i) {
    const Sample* s = nullptr;
    *ok = Probe(center + offsets[i] * delta, &s);
    if (!*ok) return kNaN;
    g[i] = (offsets[i] < 0 ? -1 : 1) * std::exp(s->sigma.head(corank).array().log().mean());
  }
  const double x = CubicRoot(g);
  *ok = std::isfinite(x) && std::abs(x) <= 1;
  return center + x * delta;
}

// Scan, then a V-fit of σ_min shrinking around its minimum, then the corank and
// the cubic fit of the vanishing singular values. NaN when nothing is located, +inf
// for a near miss. Probes right at t* may fail (the pose is not determined there:
// other branches pass through it); they are skipped — the fit needs none of them.
double SingularityClassifier::Locate(double ta, double tb, double step, int* corank) {
  constexpr int kScan = 8;
  const double delta = kFitSpacing * step;
  double best_t = ta, best = samples_[0].sigma[0];
  for (int m = 1; m <= kScan; ++m) {
    const Sample* s = nullptr;
    if (Probe(ta + (tb - ta) * m / kScan, &s) && s->sigma[0] < best) best = s->sigma[0], best_t = s->s.t;
  }
  double spacing = (tb - ta) / kScan;
  for (int it = 0; it < 40 && spacing > 0.1 * delta; ++it) {
    const Sample *l = nullptr, *c = nullptr, *r = nullptr;
    if (!Probe(best_t - spacing, &l) || !Probe(best_t, &c) || !Probe(best_t + spacing, &r)) break;
    const double a = l->sigma[0], b = c->sigma[0], d = r->sigma[0];
    if (a < b || d < b) {  // the minimum is further out: walk
      best_t += (a < d ? -spacing : spacing);
      continue;
    }
    // σ ≈ c·|t − t*|: the zero on the side of the smaller neighbour.
    best_t = a >= d ? best_t + spacing * std::min(1.0, b / (a - b)) : best_t - spacing * std::min(1.0, b / (d - b));
    spacing /= 8;
  }
  bool ok = false;
  *corank = CountVanishing(best_t, delta, &ok);
  if (!ok || *corank == 0) return ok ? std::numeric_limits<double>::infinity() : kNaN;
  double t = best_t;
  for (int it = 0; it < 4; ++it) {
    const double next = FitZero(t, delta, *corank, &ok);
    if (!ok) return kNaN;
    const bool settled = std::abs(next - t) <= 0.25 * delta;
    t = next;
    if (settled) break;
  }
  return t;
}

SingularClassification SingularityClassifier::Classify(const SystemState& base, double tb, double step) {
  SingularClassification out;
  const ConstraintSystem& sys = ws_.system();
  if (6 * sys.num_bodies() > kDenseColumns || ws_.block_solver()) return out;
  samples_.clear();
  Sample first{base, Eigen::VectorXd()};
  SolveOptions tight;
  tight.tolerance = 1e-13;
  if (!SolvePosition(ws_, tight, &first.s, false).success) return out;
  SolveDerivatives(ws_, 3, &first.s);
  first.sigma = SingularValues(first.s);
  samples_.push_back(std::move(first));
  int corank = 0;
  const double t = Locate(base.t, tb, step, &corank);
  if (std::isinf(t)) out.kind = SingularKind::None;
  if (!std::isfinite(t)) return out;
  out.t = t;
  out.corank = corank;
  out.kind = ClassifyAt(t, kFitSpacing * step, corank, &out.branches, &out.branches_exact);
  for (const Jet& j : pose_.driver_values) out.driver_values.push_back(j.c[0]);
  return out;
}

// pose_ at t: the Taylor prediction from a well-determined sample at least δ/2 away
// (the fit's own, at ±δ, ±2δ) — one closer to the position may have converged to
// another assembly or be fixed only to √(residual) along the null space (Newton
// stalls there): the N-four-bar, N = 2, had one 1.4e-11 s from t* with σ_min 0.009.
// Of the eight nearest such samples the prediction whose k vanishing singular values
// are smallest is kept: the nearest alone left them at 1e-13 for N = 3 (360 steps),
// too far from q* for the tangent count, where a sample farther off gave 1e-17.
void SingularityClassifier::PoseAt(double t, double delta, int corank) {
  constexpr int kCandidates = 8;
  std::vector<const Sample*> near;
  for (const Sample& s : samples_)
    if (WellDetermined(s) && std::abs(s.s.t - t) >= 0.5 * delta) near.push_back(&s);
  auto closer = [t](const Sample* a, const Sample* b) { return std::abs(a->s.t - t) < std::abs(b->s.t - t); };
  const size_t keep = std::min<size_t>(kCandidates, near.size());
  std::partial_sort(near.begin(), near.begin() + keep, near.end(), closer);
  near.resize(keep);
  if (near.empty()) near.push_back(&samples_[0]);
  double best = std::numeric_limits<double>::infinity();
  for (const Sample* from : near) {
    SystemState candidate = from->s;
    PredictPose(t - from->s.t, 3, &candidate);
    EvalDriverFunctions(ws_.system().model(), t, &candidate);
    const Eigen::VectorXd sv = SingularValues(candidate);  // ascending
    const double vanishing = sv[std::min<int>(corank, sv.size()) - 1] / sv[sv.size() - 1];
    if (!(vanishing >= best)) best = vanishing, pose_ = candidate;
  }
}

// At the located t: the pose (PoseAt), the null spaces U0, V0 of the scaled Φ_q, the
// fold test U0ᵀν ≠ 0 and the second-order tangent cone U0ᵀγ(w + ρV0α) = 0
// (docs/singularities.md §2–§3).
SingularKind SingularityClassifier::ClassifyAt(double t, double delta, int corank, int* branches, bool* exact) {
  const ConstraintSystem& sys = ws_.system();
  PoseAt(t, delta, corank);
  const std::vector<int>& rows = ws_.active();
  const Eigen::MatrixXd J = ActiveScaledJacobian(sys, pose_, rows);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  const int n = static_cast<int>(sv.size()), r = n - corank;
  // The vanishing ones must be far below the rest there (the rank threshold).
  if (corank < 1 || corank > 8 || !(sv[n - 1 - (corank - 1)] <= 1e-6 * sv[0]) || !(sv[r - 1] > 1e-4 * sv[0]))
    return SingularKind::Undetermined;
  const Eigen::MatrixXd U0 = svd.matrixU().rightCols(corank), V0 = svd.matrixV().rightCols(corank);
  const Eigen::VectorXd weights = RowScales(sys, rows), cols = DimensionlessColumnScales(sys);
  const Eigen::VectorXd nu = ScaledRhs(sys, pose_, rows, weights, nullptr);
  if (!(nu.norm() > 0)) return SingularKind::Undetermined;  // drivers at rest: no direction of motion
  if ((U0.transpose() * nu).norm() > 1e-6 * nu.norm()) return SingularKind::Fold;
  // w: the velocity with no null-space part (pseudo-inverse on the range).
  const Eigen::VectorXd w = svd.matrixV().leftCols(r) *
                            (sv.head(r).cwiseInverse().asDiagonal() * (svd.matrixU().leftCols(r).transpose() * nu));
  const double rho = std::max(w.norm(), 1e-300);
  auto G = [&](const Eigen::VectorXd& alpha) {
    const Eigen::VectorXd rates = cols.cwiseProduct(w + rho * V0 * alpha);
    return Eigen::VectorXd(U0.transpose() * ScaledRhs(sys, pose_, rows, weights, &rates));
  };
  QuadraticSystem q;
  q.c = G(Eigen::VectorXd::Zero(corank));
  q.b.resize(corank, corank);
  q.A.assign(corank, Eigen::MatrixXd::Zero(corank, corank));
  std::vector<Eigen::VectorXd> plus(corank), minus(corank);
  for (int i = 0; i < corank; ++i) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(corank, i);
    plus[i] = G(e), minus[i] = G(-e);
    q.b.col(i) = (plus[i] - minus[i]) / 4;
    for (int j = 0; j < corank; ++j) q.A[j](i, i) = (plus[i][j] + minus[i][j]) / 2 - q.c[j];
  }
  for (int i = 0; i < corank; ++i)
    for (int l = i + 1; l < corank; ++l) {
      const Eigen::VectorXd g = G(Eigen::VectorXd::Unit(corank, i) + Eigen::VectorXd::Unit(corank, l));
      for (int j = 0; j < corank; ++j)
        q.A[j](i, l) = q.A[j](l, i) =
            (g[j] - q.c[j] - 2 * q.b(j, i) - 2 * q.b(j, l) - q.A[j](i, i) - q.A[j](l, l)) / 2;
    }
  // Each equation to unit size (the count does not depend on it).
  for (int j = 0; j < corank; ++j) {
    const double s = std::max({std::abs(q.c[j]), q.b.row(j).cwiseAbs().maxCoeff(), q.A[j].cwiseAbs().maxCoeff()});
    if (!(s > 0)) return SingularKind::Undetermined;
    q.c[j] /= s, q.b.row(j) /= s, q.A[j] /= s;
  }
  const QuadraticRoots roots = RealRootsOfQuadratics(q);
  *branches = static_cast<int>(roots.real.size());
  *exact = roots.complete;
  // Two real tangents are two branches, whatever else the count missed; one is a
  // unique passage only when the count is certain.
  if (roots.real.size() >= 2) return SingularKind::Bifurcation;
  return roots.real.size() == 1 && roots.complete ? SingularKind::UniquePassage : SingularKind::Undetermined;
}

}  // namespace mechkin

