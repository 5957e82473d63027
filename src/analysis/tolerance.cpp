#include "analysis/tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "analysis/load.hpp"

namespace mechkin {

namespace {

// A run of the analysis: the outputs' columns (no outputs: the bodies'), no forces,
// the sensitivities given.
RunRequest OutputRequest(const Model& model, const RunRequest& request, std::vector<std::string> sensitivity) {
  RunRequest r = request;
  r.outputs.reset();
  r.bodies.reset();
  if (!model.outputs.empty()) r.bodies = std::vector<std::string>{};
  r.forces = ForcesChoice::Off;
  r.sensitivity = std::move(sensitivity);
  return r;
}

// The columns analysed: every body/output column of the nominal run.
std::vector<int> ValueColumns(const Motion& m) {
  std::vector<int> cols;
  for (int c = 0; c < m.cols(); ++c) {
    const ColumnDescriptor& d = m.columns()[c];
    if (d.wrt < 0 && d.quantity != Quantity::Time && !d.IsDiagnostic()) cols.push_back(c);
  }
  return cols;
}

// Worst case, RSS and the ranking of one column from its sensitivity columns.
ToleranceColumn LinearStack(const Motion& m, int col, const ToleranceReport& rep) {
  ToleranceColumn tc;
  tc.name = m.columns()[col].name;
  tc.unit = m.columns()[col].unit;
  if (m.columns()[col].quantity == Quantity::VelocityRatio && m.layout().options().order == 0) {
    tc.not_computed = "not computed at order 0: a velocity ratio needs the velocities (order 1 or more)";
    return tc;
  }
  std::vector<int> sens;
  for (const auto& p : rep.parameters) sens.push_back(m.layout().SensitivityOf(tc.name, p));
  int worst_row = 0;
  for (int r = 0; r < m.rows(); ++r) {
    double wc = 0, ss = 0;
    for (size_t p = 0; p < sens.size(); ++p) {
      const double c = std::abs(m.at(r, sens[p])) * rep.tolerances[p];
      wc += c;
      ss += c * c;
    }
    tc.worst_case.push_back(wc);
    tc.rss.push_back(std::sqrt(ss));
    if (wc > tc.max_worst_case) tc.max_worst_case = wc, tc.t_worst_case = m.at(r, 0), worst_row = r;
    if (tc.rss.back() > tc.max_rss) tc.max_rss = tc.rss.back(), tc.t_rss = m.at(r, 0);
  }
  for (size_t p = 0; p < sens.size(); ++p)
    tc.contributions.emplace_back(rep.parameters[p], std::abs(m.at(worst_row, sens[p])) * rep.tolerances[p]);
  std::stable_sort(tc.contributions.begin(), tc.contributions.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return tc;
}

// Monte-Carlo samples are summed in this many fixed chunks (at most): enough to keep
// every core busy, few enough that the chunks' sums stay small next to the samples.
constexpr int kMonteCarloChunks = 64;

// Per chunk: the largest |deviation| and the running sums per (column, row).
struct MonteCarloSums {
  std::vector<double> max_abs, sum, sum_sq;
  int runs = 0, failed = 0;
};

void RunSample(const Model& model, const ParameterOverrides& set, const Motion& nominal, const std::vector<int>& cols,
               const ToleranceOptions& options, MonteCarloSums* acc) {
  LoadResult variant = WithParameters(model, set);
  if (!variant.ok()) {
    ++acc->failed;
    return;
  }
  const Motion m = RunMotion(*variant.model, OutputRequest(model, options.request, {}));
  if (m.stop.kind == StopKind::Interrupted) return;  // neither run nor failed: not counted
  if (!m.complete || m.rows() != nominal.rows()) {
    ++acc->failed;
    return;
  }
  ++acc->runs;
  const int rows = nominal.rows();
  for (size_t k = 0; k < cols.size(); ++k) {
    const int same = m.layout().Find(nominal.columns()[cols[k]].name);
    for (int r = 0; r < rows; ++r) {
      const double dev = m.at(r, same) - nominal.at(r, cols[k]);
      const size_t i = k * rows + r;
      acc->max_abs[i] = std::max(acc->max_abs[i], std::abs(dev));
      acc->sum[i] += dev;
      acc->sum_sq[i] += dev * dev;
    }
  }
}

// The samples are one seeded sequence (every parameter of sample 0, then of sample
// 1, ...): the same seed gives the same variants whatever the number of threads.
// Each chunk draws its own from the generator's state at its first sample, so the
// memory follows the chunks, not N (drawn up front, --monte-carlo 1e8 held 1e8 variants).
std::vector<std::mt19937_64> ChunkGenerators(const ToleranceOptions& options, size_t parameters, int chunks) {
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<std::mt19937_64> at_chunk;
  for (int c = 0; c < chunks; ++c) {
    at_chunk.push_back(rng);
    const long long first = static_cast<long long>(options.monte_carlo) * c / chunks;
    const long long last = static_cast<long long>(options.monte_carlo) * (c + 1) / chunks;
    for (long long draw = first * static_cast<long long>(parameters); draw < last * static_cast<long long>(parameters); ++draw)
      unit(rng);
  }
  return at_chunk;
}

void MonteCarlo(const Model& model, const Motion& nominal, const std::vector<int>& cols,
                const ToleranceOptions& options, ToleranceReport* rep) {
  // Sums in a fixed order: the samples fall into kMonteCarloChunks fixed runs of
  // consecutive samples, each summed in sample order, and the chunks are added in
  // chunk order, so the report is the same to the last bit whatever the number of
  // threads and however they share the chunks.
  const size_t cells = cols.size() * nominal.rows();
  const int chunks = std::min(options.monte_carlo, kMonteCarloChunks);
  std::vector<MonteCarloSums> acc(chunks, MonteCarloSums{std::vector<double>(cells), std::vector<double>(cells),
                                                         std::vector<double>(cells), 0, 0});
  const auto first_of = [&](int c) { return static_cast<int>(static_cast<long long>(options.monte_carlo) * c / chunks); };
  const std::vector<std::mt19937_64> chunk_rng = ChunkGenerators(options, rep->parameters.size(), chunks);
  ParallelFor(chunks, options.threads, [&](int c, int) {
    std::mt19937_64 rng = chunk_rng[c];
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    ParameterOverrides sample;
    const InterruptPoll& interrupted = options.request.interrupted;
    for (int i = first_of(c); i < first_of(c + 1) && !(interrupted && interrupted()); ++i) {
      for (size_t p = 0; p < rep->parameters.size(); ++p)
        sample[rep->parameters[p]] = model.FindParameter(rep->parameters[p])->value + unit(rng) * rep->tolerances[p];
      RunSample(model, sample, nominal, cols, options, &acc[c]);
    }
  }, options.request.interrupted);
  MonteCarloSums total = acc[0];
  for (int c = 1; c < chunks; ++c) {
    for (size_t i = 0; i < cells; ++i) {
      total.max_abs[i] = std::max(total.max_abs[i], acc[c].max_abs[i]);
      total.sum[i] += acc[c].sum[i];
      total.sum_sq[i] += acc[c].sum_sq[i];
    }
    total.runs += acc[c].runs;
    total.failed += acc[c].failed;
  }
  rep->samples = total.runs;
  rep->failed_samples = total.failed;
  rep->interrupted = total.runs + total.failed < options.monte_carlo;
  const int rows = nominal.rows();
  for (size_t k = 0; k < cols.size() && total.runs > 1; ++k) {
    ToleranceColumn& tc = rep->columns[k];
    for (int r = 0; r < rows; ++r) {
      const size_t i = k * rows + r;
      const double mean = total.sum[i] / total.runs;
      const double sd = std::sqrt(std::max(0.0, (total.sum_sq[i] - total.runs * mean * mean) / (total.runs - 1)));
      if (total.max_abs[i] > tc.mc_max_deviation) tc.mc_max_deviation = total.max_abs[i], tc.t_mc_max = rep->t[r];
      if (sd > tc.mc_max_std) tc.mc_max_std = sd, tc.t_mc_std = rep->t[r];
    }
  }
}

}  // namespace

ToleranceReport AnalyzeTolerances(const Model& model, const ToleranceOptions& options) {
  ToleranceReport rep;
  rep.seed = options.seed;
  for (const auto& p : model.parameters)
    if (p.tolerance && *p.tolerance > 0) {
      rep.parameters.push_back(p.name);
      rep.tolerances.push_back(*p.tolerance);
    }
  if (rep.parameters.empty()) {
    rep.message = "no parameter declares a tolerance: write e.g. \"rod\": {\"value\": 120, \"tolerance\": 0.05}";
    return rep;
  }
  const RunRequest nominal_request = OutputRequest(model, options.request, rep.parameters);
  if (!nominal_request.IsValid(&rep.message)) return rep;
  const Motion nominal = RunMotion(model, nominal_request);
  if (!nominal.complete) {
    rep.interrupted = nominal.stop.kind == StopKind::Interrupted;
    rep.message = "the nominal run did not complete: " + nominal.stop.message;
    return rep;
  }
  for (int r = 0; r < nominal.rows(); ++r) rep.t.push_back(nominal.at(r, 0));
  const std::vector<int> cols = ValueColumns(nominal);
  for (int c : cols) rep.columns.push_back(LinearStack(nominal, c, rep));
  if (options.monte_carlo > 0) MonteCarlo(model, nominal, cols, options, &rep);
  if (options.monte_carlo > 0 && rep.samples == 0 && !rep.interrupted) {
    // No sample to compare with the nominal motion: a "largest deviation 0" would read as a pass.
    rep.message = "every one of the " + std::to_string(rep.failed_samples) +
                  " Monte-Carlo samples failed (the variant did not compile or did not run the whole motion), so "
                  "there is no Monte-Carlo check: compare the tolerances with the mechanism's range (mechkin "
                  "range), or run without --monte-carlo for the linear estimate";
    return rep;
  }
  rep.ok = true;
  return rep;
}

}  // namespace mechkin
