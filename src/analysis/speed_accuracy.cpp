#include "analysis/speed_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>


namespace mechkin {

std::string BenchSetting::Describe() const {
  std::ostringstream o;
  o << (solver == PositionSolver::Ceres ? "ceres" : "newton") << ", tol " << tolerance << ", predictor " << predictor
    << ", " << (formulation == Formulation::P ? "p" : "omega") << ", " << steps << " steps";
  return o.str();
}

double BenchResult::worst_error() const { return *std::max_element(error, error + 4); }

Motion RunForBench(const Model& model, const BenchSetting& s) {
  Model m = model;
  m.analysis->steps = s.steps;
  TableOptions topt;
  topt.order = 3;
  topt.si = true;
  AnalysisOptions o;
  o.order = 3;
  o.solver = s.solver;
  o.tolerance = s.tolerance;
  o.predictor_order = s.predictor;
  o.formulation = s.formulation;
  return RunMotion(m, o, topt);
}

ReferenceTable ReferenceFromMotion(const Motion& motion) {
  ReferenceTable ref;
  for (int c = 0; c < motion.cols(); ++c) {
    const ColumnDescriptor& d = motion.columns()[c];
    if (d.quantity == Quantity::Time) ref.t = motion.Column(c);
    else ref.columns[d.name] = motion.Column(c);
  }
  return ref;
}

ReferenceTable ReadReferenceCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read reference table '" + path + "'");
  std::string line;
  std::vector<std::string> names;
  ReferenceTable ref;
  int line_number = 0;
  const std::string where = "reference table '" + path + "'";
  while (std::getline(in, line)) {
    ++line_number;
    if (line.rfind("# PARTIAL", 0) == 0)
      throw std::runtime_error(where + " is partial (its run stopped early): use a complete table");
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string cell;
    if (names.empty()) {
      while (std::getline(ss, cell, ',')) {
        const auto lb = cell.find(" [");
        const std::string unit = lb == std::string::npos ? "" : cell.substr(lb + 2, cell.size() - lb - 3);
        const std::string base = unit.substr(0, unit.find('/'));
        if (!base.empty() && base != "s" && base != "m" && base != "rad" && base != "1")
          throw std::runtime_error(where + ": column '" + cell + "' is not in SI units: write the reference with `mechkin run --si`");
        names.push_back(cell.substr(0, lb));
      }
      if (names.empty() || names[0] != "t")
        throw std::runtime_error(where + ": the first column must be 't [s]' (a table written by `mechkin run --si`)");
      continue;
    }
    size_t c = 0;
    while (std::getline(ss, cell, ',') && c < names.size()) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (cell.empty() || *end != '\0')
        throw std::runtime_error(where + ", line " + std::to_string(line_number) + ": '" + cell + "' is not a number");
      if (names[c] == "t") ref.t.push_back(v); else ref.columns[names[c]].push_back(v);
      ++c;
    }
    if (c != names.size())
      throw std::runtime_error(where + ", line " + std::to_string(line_number) + ": " + std::to_string(c) + " cells, the header has " + std::to_string(names.size()));
  }
  if (ref.t.empty()) throw std::runtime_error(where + " has no rows");
  return ref;
}

namespace {

// Errors per derivative order (translational and output columns; Euler parameters and
// diagnostics excluded), each relative to the largest reference value of that order.
// The column's kind and order come from its descriptor, never from its name.
bool Compared(const ColumnDescriptor& d) {
  return !d.IsDiagnostic() && d.quantity != Quantity::Time && d.quantity != Quantity::EulerParameter &&
         d.quantity != Quantity::AngularVelocity && d.order <= 3;
}

void Compare(const Motion& run, const ReferenceTable& ref, double* err) {
  double scale[4] = {0, 0, 0, 0}, diff[4] = {0, 0, 0, 0};
  const std::vector<double> t = run.Column(0);
  for (int c = 0; c < run.cols(); ++c) {
    const ColumnDescriptor& d = run.columns()[c];
    if (!Compared(d)) continue;
    const auto it = ref.columns.find(d.name);
    if (it == ref.columns.end()) continue;
    const int k = d.order;
    size_t j = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      while (j < ref.t.size() && ref.t[j] < t[i] - 1e-9 * (std::abs(t[i]) + 1)) ++j;
      if (j >= ref.t.size() || std::abs(ref.t[j] - t[i]) > 1e-9 * (std::abs(t[i]) + 1)) continue;
      diff[k] = std::max(diff[k], std::abs(run.at(static_cast<int>(i), c) - it->second[j]));
      scale[k] = std::max(scale[k], std::abs(it->second[j]));
    }
  }
  for (int k = 0; k < 4; ++k) err[k] = scale[k] > 0 ? diff[k] / scale[k] : diff[k];
}

}  // namespace

std::vector<BenchSetting> BenchGrid(const Model& model, const BenchOptions& options) {
  const int n = model.analysis->steps;
  std::vector<BenchSetting> grid;
  if (options.quick) {
    for (double tol : {1e-4, 1e-8, 1e-12})
      for (int pred : {0, 3}) grid.push_back({PositionSolver::Newton, tol, pred, Formulation::Omega, n});
    grid.push_back({PositionSolver::Ceres, 1e-10, 3, Formulation::Omega, n});
    grid.push_back({PositionSolver::Newton, 1e-10, 3, Formulation::Omega, std::max(1, n / 4)});
    return grid;
  }
  for (PositionSolver sv : {PositionSolver::Newton, PositionSolver::Ceres})
    for (double tol : {1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14})
      for (int pred : {0, 1, 2, 3})
        for (Formulation f : {Formulation::Omega, Formulation::P})
          for (int steps : {std::max(1, n / 4), n, 4 * n}) {
            if (sv == PositionSolver::Ceres && (pred != 3 || f != Formulation::Omega)) continue;
            grid.push_back({sv, tol, pred, f, steps});
          }
  return grid;
}

std::vector<BenchResult> RunBench(const Model& model, const std::vector<BenchSetting>& grid,
                                  const ReferenceTable& reference, const BenchOptions& options) {
  std::vector<BenchResult> results;
  for (const BenchSetting& s : grid) {
    BenchResult r;
    r.setting = s;
    std::vector<double> medians;
    for (int rep = 0; rep < std::max(1, options.repeats); ++rep) {
      const Motion table = RunForBench(model, s);
      const AnalysisReport& report = table.report;
      r.complete = report.complete;
      if (!report.complete || report.steps.empty()) break;
      const StepStatistics st = SummarizeSteps(report.steps);
      medians.push_back(st.median_us);
      r.iterations = st.mean_iterations;
      r.residual = st.max_residual;
      if (rep == 0) Compare(table, reference, r.error);
    }
    if (r.complete && !medians.empty()) {
      std::sort(medians.begin(), medians.end());
      r.us_min = medians.front();
      r.us_max = medians.back();
      r.us_median = medians[medians.size() / 2];
    }
    results.push_back(r);
  }
  // Pareto front: no other complete result is both faster and more accurate.
  for (auto& a : results) {
    if (!a.complete) continue;
    a.on_front = std::none_of(results.begin(), results.end(), [&](const BenchResult& b) {
      return b.complete && &b != &a && b.us_median <= a.us_median && b.worst_error() <= a.worst_error() &&
             (b.us_median < a.us_median || b.worst_error() < a.worst_error());
    });
  }
  return results;
}

}  // namespace mechkin
