#include "analysis/sweep_curves.hpp"

#include <algorithm>
#include <limits>
#include <mutex>

#include "analysis/parallel.hpp"

namespace mechkin {

const std::vector<std::string>& SweepStatusNames() {
  // Append only: a dataset's codes stay readable by later versions.
  static const std::vector<std::string> names = {"complete", "invalid", "assembly", "refused",     "limit",
                                                 "singular", "failed",  "contact",  "joint limit", "interrupted"};
  return names;
}

int SweepStatusCode(const std::string& status) {
  const auto& names = SweepStatusNames();
  const auto it = std::find(names.begin(), names.end(), status);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

bool SelectCurves(const Model& model, const RunRequest& request, const std::vector<std::string>& names,
                  CurveSelection* selection, std::string* error) {
  if (!request.IsValid(error)) return false;
  if (!model.analysis) {
    *error = "the file has no \"analysis\" block (start, end, steps): a dataset keeps every row of a run";
    return false;
  }
  if (names.empty()) {
    *error = "--curves: name at least one column, e.g. --curves coupler_point.x,coupler_point.y";
    return false;
  }
  // What `mechkin run --order K --tol T` runs: every body and output, forces as the file
  // asks; the rows' diagnostics are not kept.
  selection->request = RunRequest{};
  selection->request.order = request.order;
  selection->request.tolerance = request.tolerance;
  selection->request.solver = request.solver;
  selection->request.interrupted = request.interrupted;
  selection->request.keep_step_diagnostics = false;
  const MotionLayout layout(model, PlanRun(model, selection->request).table);
  for (const std::string& name : names) {
    const int c = layout.Find(name);
    if (c < 0) {
      std::string there;
      for (const ColumnDescriptor& d : layout.columns())
        if (d.quantity != Quantity::Time && !d.IsDiagnostic()) there += (there.empty() ? "" : ", ") + d.name;
      *error = "--curves: no column '" + name + "' in the runs of this file at --order " +
               std::to_string(request.order) + " (there are: " + there + ")";
      return false;
    }
    selection->columns.push_back(c);
    selection->names.push_back(layout.columns()[c].name);
    selection->units.push_back(layout.columns()[c].unit);
  }
  selection->rows = model.analysis->steps + 1;
  return true;
}

VariantCurves RunVariantCurves(const Model& model, const ParameterOverrides& values, const CurveSelection& selection) {
  VariantCurves v;
  for (const auto& kv : values) v.values.push_back(kv.second);
  LoadResult compiled = WithParameters(model, values);
  if (!compiled.ok()) {
    v.status = "invalid";
    v.message = compiled.errors.empty() ? "the file does not compile" : compiled.errors.front().ToString();
    return v;
  }
  const Motion m = RunMotion(*compiled.model, selection.request);
  v.status = VariantStatus(m);
  v.message = m.complete ? "" : m.stop.Summary();
  v.rows = std::min(m.rows(), selection.rows);
  if (!m.complete && m.rows() > 0) v.t_stop = m.at(m.rows() - 1, 0);
  const size_t cols = selection.columns.size();
  v.t.resize(v.rows);
  v.curves.resize(static_cast<size_t>(v.rows) * cols);
  for (int r = 0; r < v.rows; ++r) {
    v.t[r] = m.at(r, 0);
    for (size_t k = 0; k < cols; ++k) v.curves[r * cols + k] = m.at(r, selection.columns[k]);
  }
  return v;
}

bool RunCurveSweep(const Model& model, const ShardVariants& shard, const CurveSelection& selection, int threads,
                   const std::function<bool(VariantCurves&&)>& sink, const std::function<void(int done)>& progress) {
  std::mutex lock;
  bool sink_failed = false;
  int done = 0;
  const InterruptPoll& interrupted = selection.request.interrupted;
  auto stop = [&] { return sink_failed || (interrupted && interrupted()); };
  ParallelFor(static_cast<int>(shard.size()), threads, [&](int k, int) {
    VariantCurves v = RunVariantCurves(model, shard.Variant(k), selection);
    if (v.status == "interrupted") return;  // part of the motion: not kept
    v.index = shard.Index(k);
    v.position = k;
    std::lock_guard<std::mutex> hold(lock);
    if (sink_failed) return;
    if (!sink(std::move(v))) sink_failed = true;
    ++done;
    if (progress) progress(done);
  }, stop);
  return !sink_failed && done == static_cast<int>(shard.size());
}

}  // namespace mechkin
