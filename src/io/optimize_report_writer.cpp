#include "io/optimize_report_writer.hpp"

#include <cmath>
#include <iomanip>

#include "io/convert_internal.hpp"

namespace mechkin {

bool WithParameterValues(const std::string& text, const std::map<std::string, double>& values, std::string* out,
                         std::string* error) {
  convert::Json doc;
  try {
    doc = convert::Json::parse(text);
  } catch (const std::exception& e) {
    *error = std::string("the file cannot be read again as JSON: ") + e.what();
    return false;
  }
  if (!doc.is_object() || !doc.contains("parameters") || !doc["parameters"].is_object()) {
    *error = "the file has no \"parameters\" object";
    return false;
  }
  convert::Json& params = doc["parameters"];
  for (const auto& [name, value] : values) {
    if (!params.contains(name)) {
      *error = "the file has no parameter '" + name + "' at /parameters";
      return false;
    }
    convert::Json& p = params[name];
    if (p.is_object()) p["value"] = value;
    else p = value;
  }
  *out = convert::Dump(doc);
  return true;
}

namespace {

using Json = nlohmann::ordered_json;

Json JsonNumber(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json Vector(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(JsonNumber(x));
  return a;
}

Json StartJson(const OptimizeStart& s) {
  return Json{{"initial", Vector(s.initial)},
              {"final", Vector(s.final)},
              {"objective_initial", JsonNumber(s.objective_initial)},
              {"objective_final", JsonNumber(s.objective_final)},
              {"iterations", s.iterations},
              {"ok", s.ok},
              {"feasible", s.feasible},
              {"failed_evaluations", s.failed_evaluations},
              {"failures", s.failures},
              {"termination", s.termination}};
}

}  // namespace

std::string OptimizeReportJsonText(const OptimizeResult& r) {
  Json j{{"ok", r.ok}, {"converged", r.converged}, {"interrupted", r.interrupted}, {"message", r.message},
         {"minimize", r.minimize}, {"objective_before", JsonNumber(r.objective_before)},
         {"objective_after", JsonNumber(r.objective_after)}};
  Json params = Json::array();
  for (size_t k = 0; k < r.vary.size(); ++k)
    params.push_back({{"name", r.vary[k]},
                      {"before", k < r.before.size() ? JsonNumber(r.before[k]) : Json(nullptr)},
                      {"after", k < r.after.size() ? JsonNumber(r.after[k]) : Json(nullptr)},
                      {"gradient", k < r.gradient.size() ? JsonNumber(r.gradient[k]) : Json(nullptr)}});
  j["parameters"] = params;
  j["iterations"] = r.iterations;
  j["gradient_norm"] = JsonNumber(r.gradient_norm);
  j["best_start"] = r.best_start;
  j["active_bounds"] = r.active_bounds;
  Json cons = Json::array();
  for (size_t c = 0; c < r.constraints.size(); ++c)
    cons.push_back({{"reduction", r.constraints[c].reduction},
                    {"relation", r.constraints[c].at_least ? ">=" : "<="},
                    {"bound", r.constraints[c].bound},
                    {"value", c < r.constraint_values.size() ? JsonNumber(r.constraint_values[c]) : Json(nullptr)},
                    {"active", c < r.constraint_active.size() && r.constraint_active[c]}});
  j["constraints"] = cons;
  Json starts = Json::array();
  for (const OptimizeStart& s : r.per_start) starts.push_back(StartJson(s));
  j["starts"] = starts;
  return j.dump();
}

void PrintOptimizeReport(const OptimizeResult& r, std::ostream& out) {
  out << std::setprecision(12);
  if (!r.ok) {
    out << "optimize: " << r.message << "\n";
    return;
  }
  out << "minimize " << r.minimize << ": " << r.objective_before << " -> " << r.objective_after
      << (r.converged ? " (converged)" : r.interrupted ? " (interrupted)" : " (not converged)") << "\n";
  if (!r.message.empty()) out << "  " << r.message << "\n";
  out << "best start " << r.best_start + 1 << " of " << r.per_start.size() << ", " << r.iterations
      << " iterations, gradient norm " << r.gradient_norm << "\n";
  for (size_t k = 0; k < r.vary.size(); ++k) {
    out << "  " << r.vary[k] << ": " << r.before[k] << " -> " << (k < r.after.size() ? r.after[k] : NAN);
    if (k < r.gradient.size()) out << "   d/d = " << r.gradient[k];
    out << "\n";
  }
  for (const std::string& b : r.active_bounds) out << "  active bound: " << b << "\n";
  for (size_t c = 0; c < r.constraints.size(); ++c) {
    const OptimizeConstraint& con = r.constraints[c];
    out << "  subject to " << con.reduction << (con.at_least ? " >= " : " <= ") << con.bound;
    if (c < r.constraint_values.size())
      out << ": " << r.constraint_values[c] << (r.constraint_active[c] ? " (active)" : "");
    out << "\n";
  }
  for (size_t s = 0; s < r.per_start.size(); ++s) {
    const OptimizeStart& st = r.per_start[s];
    out << "  start " << s + 1 << ": ";
    if (!st.ok) {
      out << st.termination << "\n";
      continue;
    }
    out << st.objective_initial << " -> " << st.objective_final << ", "
        << st.iterations << " iterations" << (st.feasible || !st.ok ? "" : ", infeasible") << ": " << st.termination;
    if (st.failed_evaluations && st.ok)
      out << "; " << st.failed_evaluations << " failed variant(s), first: " << st.failures.front();
    out << "\n";
  }
}

}  // namespace mechkin
