#include "analysis/reduction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "math/numbers.hpp"

namespace mechkin {

const char* ReduceKindName(ReduceKind k) {
  switch (k) {
    case ReduceKind::Min: return "min";
    case ReduceKind::Max: return "max";
    case ReduceKind::Rms: return "rms";
    case ReduceKind::Mean: return "mean";
    case ReduceKind::At: return "at";
    case ReduceKind::Sse: return "sse";
  }
  return "?";
}

std::vector<double> HermiteCoefficients(const double* d0, const double* d1, int m, double h) {
  const int n = 2 * m + 2;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd b(n);
  for (int end = 0; end < 2; ++end)
    for (int k = 0; k <= m; ++k) {
      const int row = end * (m + 1) + k;
      b(row) = (end ? d1 : d0)[k] * std::pow(h, k);  // d^k/ds^k = h^k d^k/dt^k
      for (int j = k; j < n; ++j) {
        double f = 1;
        for (int i = 0; i < k; ++i) f *= j - i;
        a(row, j) = end ? f : (j == k ? f : 0.0);  // s = 1: every power is 1; s = 0: only s^k
      }
    }
  const Eigen::VectorXd c = a.fullPivLu().solve(b);
  return std::vector<double>(c.data(), c.data() + n);
}

double HermiteEval(const std::vector<double>& c, double s, int k) {
  double v = 0;
  for (int j = static_cast<int>(c.size()) - 1; j >= k; --j) {
    double f = 1;
    for (int i = 0; i < k; ++i) f *= j - i;
    v = v * s + f * c[j];
  }
  return v;
}

namespace {

constexpr int kOrders = 4;  // value, velocity, acceleration, jerk: a Hermite of degree 7 at most

// One row as a reduction reads it: t, and per block (0: the column; 1 + p: its
// sensitivity to parameter p) the value and its first three time derivatives.
struct Sample {
  double t = 0;
  std::vector<double> d;
  const double* block(int j) const { return &d[static_cast<size_t>(j) * kOrders]; }
};

// Where the interpolant of [a, b] is evaluated: the interval, the degree used and s.
struct Place {
  const Sample* a = nullptr;
  const Sample* b = nullptr;
  int m = 0;
  double s = 0;
};

// The highest jet order both ends carry finite (0: none beyond the value).
int CommonOrder(const Sample& a, const Sample& b, int m) {
  for (int k = 1; k <= m; ++k)
    if (!std::isfinite(a.d[k]) || !std::isfinite(b.d[k])) return k - 1;
  return m;
}

double Interpolate(const Place& p, int block) {
  if (p.m == 0) return p.a->block(block)[0] + p.s * (p.b->block(block)[0] - p.a->block(block)[0]);
  const double h = p.b->t - p.a->t;
  return HermiteEval(HermiteCoefficients(p.a->block(block), p.b->block(block), p.m, h), p.s);
}

// The extremum of the column's Hermite interpolant on [a, b] (sign +1: the minimum):
// the best of a grid of the interval, refined by Newton on the derivative. The
// interpolant's error is O(h^(2m+2)) (docs/constraints.md §14).
Place Extremum(const Sample& a, const Sample& b, int m, double sign, double* value) {
  Place p{&a, &b, CommonOrder(a, b, m), 0};
  if (p.m == 0 || b.t <= a.t) {
    const bool at_b = sign * b.d[0] < sign * a.d[0];
    p.s = at_b ? 1 : 0;
    *value = at_b ? b.d[0] : a.d[0];
    return p;
  }
  const std::vector<double> c = HermiteCoefficients(a.block(0), b.block(0), p.m, b.t - a.t);
  constexpr int kGrid = 32;
  double best = HermiteEval(c, 0);
  for (int i = 1; i <= kGrid; ++i) {
    const double s = static_cast<double>(i) / kGrid, v = HermiteEval(c, s);
    if (sign * v < sign * best) best = v, p.s = s;
  }
  double s = p.s;
  for (int it = 0; it < 20; ++it) {
    const double d1 = HermiteEval(c, s, 1), d2 = HermiteEval(c, s, 2);
    if (!(sign * d2 > 0)) break;
    const double next = std::clamp(s - d1 / d2, 0.0, 1.0);
    if (std::abs(next - s) < 1e-15) break;
    s = next;
  }
  if (sign * HermiteEval(c, s) <= sign * best) p.s = s, best = HermiteEval(c, s);
  *value = best;
  return p;
}

}  // namespace

struct ReductionAccumulator::State {
  Reduction r;
  std::vector<int> cols;  // per block and order: the table column, or −1
  int m = 0;              // jet orders the table has for the column (0..3)
  int params = 0;
  std::string unit, problem;
  std::vector<std::string> wrt;
  long long rows = 0;
  Sample last, prev, best, next;
  bool has_best = false, has_prev = false, has_next = false;
  long long best_row = -1;
  double t0 = 0, sum = 0, sum2 = 0;
  std::vector<double> g, g2;  // the trapezoid sums of s_p and v s_p
  bool at_done = false;
  Place at_place;
  Sample at_a, at_b;

  Sample cur;  // the row being read, reused: no allocation per row once sized

  // Sse: this state is column `part` of `parts`; per target time its value and
  // sensitivities (file units: × factor) once the rows around it are read.
  int part = 0, parts = 1;
  double factor = 1;
  std::vector<char> found;
  std::vector<double> target_value;
  std::vector<std::vector<double>> target_gradient;
  // Rms with sensitivities: per row v, its trapezoid weight Σ Δt/2 and s_p (the
  // least-squares residuals √(w/T) v of rms², docs/constraints.md §15).
  std::vector<double> row_value, row_weight, row_sens;

  // Fills `cur` from a table row (column t_col is t).
  void Read(const double* row, int t_col) {
    cur.t = row[t_col];
    cur.d.resize(cols.size());
    for (size_t i = 0; i < cols.size(); ++i) cur.d[i] = cols[i] >= 0 ? row[cols[i]] : kNaN;
  }
  void MinMax(const Sample& cur);
  void Trapezoid(const Sample& cur);
  void At(const Sample& cur);
  void Targets(const Sample& cur);
  ReductionResult Result() const;
  void RmsResiduals(double span, ReductionResult* out) const;
  void Extreme(ReductionResult* out) const;
};

namespace {

// The column of output `c` of time-derivative `order` in the layout, or −1: a point's
// coordinate by its component, a single-valued output's first series.
int OutputColumnOf(const MotionLayout& layout, const OutputColumn& c, bool point, int order) {
  for (const auto& g : layout.segments()) {
    if (g.kind != MotionLayout::Segment::Kind::Output || g.index != c.output) continue;
    const ColumnDescriptor& head = layout.columns()[g.first];
    for (int i = g.first; i < g.first + g.count; ++i) {
      const ColumnDescriptor& d = layout.columns()[i];
      const bool same = point ? d.component == c.component : d.component == head.component;
      if (d.wrt < 0 && d.order == order && d.quantity == head.quantity && same) return i;
    }
  }
  return -1;
}

}  // namespace

int ValueColumnOf(const Model& model, const MotionLayout& layout, const OutputColumn& column) {
  return OutputColumnOf(layout, column, model.outputs[column.output].kind == OutputKind::Point, 0);
}

namespace {

// An "sse" reduction as one reduction per column (each reads its column at the
// target times; Finish adds them up), the others as they are.
std::vector<std::pair<Reduction, int>> Parts(std::vector<Reduction> which) {
  std::vector<std::pair<Reduction, int>> out;
  for (Reduction& r : which) {
    if (r.kind != ReduceKind::Sse) {
      out.emplace_back(std::move(r), 0);
      continue;
    }
    for (size_t k = 0; k < r.columns.size(); ++k) {
      Reduction part = r;
      part.column = r.columns[k];
      out.emplace_back(std::move(part), static_cast<int>(k));
    }
  }
  return out;
}

}  // namespace

ReductionAccumulator::ReductionAccumulator(const Model& model, const MotionLayout& layout, std::vector<Reduction> which) {
  const std::vector<std::string>& params = layout.options().sensitivity;
  for (auto& [r, part] : Parts(std::move(which))) {
    State s;
    s.r = std::move(r);
    s.part = part;
    s.parts = s.r.kind == ReduceKind::Sse ? static_cast<int>(s.r.columns.size()) : 1;
    s.params = static_cast<int>(params.size());
    s.wrt = params;
    s.cols.assign(static_cast<size_t>(kOrders) * (1 + s.params), -1);
    const bool point = model.outputs[s.r.column.output].kind == OutputKind::Point;
    for (int k = 0; k < kOrders; ++k) {
      const int col = OutputColumnOf(layout, s.r.column, point, k);
      s.cols[k] = col;
      for (int p = 0; p < s.params && col >= 0; ++p) s.cols[(1 + p) * kOrders + k] = layout.SensitivityOf(col, p);
    }
    while (s.m + 1 < kOrders && s.cols[s.m + 1] >= 0) ++s.m;
    if (s.cols[0] < 0)
      s.problem = "output '" + model.outputs[s.r.column.output].name +
                  "' is not in the table (select it with --outputs, or leave --outputs out)";
    else
      s.unit = layout.columns()[s.cols[0]].unit, s.factor = FileUnitFactor(model, layout, s.cols[0]);
    s.g.assign(s.params, 0);
    s.g2.assign(s.params, 0);
    s.found.assign(s.r.target_t.size(), 0);
    s.target_value.assign(s.r.target_t.size(), kNaN);
    s.target_gradient.assign(s.r.target_t.size(), std::vector<double>(s.params, kNaN));
    states_.push_back(std::move(s));
  }
}

ReductionAccumulator::~ReductionAccumulator() = default;

void ReductionAccumulator::Row(const double* row) {
  for (State& s : states_) {
    if (!s.problem.empty()) continue;
    s.Read(row, 0);  // column 0 is t
    const Sample& cur = s.cur;
    if (s.r.kind == ReduceKind::Min || s.r.kind == ReduceKind::Max) s.MinMax(cur);
    else if (s.r.kind == ReduceKind::At) s.At(cur);
    else if (s.r.kind == ReduceKind::Sse) s.Targets(cur);
    else s.Trapezoid(cur);
    if (s.rows == 0) s.t0 = cur.t;
    s.last = cur;
    ++s.rows;
  }
}

// The best row so far with its neighbours: the extremum lies between them.
void ReductionAccumulator::State::MinMax(const Sample& cur) {
  const double sign = r.kind == ReduceKind::Min ? 1 : -1;
  if (has_best && best_row == rows - 1) next = cur, has_next = true;
  if (!std::isfinite(cur.d[0])) return;
  if (!has_best || sign * cur.d[0] < sign * best.d[0]) {
    has_prev = rows > 0 && std::isfinite(last.d[0]);
    if (has_prev) prev = last;
    best = cur;
    has_best = true;
    has_next = false;
    best_row = rows;
  }
}

// ∫ v dt and ∫ v² dt by the trapezoid rule over the rows, and their sensitivities
// (the exact derivatives of the sums: Σ (s_i + s_i+1)/2 Δt, Σ (v_i s_i + v_i+1 s_i+1) Δt/2 · 2).
void ReductionAccumulator::State::Trapezoid(const Sample& cur) {
  if (r.kind == ReduceKind::Rms && params > 0) {
    row_value.push_back(cur.d[0]);
    row_weight.push_back(0);
    for (int p = 0; p < params; ++p) row_sens.push_back(cur.block(1 + p)[0]);
  }
  if (rows == 0) return;
  const double dt = cur.t - last.t;
  if (!row_weight.empty()) row_weight[row_weight.size() - 2] += dt / 2, row_weight.back() += dt / 2;
  const double a = last.d[0], b = cur.d[0];
  sum += 0.5 * (a + b) * dt;
  sum2 += 0.5 * (a * a + b * b) * dt;
  for (int p = 0; p < params; ++p) {
    const double sa = last.block(1 + p)[0], sb = cur.block(1 + p)[0];
    g[p] += 0.5 * (sa + sb) * dt;
    g2[p] += (a * sa + b * sb) * dt;  // d/dp of (a² + b²)/2 Δt
  }
}

// The first pair of rows around t: the Hermite interpolant there.
void ReductionAccumulator::State::At(const Sample& cur) {
  if (at_done) return;
  if (cur.t == r.t) {
    at_a = at_b = cur;
    at_place = Place{&at_a, &at_b, 0, 0};
    at_done = true;
  } else if (rows > 0 && last.t < r.t && r.t < cur.t) {
    at_a = last;
    at_b = cur;
    at_place = Place{&at_a, &at_b, CommonOrder(last, cur, m), (r.t - last.t) / (cur.t - last.t)};
    at_done = true;
  }
}

// Sse: each target time between the last row and this one (or on this row): the
// column's value and sensitivities there, interpolated as "at" does, in file units.
void ReductionAccumulator::State::Targets(const Sample& cur) {
  for (size_t i = 0; i < found.size(); ++i) {
    const double t = r.target_t[i];
    if (found[i] || !(cur.t == t || (rows > 0 && last.t < t && t < cur.t))) continue;
    const Place p = cur.t == t ? Place{&cur, &cur, 0, 0}
                               : Place{&last, &cur, CommonOrder(last, cur, m), (t - last.t) / (cur.t - last.t)};
    target_value[i] = factor * Interpolate(p, 0);
    for (int k = 0; k < params; ++k) target_gradient[i][k] = factor * Interpolate(p, 1 + k);
    found[i] = 1;
  }
}

// Min/Max: the extremum of the interpolants either side of the best row; the
// gradient by the envelope theorem, d(min)/dp = ∂v/∂p at the located t (the
// sensitivities' interpolant there, built from the same rows).
void ReductionAccumulator::State::Extreme(ReductionResult* out) const {
  const double sign = r.kind == ReduceKind::Min ? 1 : -1;
  Place p{&best, &best, 0, 0};
  double value = best.d[0];
  auto consider = [&](const Sample& a, const Sample& b) {
    double v = 0;
    const Place q = Extremum(a, b, m, sign, &v);
    if (sign * v < sign * value || (q.m > 0 && p.m == 0 && sign * v <= sign * value)) value = v, p = q;
  };
  if (has_prev) consider(prev, best);
  if (has_next) consider(best, next);
  out->value = value;
  out->t = p.a->t + p.s * (p.b->t - p.a->t);
  out->located = p.m > 0;
  for (int k = 0; k < params; ++k) out->gradient[k] = Interpolate(p, 1 + k);
}

// rms² = Σ (w_i/T) v_i² (the trapezoid sum): residuals √(w_i/T) v_i, gradients √(w_i/T) s_i.
void ReductionAccumulator::State::RmsResiduals(double span, ReductionResult* out) const {
  if (!(span > 0)) return;
  for (size_t i = 0; i < row_value.size(); ++i) {
    const double w = std::sqrt(row_weight[i] / span);
    out->residuals.push_back(w * row_value[i]);
    std::vector<double> g(params);
    for (int k = 0; k < params; ++k) g[k] = w * row_sens[i * params + k];
    out->residual_gradient.push_back(std::move(g));
  }
}

ReductionResult ReductionAccumulator::State::Result() const {
  ReductionResult out;
  out.name = r.name;
  out.of = r.of;
  out.kind = r.kind;
  out.unit = unit;
  out.rows = static_cast<int>(rows);
  out.problem = problem;
  out.in_table = cols[0] >= 0;
  out.wrt = wrt;
  out.gradient.assign(params, kNaN);
  if (!problem.empty()) return out;
  if (rows == 0) return out.problem = "the run made no row", out;
  const double span = last.t - t0;
  switch (r.kind) {
    case ReduceKind::Min:
    case ReduceKind::Max:
      if (!has_best) return out.problem = "the column has no finite value", out;
      Extreme(&out);
      break;
    case ReduceKind::Mean:
      out.value = span > 0 ? sum / span : last.d[0];
      for (int k = 0; k < params; ++k) out.gradient[k] = span > 0 ? g[k] / span : last.block(1 + k)[0];
      break;
    case ReduceKind::Rms:
      out.value = span > 0 ? std::sqrt(sum2 / span) : std::abs(last.d[0]);
      for (int k = 0; k < params; ++k)
        out.gradient[k] = span > 0 ? g2[k] / (2 * span * out.value) : std::copysign(1.0, last.d[0]) * last.block(1 + k)[0];
      RmsResiduals(span, &out);
      break;
    case ReduceKind::At:
      out.t = r.t;
      if (!at_done) return out.problem = "t = " + std::to_string(r.t) + " s is not within the rows of the run", out;
      out.value = Interpolate(at_place, 0);
      for (int k = 0; k < params; ++k) out.gradient[k] = Interpolate(at_place, 1 + k);
      break;
    case ReduceKind::Sse:
      break;  // AddTargets
  }
  return out;
}

namespace {

// One column's part of an "sse" into its result: the residuals at the target times
// (column − target, file units), the sum of their squares and its gradient (chain
// rule: 2 Σ r ∂r/∂p, ∂r/∂p the column's sensitivity there; docs/constraints.md §15).
void AddTargets(const ReductionResult& part_result, const Reduction& r, int part, int parts,
                const std::vector<double>& value, const std::vector<std::vector<double>>& grad, ReductionResult* out) {
  const size_t n = r.target_t.size(), p = out->wrt.size();
  if (part == 0) {
    out->of.clear();
    for (const std::string& c : r.column_names) out->of += (out->of.empty() ? "" : ",") + c;
    out->unit = "";
    out->value = 0;
    out->gradient.assign(p, 0);
    out->residuals.assign(n * parts, kNaN);
    out->residual_gradient.assign(n * parts, std::vector<double>(p, kNaN));
  }
  if (!part_result.problem.empty() && out->problem.empty()) out->problem = part_result.problem;
  for (size_t i = 0; i < n && out->problem.empty(); ++i) {
    if (!std::isfinite(value[i])) {
      out->problem = "t = " + std::to_string(r.target_t[i]) + " s (target " + std::to_string(i) + " of " +
                     r.column_names[part] + ") is not within the rows of the run";
      break;
    }
    const double res = value[i] - r.target_values[i][part];
    out->residuals[i * parts + part] = res;
    out->residual_gradient[i * parts + part] = grad[i];
    out->value += res * res;
    for (size_t k = 0; k < p; ++k) out->gradient[k] += 2 * res * grad[i][k];
  }
  if (!out->problem.empty()) {
    out->value = kNaN;
    out->gradient.assign(p, kNaN);
  }
}

}  // namespace

std::vector<ReductionResult> ReductionAccumulator::Finish() const {
  std::vector<ReductionResult> out;
  for (const State& s : states_) {
    if (s.r.kind != ReduceKind::Sse) {
      out.push_back(s.Result());
      continue;
    }
    ReductionResult part = s.Result();
    if (s.part == 0) out.push_back(part);
    AddTargets(part, s.r, s.part, s.parts, s.target_value, s.target_gradient, &out.back());
  }
  return out;
}

std::vector<ReductionResult> ComputeReductions(const Model& model, const Motion& motion) {
  if (model.reductions.empty()) return {};
  ReductionAccumulator acc(model, motion.layout());
  for (int r = 0; r < motion.rows(); ++r) acc.Row(&motion.values()[static_cast<size_t>(r) * motion.cols()]);
  return acc.Finish();
}

double FileUnitFactor(const Model& model, const MotionLayout& layout, int column) {
  switch (layout.columns()[column].quantity) {
    case Quantity::PointPosition:
    case Quantity::Distance:
    case Quantity::JointSlide:
    case Quantity::Clearance:
      return 1 / (layout.length_factor() * model.units.length_to_si);
    case Quantity::JointAngle:
    case Quantity::Angle:
      return 1 / (layout.angle_factor() * model.units.angle_to_si);
    default:
      return 1;
  }
}

}  // namespace mechkin
