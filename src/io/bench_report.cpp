#include "io/bench_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/table_writer.hpp"

namespace mechkin {

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
      << "<text x=\"" << W / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">" << XmlEscape(title) << "</text>\n";
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
        << (r.on_front ? "#d62728" : "#1f77b4") << "\" opacity=\"0.7\"><title>" << XmlEscape(r.setting.Describe()) << "</title></circle>\n";
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
