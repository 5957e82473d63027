#include "analysis/speed_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "output/motion_table.hpp"

namespace mechkin {

std::string BenchSetting::Describe() const {
  std::ostringstream o;
  o << (solver == PositionSolver::Ceres ? "ceres" : "newton") << ", tol " << tolerance << ", predictor " << predictor
    << ", " << (formulation == Formulation::P ? "p" : "omega") << ", " << steps << " steps";
  return o.str();
}

double BenchResult::worst_error() const { return *std::max_element(error, error + 4); }

ReferenceTable RunForBench(const Model& model, const BenchSetting& s, AnalysisReport* report) {
  Model m = model;
  m.analysis->steps = s.steps;
  TableOptions topt;
  topt.order = 3;
  topt.si = true;
  MotionTable table(m, topt);
  AnalysisOptions o;
  o.order = 3;
  o.solver = s.solver;
  o.tolerance = s.tolerance;
  o.predictor_order = s.predictor;
  o.formulation = s.formulation;
  *report = RunKinematicAnalysis(m, o, [&](const SystemState& st, const StepDiagnostics& d) {
    table.AddRow(st, d.t, d.iterations, d.residual, d.condition, d.error_bound);
  });
  ReferenceTable ref;
  for (size_t c = 0; c < table.header().size(); ++c) {
    const std::string name = table.header()[c].substr(0, table.header()[c].find(" ["));
    auto& col = name == "t" ? ref.t : ref.columns[name];
    for (const auto& row : table.rows()) col.push_back(row[c]);
  }
  return ref;
}

ReferenceTable ReadReferenceCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read reference table '" + path + "'");
  std::string line;
  std::vector<std::string> names;
  ReferenceTable ref;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    std::string cell;
    if (names.empty()) {
      while (std::getline(ss, cell, ',')) names.push_back(cell.substr(0, cell.find(" [")));
      continue;
    }
    size_t c = 0;
    while (std::getline(ss, cell, ',') && c < names.size()) {
      const double v = std::strtod(cell.c_str(), nullptr);
      if (names[c] == "t") ref.t.push_back(v); else ref.columns[names[c]].push_back(v);
      ++c;
    }
  }
  if (ref.t.empty()) throw std::runtime_error("reference table '" + path + "' has no rows");
  return ref;
}

namespace {

int OrderOf(const std::string& name) {
  const auto p = name.find("_t");
  if (p == std::string::npos) return 0;
  return static_cast<int>(name.size() - p - 1);
}

// Errors per derivative order (translational and output columns; Euler parameters and
// diagnostics excluded), each relative to the largest reference value of that order.
void Compare(const ReferenceTable& run, const ReferenceTable& ref, double* err) {
  double scale[4] = {0, 0, 0, 0}, diff[4] = {0, 0, 0, 0};
  for (const auto& [name, values] : run.columns) {
    if (name == "newton_iterations" || name == "residual" || name == "condition" || name.rfind("error_bound", 0) == 0 ||
        name.find(".e") != std::string::npos ||
        name.find(".w") != std::string::npos)
      continue;
    const auto it = ref.columns.find(name);
    if (it == ref.columns.end()) continue;
    const int k = OrderOf(name);
    if (k > 3) continue;
    size_t j = 0;
    for (size_t i = 0; i < run.t.size(); ++i) {
      while (j < ref.t.size() && ref.t[j] < run.t[i] - 1e-9 * (std::abs(run.t[i]) + 1)) ++j;
      if (j >= ref.t.size() || std::abs(ref.t[j] - run.t[i]) > 1e-9 * (std::abs(run.t[i]) + 1)) continue;
      diff[k] = std::max(diff[k], std::abs(values[i] - it->second[j]));
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
      AnalysisReport report;
      const ReferenceTable table = RunForBench(model, s, &report);
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

void WriteBenchCsv(const std::vector<BenchResult>& results, std::ostream& out) {
  out << "solver,tolerance,predictor,formulation,steps,complete,us_per_step_median,us_per_step_min,us_per_step_max,"
         "newton_iterations,max_residual,error_position,error_velocity,error_acceleration,error_jerk,on_front\n";
  for (const auto& r : results) {
    const auto& s = r.setting;
    out << (s.solver == PositionSolver::Ceres ? "ceres" : "newton") << "," << s.tolerance << "," << s.predictor << ","
        << (s.formulation == Formulation::P ? "p" : "omega") << "," << s.steps << "," << (r.complete ? 1 : 0) << ","
        << r.us_median << "," << r.us_min << "," << r.us_max << "," << r.iterations << "," << r.residual;
    for (double e : r.error) out << "," << e;
    out << "," << (r.on_front ? 1 : 0) << "\n";
  }
}

void WriteBenchSvg(const std::vector<BenchResult>& results, const std::string& title, std::ostream& out) {
  const double W = 640, H = 420, L = 70, R = 20, T = 40, B = 50;
  double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
  for (const auto& r : results) {
    if (!r.complete) continue;
    xmin = std::min(xmin, r.us_median); xmax = std::max(xmax, r.us_median);
    const double e = std::max(r.worst_error(), 1e-17);
    ymin = std::min(ymin, e); ymax = std::max(ymax, e);
  }
  if (xmax <= 0) { xmin = 1; xmax = 10; ymin = 1e-16; ymax = 1; }
  const double lx0 = std::floor(std::log10(xmin)), lx1 = std::ceil(std::log10(xmax)) + (xmin == xmax);
  const double ly0 = std::floor(std::log10(ymin)), ly1 = std::ceil(std::log10(ymax)) + (ymin == ymax);
  auto X = [&](double v) { return L + (std::log10(v) - lx0) / (lx1 - lx0) * (W - L - R); };
  auto Y = [&](double v) { return H - B - (std::log10(std::max(v, 1e-17)) - ly0) / (ly1 - ly0) * (H - T - B); };
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << W / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">" << title << "</text>\n";
  for (double e = lx0; e <= lx1; ++e)
    out << "<line x1=\"" << X(std::pow(10, e)) << "\" y1=\"" << T << "\" x2=\"" << X(std::pow(10, e)) << "\" y2=\"" << H - B
        << "\" stroke=\"#ddd\"/><text x=\"" << X(std::pow(10, e)) << "\" y=\"" << H - B + 16 << "\" text-anchor=\"middle\">1e"
        << e << "</text>\n";
  for (double e = ly0; e <= ly1; e += 2)
    out << "<line x1=\"" << L << "\" y1=\"" << Y(std::pow(10, e)) << "\" x2=\"" << W - R << "\" y2=\"" << Y(std::pow(10, e))
        << "\" stroke=\"#ddd\"/><text x=\"" << L - 6 << "\" y=\"" << Y(std::pow(10, e)) + 4 << "\" text-anchor=\"end\">1e" << e
        << "</text>\n";
  out << "<text x=\"" << W / 2 << "\" y=\"" << H - 12 << "\" text-anchor=\"middle\">time per step [us]</text>\n"
      << "<text x=\"16\" y=\"" << H / 2 << "\" transform=\"rotate(-90 16 " << H / 2
      << ")\" text-anchor=\"middle\">largest relative error (position..jerk)</text>\n";
  std::vector<const BenchResult*> front;
  for (const auto& r : results) {
    if (!r.complete) continue;
    out << "<circle cx=\"" << X(r.us_median) << "\" cy=\"" << Y(r.worst_error()) << "\" r=\"3\" fill=\""
        << (r.on_front ? "#d62728" : "#1f77b4") << "\" opacity=\"0.7\"><title>" << r.setting.Describe() << "</title></circle>\n";
    if (r.on_front) front.push_back(&r);
  }
  std::sort(front.begin(), front.end(), [](auto a, auto b) { return a->us_median < b->us_median; });
  if (front.size() > 1) {
    out << "<polyline fill=\"none\" stroke=\"#d62728\" points=\"";
    for (auto* r : front) out << X(r->us_median) << "," << Y(r->worst_error()) << " ";
    out << "\"/>\n";
  }
  out << "</svg>\n";
}

void PrintFront(const std::vector<BenchResult>& results, std::ostream& out) {
  std::vector<const BenchResult*> front;
  for (const auto& r : results) if (r.on_front) front.push_back(&r);
  std::sort(front.begin(), front.end(), [](auto a, auto b) { return a->us_median < b->us_median; });
  char line[320];
  out << "Pareto front (time per step vs largest relative error of position, velocity, acceleration, jerk):\n";
  std::snprintf(line, sizeof line, "  %-48s %12s %10s %10s %10s %10s %10s\n", "setting", "us/step", "iter/step",
                "e(pos)", "e(vel)", "e(acc)", "e(jerk)");
  out << line;
  for (auto* r : front) {
    std::snprintf(line, sizeof line, "  %-48s %8.2f [%.2f-%.2f] %6.2f %10.2e %10.2e %10.2e %10.2e\n",
                  r->setting.Describe().c_str(), r->us_median, r->us_min, r->us_max, r->iterations, r->error[0],
                  r->error[1], r->error[2], r->error[3]);
    out << line;
  }
  struct Need { const char* what; double bound; };
  for (const Need& need : {Need{"a design sweep, within 1e-3", 1e-3}, Need{"drawings and tolerancing, within 1e-6", 1e-6},
                           Need{"cam and jerk checks, within 1e-9", 1e-9}}) {
    const BenchResult* best = nullptr;
    for (const auto& r : results)
      if (r.complete && r.worst_error() <= need.bound && (!best || r.us_median < best->us_median)) best = &r;
    out << "recommendation for " << need.what << " of the motion's size: ";
    if (best) {
      std::snprintf(line, sizeof line, "%s (%.2f us/step)", best->setting.Describe().c_str(), best->us_median);
      out << line << "\n";
    } else {
      out << "none of the settings tried reaches it\n";
    }
  }
}

}  // namespace mechkin
