#include "analysis/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <random>
#include <stdexcept>

#include "analysis/motion.hpp"
#include "analysis/parallel.hpp"

namespace mechkin {

bool ParseGridAxis(const std::string& text, GridAxis* axis, std::string* error) {
  const auto eq = text.find('=');
  const auto c1 = text.find(':', eq == std::string::npos ? 0 : eq);
  const auto c2 = c1 == std::string::npos ? c1 : text.find(':', c1 + 1);
  auto number = [](const std::string& s, double* v) {
    char* end = nullptr;
    *v = std::strtod(s.c_str(), &end);
    return !s.empty() && end == s.c_str() + s.size() && std::isfinite(*v);
  };
  double count = 0;
  if (eq == std::string::npos || eq == 0 || c2 == std::string::npos ||
      !number(text.substr(eq + 1, c1 - eq - 1), &axis->from) || !number(text.substr(c1 + 1, c2 - c1 - 1), &axis->to) ||
      !number(text.substr(c2 + 1), &count) || count != std::floor(count) || count < 1 || count > 1e7) {
    *error = "--grid '" + text + "': expected NAME=FROM:TO:COUNT, e.g. --grid crank=90:110:21";
    return false;
  }
  axis->parameter = text.substr(0, eq);
  axis->count = static_cast<int>(count);
  return true;
}

std::vector<ParameterOverrides> GridVariants(const std::vector<GridAxis>& axes) {
  std::vector<ParameterOverrides> out(1);
  for (const GridAxis& a : axes) {
    std::vector<ParameterOverrides> next;
    next.reserve(out.size() * a.count);
    for (const auto& base : out)
      for (int k = 0; k < a.count; ++k) {
        ParameterOverrides v = base;
        v[a.parameter] = a.count == 1 ? a.from : a.from + (a.to - a.from) * k / (a.count - 1);
        next.push_back(std::move(v));
      }
    out = std::move(next);
  }
  return out;
}

std::vector<ParameterOverrides> SampleVariants(const Model& model, int count, unsigned long seed, std::string* error) {
  std::vector<const Parameter*> ranged;
  for (const auto& p : model.parameters)
    if (p.min && p.max) ranged.push_back(&p);
  if (ranged.empty()) {
    *error = "no parameter declares a range: write e.g. \"crank\": {\"value\": 40, \"min\": 30, \"max\": 50}";
    return {};
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ParameterOverrides> out(count);
  for (auto& v : out)
    for (const Parameter* p : ranged) v[p->name] = *p->min + (*p->max - *p->min) * unit(rng);
  return out;
}

namespace {

// The grid variant number `index` (row-major, the last axis fastest), as GridVariants makes it.
ParameterOverrides GridVariant(const std::vector<GridAxis>& axes, long long index) {
  std::vector<int> digit(axes.size());
  for (size_t a = axes.size(); a-- > 0;) {
    digit[a] = static_cast<int>(index % axes[a].count);
    index /= axes[a].count;
  }
  ParameterOverrides v;
  for (size_t a = 0; a < axes.size(); ++a) {
    const GridAxis& g = axes[a];
    const int k = digit[a];
    v[g.parameter] = g.count == 1 ? g.from : g.from + (g.to - g.from) * k / (g.count - 1);
  }
  return v;
}

std::vector<std::string> KeysOf(const ParameterOverrides& v) {
  std::vector<std::string> keys;
  for (const auto& kv : v) keys.push_back(kv.first);
  return keys;
}

}  // namespace

// The seeded samples of one shard, drawn in the order SampleVariants draws them (one
// std::mt19937_64 stream through every variant of the sweep, the parameters in the
// model's order) and kept only for the last kWindow of the shard's variants: the
// threads ask in nearly ascending order, so a variant asked for is either ahead
// (drawn on) or just behind (in the window). An older one restarts the stream.
class SampleStream {
 public:
  struct Range {
    std::string name;
    double min, max;
  };
  SampleStream(std::vector<Range> ranged, std::vector<std::string> keys, unsigned long seed, int first,
               int stride)
      : ranged_(std::move(ranged)), keys_(std::move(keys)), seed_(seed), first_(first), stride_(stride),
        window_(kWindow * keys_.size()) {
    Restart();
  }
  ParameterOverrides Variant(size_t k) {
    std::lock_guard<std::mutex> hold(lock_);
    if (k + kWindow < next_) Restart();
    while (next_ <= k) DrawShardVariant();
    ParameterOverrides v;
    const double* values = &window_[(k % kWindow) * keys_.size()];
    for (size_t p = 0; p < keys_.size(); ++p) v.emplace_hint(v.end(), keys_[p], values[p]);
    return v;
  }

 private:
  static constexpr size_t kWindow = 1024;
  void Restart() {
    rng_.seed(seed_);
    drawn_ = 0;
    next_ = 0;
  }
  // Draws through the other shards' variants to this shard's next one, into the window.
  void DrawShardVariant() {
    const long long index = first_ + static_cast<long long>(next_) * stride_;
    for (; drawn_ < index; ++drawn_)
      for (size_t p = 0; p < ranged_.size(); ++p) unit_(rng_);
    ParameterOverrides v;  // keyed as SampleVariants keys it, so the values sort alike
    for (const Range& p : ranged_) v[p.name] = p.min + (p.max - p.min) * unit_(rng_);
    ++drawn_;
    double* values = &window_[(next_ % kWindow) * keys_.size()];
    for (const auto& kv : v) *values++ = kv.second;
    ++next_;
  }
  const std::vector<Range> ranged_;  // the model's parameters with min and max, in its order
  const std::vector<std::string> keys_;
  const unsigned long seed_;
  const int first_, stride_;
  std::vector<double> window_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  long long drawn_ = 0;  // whole-sweep variants drawn
  size_t next_ = 0;      // the shard's next variant to draw
  std::mutex lock_;
};

ParameterOverrides ShardVariants::Variant(size_t k) const {
  if (samples_) return samples_->Variant(k);
  if (!grid_.empty()) return GridVariant(grid_, Index(k));
  ParameterOverrides v;
  for (size_t p = 0; p < parameters.size(); ++p)
    v.emplace_hint(v.end(), parameters[p], listed_[k * parameters.size() + p]);
  return v;
}

void ShardVariants::Add(int index, const ParameterOverrides& variant) {
  if (count_ == 0) first_ = index;
  if (count_ == 1) stride_ = index - first_;
  if (stride_ < 1 || index != Index(count_))
    throw std::invalid_argument("ShardVariants::Add: variant " + std::to_string(index) +
                                " does not continue the shard's even steps from " + std::to_string(first_));
  for (const auto& kv : variant) listed_.push_back(kv.second);
  ++count_;
}

namespace {

// The count of variants with index ≡ shard−1 (mod shards) among `total`.
size_t ShardCount(long long total, int shard, int shards) {
  return total < shard ? 0 : static_cast<size_t>((total - shard) / shards + 1);
}

}  // namespace

ShardVariants GridShard(const std::vector<GridAxis>& axes, int shard, int shards) {
  ShardVariants out;
  long long total = 1;
  for (const GridAxis& a : axes) total *= a.count;  // the caller bounds it (1e8)
  out.total = static_cast<int>(total);
  out.parameters = KeysOf(GridVariant(axes, 0));
  out.grid_ = axes;
  out.first_ = shard - 1;
  out.stride_ = shards;
  out.count_ = ShardCount(total, shard, shards);
  return out;
}

ShardVariants SampleShard(const Model& model, int count, unsigned long seed, int shard, int shards, std::string* error) {
  ShardVariants out;
  std::vector<const Parameter*> ranged;
  for (const auto& p : model.parameters)
    if (p.min && p.max) ranged.push_back(&p);
  if (ranged.empty()) {
    *error = "no parameter declares a range: write e.g. \"crank\": {\"value\": 40, \"min\": 30, \"max\": 50}";
    return out;
  }
  out.total = count;
  for (const Parameter* p : ranged) out.parameters.push_back(p->name);
  std::sort(out.parameters.begin(), out.parameters.end());  // the overrides' key order
  out.first_ = shard - 1;
  out.stride_ = shards;
  out.count_ = ShardCount(count, shard, shards);
  std::vector<SampleStream::Range> ranges;
  for (const Parameter* p : ranged) ranges.push_back({p->name, *p->min, *p->max});
  out.samples_ = std::make_shared<SampleStream>(std::move(ranges), out.parameters, seed, out.first_, out.stride_);
  return out;
}

RunRequest VariantRequest(const Model& model, const RunRequest& request) {
  RunRequest r = request;
  r.outputs.reset();
  r.bodies.reset();
  if (!model.outputs.empty()) r.bodies = std::vector<std::string>{};
  r.forces = ForcesChoice::Off;
  r.sensitivity.clear();
  r.keep_step_diagnostics = false;
  return r;
}

namespace {

TableOptions SweepTable(const Model& model, int order) {
  RunRequest r;
  r.order = order;
  return PlanRun(model, VariantRequest(model, r)).table;
}

std::vector<int> SummaryColumns(const MotionLayout& layout) {
  std::vector<int> cols;
  for (int c = 0; c < layout.size(); ++c) {
    const ColumnDescriptor& d = layout.columns()[c];
    if (d.quantity != Quantity::Time && !d.IsDiagnostic()) cols.push_back(c);
  }
  return cols;
}

// Min/max of the summary columns and the worst condition over a run's rows.
void Summarize(const Motion& m, VariantSummary* v) {
  const std::vector<int> cols = SummaryColumns(m.layout());
  const int condition = m.layout().Find("condition");
  v->min.assign(cols.size(), std::numeric_limits<double>::quiet_NaN());
  v->max = v->min;
  for (int r = 0; r < m.rows(); ++r) {
    for (size_t k = 0; k < cols.size(); ++k) {
      const double x = m.at(r, cols[k]);
      if (r == 0 || x < v->min[k]) v->min[k] = x;
      if (r == 0 || x > v->max[k]) v->max[k] = x;
    }
    if (m.at(r, condition) > v->max_condition) v->max_condition = m.at(r, condition), v->t_max_condition = m.at(r, 0);
  }
}

std::string StatusOf(StopKind stop) {
  switch (stop) {
    case StopKind::None: return "complete";
    case StopKind::Refused: return "refused";
    case StopKind::AssemblyFailed: return "assembly";
    case StopKind::SingularPosition: return "singular";
    case StopKind::SolveFailed: return "failed";
    case StopKind::Interrupted: return "interrupted";
    case StopKind::JointLimit: return "joint limit";
    case StopKind::Contact: return "contact";
  }
  return "failed";
}

}  // namespace

std::string VariantStatus(const Motion& m) { return m.report.limit ? "limit" : StatusOf(m.stop.kind); }

std::vector<ColumnDescriptor> SweepColumnDescriptors(const Model& model, int order) {
  const MotionLayout layout(model, SweepTable(model, order));
  std::vector<ColumnDescriptor> columns;
  for (int c : SummaryColumns(layout)) columns.push_back(layout.columns()[c]);
  return columns;
}

std::vector<std::string> SweepColumns(const Model& model, int order) {
  std::vector<std::string> names;
  for (const ColumnDescriptor& c : SweepColumnDescriptors(model, order)) names.push_back(c.Header());
  return names;
}

VariantSummary RunVariant(const Model& model, const ParameterOverrides& values, const SweepOptions& options) {
  VariantSummary v;
  for (const auto& kv : values) v.values.push_back(kv.second);
  LoadResult compiled = WithParameters(model, values);
  if (!compiled.ok()) {
    v.status = "invalid";
    v.message = compiled.errors.empty() ? "the file does not compile" : compiled.errors.front().ToString();
    v.min.assign(SweepColumns(model, options.request.order).size(), std::numeric_limits<double>::quiet_NaN());
    v.max = v.min;
    return v;
  }
  const Motion m = RunMotion(*compiled.model, VariantRequest(*compiled.model, options.request));
  v.status = VariantStatus(m);
  v.message = m.complete ? "" : m.stop.Summary();
  v.rows = m.rows();
  if (!m.complete && m.rows() > 0) v.t_stop = m.at(m.rows() - 1, 0);
  Summarize(m, &v);  // the variant's layout has the base model's columns: same file
  return v;
}

SweepResult RunSweep(const Model& model, const std::vector<ParameterOverrides>& variants, const SweepOptions& options) {
  ShardVariants shard;
  shard.total = static_cast<int>(variants.size());
  if (!variants.empty()) shard.parameters = KeysOf(variants.front());
  for (int i = options.shard - 1; i < shard.total; i += options.shards) shard.Add(i, variants[i]);
  return RunSweepShard(model, shard, options);
}

SweepResult RunSweepShard(const Model& model, const ShardVariants& shard, const SweepOptions& options) {
  SweepResult result;
  result.total = shard.total;
  result.shard = options.shard;
  result.shards = options.shards;
  result.parameters = shard.parameters;
  std::string why;
  if (!options.request.IsValid(&why)) throw std::invalid_argument(why);
  result.columns = SweepColumns(model, options.request.order);
  result.variants.resize(shard.size());
  std::vector<char> finished(shard.size(), 0);
  std::mutex progress_lock;
  int done = 0;
  ParallelFor(static_cast<int>(shard.size()), options.threads, [&](int k, int) {
    VariantSummary v = RunVariant(model, shard.Variant(k), options);
    if (v.status == "interrupted") return;  // a summary of part of the motion: not reported
    result.variants[k] = std::move(v);
    result.variants[k].index = shard.Index(k);
    finished[k] = 1;
    if (!options.progress) return;
    std::lock_guard<std::mutex> hold(progress_lock);
    options.progress(++done);
  }, options.request.interrupted);
  // Interrupted: the report keeps the variants that finished, in index order.
  size_t kept = 0;
  for (size_t k = 0; k < finished.size(); ++k)
    if (finished[k]) {
      if (kept != k) result.variants[kept] = std::move(result.variants[k]);  // never onto itself
      ++kept;
    }
  result.interrupted = kept < finished.size();
  result.variants.resize(kept);
  return result;
}

}  // namespace mechkin
