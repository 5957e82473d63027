// The live page's core (issue 30): mechkin's spec reading, Compile(spec, overrides),
// the Newton position solve, the derivative orders and the mobility report, compiled
// to WebAssembly (tools/build_live.sh) behind a small C API that the page's script
// (src/io/viewer/live.js) calls. Never part of the native build (CMake's io glob is
// not recursive); Ceres, FCL, SuiteSparse and threads are left out, their entry
// points answered by src/io/live/live_stubs.cpp.
//
// The page recompiles the file's text with the sliders' values exactly as
// `mechkin run --set NAME=VALUE` does (LoadMechanismText with the overrides), runs
// the same RunRequest a `run` does by default, and reads the rows in the table's
// units (the CSV's numbers, before their printing).
#include <cstring>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/load.hpp"
#include "analysis/run_request.hpp"
#include "io/plot_marks.hpp"
#include "mobility/mobility.hpp"

namespace mechkin::live {
namespace {

struct State {
  std::string text;             // the mechanism file as the page holds it
  ParameterOverrides overrides;  // the sliders' values
  std::optional<Model> model;   // the last model that compiled
  std::vector<double> table;    // the last run's rows, row-major
  int rows = 0, cols = 0;
  std::string columns;  // JSON: the headers of the last run
  std::string error;    // the last failure's message ("" when the last call worked)
  std::string mobility;  // JSON of the last model's mobility report
  std::string status;    // JSON: how the last run ended
};

State& Live() {
  static State s;
  return s;
}

std::string Messages(const std::vector<Diagnostic>& errors) {
  std::string out;
  for (const Diagnostic& d : errors) out += (out.empty() ? "" : "\n") + d.ToString();
  return out;
}

std::string MobilityJson(const Model& model) {
  const MobilityReport r = CalcMobility(model);
  nlohmann::json j = {{"assembled", r.assembled},   {"mobility", r.mobility},
                      {"redundant", r.redundant},   {"equations", r.equations},
                      {"rank", r.rank},             {"driving", DrivingStatusName(r.driving_status)},
                      {"dof_after_drivers", r.dof_after_drivers}, {"verdict", r.verdict},
                      {"singular_lost", r.singular_lost}, {"assembly_message", r.assembly_message}};
  return j.dump();
}

// Compiles the text with the overrides; false with the loader's messages, or with the
// message of anything compiling throws (an exception must not leave an extern "C" call:
// it would abort the module and the page with it).
bool CompileNow(State& s) {
  try {
    LoadResult loaded = LoadMechanismText(s.text, "page", s.overrides);
    if (!loaded.ok()) {
      s.error = Messages(loaded.errors);
      return false;
    }
    s.model = std::move(loaded.model);
    return true;
  } catch (const std::exception& e) {
    s.error = e.what();
    return false;
  }
}

// The run's table and how it ended: the stop's message, the singular positions it
// passed (the report's notes) and the plots' marks, as the viewer's page has them.
void KeepMotion(State& s, const Motion& m) {
  s.rows = m.rows();
  s.cols = m.cols();
  s.table = m.values();
  nlohmann::json names = nlohmann::json::array();
  for (const ColumnDescriptor& c : m.columns()) names.push_back({c.name, c.Header()});
  s.columns = names.dump();
  nlohmann::json marks = nlohmann::json::array();
  for (const PlotMark& mark : PlotMarks(*s.model, m)) marks.push_back({{"t", mark.t}, {"kind", mark.kind}, {"label", mark.label}});
  s.status = nlohmann::json{{"complete", m.complete}, {"message", m.stop.message}, {"notes", m.report.notes},
                            {"marks", marks}}.dump();
}

}  // namespace
}  // namespace mechkin::live

using mechkin::live::Live;

extern "C" {

/// Holds a mechanism file's text and compiles it with no overrides: 0, or 1 with mk_live_error().
int mk_live_load(const char* json) {
  auto& s = Live();
  s = {};
  s.text = json ? json : "";
  return mechkin::live::CompileNow(s) ? 0 : 1;
}

/// Sets (or, for a NaN value, removes) one parameter override, as `--set NAME=VALUE`.
void mk_live_set(const char* name, double value) {
  auto& s = Live();
  if (value != value) s.overrides.erase(name);
  else s.overrides[name] = value;
}

/// Drops every override.
void mk_live_clear() { Live().overrides.clear(); }

/// Recompiles with the overrides and runs the file's analysis (`steps` > 0 replaces its
/// step count, as `run` with /analysis/steps changed; 0 keeps it); the rows in the table's
/// units. Returns the table (rows × cols doubles) or null with mk_live_error(); on a
/// failure the last valid model and table are kept.
const double* mk_live_run(int steps, int order) {
  auto& s = Live();
  s.error.clear();
  std::optional<mechkin::Model> last = s.model;
  if (!mechkin::live::CompileNow(s)) return nullptr;
  try {
    mechkin::Model& model = *s.model;
    if (steps > 0 && model.analysis) model.analysis->steps = steps;
    mechkin::RunRequest request;
    request.order = order;
    const mechkin::Motion motion = mechkin::RunMotion(model, request);
    if (motion.rows() == 0) {
      s.error = motion.stop.message;
      s.model = std::move(last);
      return nullptr;
    }
    mechkin::live::KeepMotion(s, motion);
    s.mobility.clear();
  } catch (const std::exception& e) {
    s.error = e.what();
    s.model = std::move(last);
    return nullptr;
  }
  return s.table.data();
}

int mk_live_rows() { return Live().rows; }
int mk_live_cols() { return Live().cols; }
/// JSON array of the last table's columns: [name, header] ("crank.x", "crank.x [mm]").
const char* mk_live_columns() { return Live().columns.c_str(); }
/// JSON: {"complete": bool, "message": the stop's explanation, "notes": [the singular
/// positions passed], "marks": [{"t", "kind", "label"}: the plots' marks]}.
const char* mk_live_status() { return Live().status.c_str(); }
const char* mk_live_error() { return Live().error.c_str(); }

/// JSON of the current model's mobility report (constraints.md §6), computed on demand.
const char* mk_live_mobility() {
  auto& s = Live();
  if (!s.model) return "{}";
  try {
    if (s.mobility.empty()) s.mobility = mechkin::live::MobilityJson(*s.model);
  } catch (const std::exception& e) {
    s.error = e.what();
    return "{}";
  }
  return s.mobility.c_str();
}

}  // extern "C"
