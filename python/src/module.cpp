// _mechkin: the C++ core for Python. Models are immutable and shared; a Motion's
// table is exposed as a numpy view of the core's own buffer (no copy), kept
// alive by the Motion object. The GIL is released while solving and writing.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "analysis/check_report.hpp"
#include "analysis/reduction.hpp"
#include "analysis/count_limits.hpp"
#include "analysis/enum_names.hpp"
#include "analysis/motion.hpp"
#include "analysis/range.hpp"
#include "analysis/run_request.hpp"
#include "analysis/sweep.hpp"
#include "analysis/sweep_curves.hpp"
#include "analysis/tolerance.hpp"
#include "io/check_report_writer.hpp"
#include "io/hdf5_dataset.hpp"
#include "io/load_any.hpp"
#include "io/range_report_writer.hpp"
#include "io/table_writer.hpp"
#include "io/tolerance_report_writer.hpp"
#include "analysis/load.hpp"
#include "analysis/optimize.hpp"
#include "io/optimize_report_writer.hpp"
#include "check_report_binding.hpp"
#include "interrupt_binding.hpp"
#include "request_binding.hpp"

namespace py = pybind11;
using namespace mechkin;
using namespace mechkin_python;

namespace {

// A compiled model with the text it came from (its pickled form).
struct LoadedModel {
  std::shared_ptr<const Model> model;
  std::vector<Diagnostic> warnings;
  std::string text, source;
  ParameterOverrides overrides;  // with_parameters / --set values (part of the pickled form)
};

py::list DiagnosticList(const std::vector<Diagnostic>& ds) {
  py::list out;
  for (const auto& d : ds) out.append(py::cast(d));
  return out;
}

// (model or None, errors, warnings) of a load; the model keeps `text`, its pickled form.
py::tuple LoadedTuple(LoadResult r, const std::string& text, const std::string& source,
                      const ParameterOverrides& overrides) {
  if (!r.ok()) return py::make_tuple(py::none(), DiagnosticList(r.errors), DiagnosticList(r.warnings));
  auto m = std::make_shared<LoadedModel>();
  m->model = std::make_shared<const Model>(std::move(*r.model));
  m->warnings = r.warnings;
  m->text = text;
  m->source = source;
  m->overrides = overrides;
  return py::make_tuple(m, py::list(), DiagnosticList(r.warnings));
}

// (model or None, errors, warnings)
py::tuple CompileText(const std::string& text, const std::string& source, const ParameterOverrides& overrides) {
  LoadResult r;
  {
    py::gil_scoped_release release;
    r = LoadMechanismText(text, source, overrides);
  }
  return LoadedTuple(std::move(r), text, source, overrides);
}

// A mechanism file or a foreign file (URDF, MJCF, SDFormat, FreeCAD), the latter
// driven by `drives` (joint → function of t, SI) over `span` (start, end, steps; empty:
// the importer's default): (model or None, errors, warnings) as CompileText. A
// foreign model keeps the imported spec's text, so that it pickles as any other.
py::tuple CompileFile(const std::string& path, const ParameterOverrides& overrides,
                      const std::vector<std::pair<std::string, std::string>>& drives, const std::vector<double>& span) {
  importers::ImportOptions foreign;
  foreign.drives = drives;
  if (span.size() == 3) foreign.start = span[0], foreign.end = span[1], foreign.steps = static_cast<int>(span[2]);
  foreign.span_given = span.size() == 3;
  LoadResult r;
  std::string imported_text;
  {
    py::gil_scoped_release release;
    r = LoadAnyMechanism(path, overrides, foreign, &imported_text);
  }
  return LoadedTuple(std::move(r), imported_text, path, overrides);
}

// The same model compiled from its spec with other parameter values (no re-parse of
// the text): (model or None, errors, warnings) as CompileText.
py::tuple ModelWithParameters(const LoadedModel& m, const ParameterOverrides& values) {
  LoadResult r;
  {
    py::gil_scoped_release release;
    r = WithParameters(*m.model, values);
  }
  if (!r.ok()) return py::make_tuple(py::none(), DiagnosticList(r.errors), DiagnosticList(r.warnings));
  auto variant = std::make_shared<LoadedModel>(m);
  variant->model = std::make_shared<const Model>(std::move(*r.model));
  variant->warnings = r.warnings;
  for (const auto& kv : values) variant->overrides[kv.first] = kv.second;
  return py::make_tuple(variant, py::list(), DiagnosticList(r.warnings));
}

PyCheckReport CheckModel(const LoadedModel& m) {
  LoadResult loaded;
  loaded.model = *m.model;
  loaded.warnings = m.warnings;
  py::gil_scoped_release release;
  return PyCheckReport{CheckLoaded(m.source, loaded)};
}

// Argument checks of the Python front end that are not a run request's: as ValueError.
void Require(bool ok, const std::string& what) {
  if (!ok) throw py::value_error(what);
}

// (JSON text, text): a report's JSON form (the CLI's --format json) and its text form.
template <typename Report>
py::tuple ReportAndText(const Report& report, std::string (*to_json)(const Report&),
                        void (*print)(const Report&, std::ostream&)) {
  std::ostringstream text;
  print(report, text);
  return py::make_tuple(to_json(report), text.str());
}

// The request's ranges for the fields a command takes (ValueError with IsValid's message).
void ValidateOrderAndTolerance(int order, double tol) {
  RunRequest r;
  r.order = order;
  r.tolerance = tol;
  ValidateRequest(r);
}

// `mechkin range`: (report dict, text).
py::tuple RangeOfModel(const LoadedModel& m, const std::string& driver, int steps, double span, double tol) {
  Require(CountProblem(kRangeSteps, steps).empty(), CountProblem(kRangeSteps, steps));
  Require(span >= 0 && std::isfinite(span), "span must be a positive length in file units (0: 4 x the mechanism's size)");
  ValidateOrderAndTolerance(0, tol);
  RangeOptions options;
  options.driver = driver;
  options.steps = steps;
  options.span = span;
  options.tolerance = tol;
  RangeReport report;
  const PythonInterrupt interrupt;
  options.interrupted = interrupt.Poll();
  {
    py::gil_scoped_release release;
    report = CalcRange(*m.model, options);
  }
  interrupt.RethrowIfRaised();
  return ReportAndText(report, &RangeReportJsonText, &PrintRangeReport);
}

// `mechkin tolerance`: (report dict, text).
py::tuple ToleranceOfModel(const LoadedModel& m, int order, int monte_carlo, unsigned long seed, int threads,
                           double tol) {
  ValidateOrderAndTolerance(order, tol);
  Require(CountProblem(kMonteCarloSamples, monte_carlo).empty(), CountProblem(kMonteCarloSamples, monte_carlo));
  Require(threads >= 0 && threads <= 4096, "threads must be between 0 (all cores) and 4096");
  ToleranceOptions options;
  options.request.order = order;
  options.request.tolerance = tol;
  options.monte_carlo = monte_carlo;
  options.seed = seed;
  options.threads = threads;
  ToleranceReport report;
  const PythonInterrupt interrupt;
  options.request.interrupted = interrupt.Poll();
  {
    py::gil_scoped_release release;
    report = AnalyzeTolerances(*m.model, options);
  }
  interrupt.RethrowIfRaised();
  return ReportAndText(report, &ToleranceReportJsonText, &PrintToleranceReport);
}

// Model.optimize / objective / gradient (analysis/optimize.hpp): the request as the
// CLI's `mechkin optimize` builds it.
OptimizeRequest PyOptimizeRequest(const std::vector<std::string>& vary, const std::string& minimize,
                                  const std::vector<std::string>& subject_to, int starts, unsigned long seed,
                                  int max_iterations, int order, double tol) {
  ValidateOrderAndTolerance(order, tol);
  OptimizeRequest r;
  r.vary = vary;
  r.minimize = minimize;
  r.starts = starts;
  r.seed = seed;
  r.max_iterations = max_iterations;
  r.run.order = order;
  r.run.tolerance = tol;
  for (const std::string& text : subject_to) {
    OptimizeConstraint c;
    std::string why;
    Require(ParseOptimizeConstraint(text, &c, &why), why);
    r.subject_to.push_back(c);
  }
  return r;
}

// (report JSON, report text, {parameter: optimised value}).
py::tuple OptimizeModel(const LoadedModel& m, const std::vector<std::string>& vary, const std::string& minimize,
                        const std::vector<std::string>& subject_to, int starts, unsigned long seed,
                        int max_iterations, int order, double tol) {
  OptimizeRequest r = PyOptimizeRequest(vary, minimize, subject_to, starts, seed, max_iterations, order, tol);
  const std::string problem = OptimizeRequestProblem(*m.model, r);
  Require(problem.empty(), problem);
  OptimizeResult result;
  const PythonInterrupt interrupt;
  r.interrupted = interrupt.Poll();
  {
    py::gil_scoped_release release;
    result = Optimize(*m.model, r);
  }
  interrupt.RethrowIfRaised();
  py::dict after;
  for (size_t k = 0; k < result.vary.size() && k < result.after.size(); ++k) after[py::str(result.vary[k])] = result.after[k];
  std::ostringstream text;
  PrintOptimizeReport(result, text);
  return py::make_tuple(OptimizeReportJsonText(result), text.str(), after);
}

// (value, gradient) of a reduction at parameter values; ValueError when the variant fails.
py::tuple ObjectiveOfModel(const LoadedModel& m, const std::string& name, const std::vector<std::string>& vary,
                           const std::vector<double>& values, int order, double tol) {
  OptimizeRequest r = PyOptimizeRequest(vary, name, {}, 1, 0, 1, order, tol);
  Require(values.size() == vary.size(), "give one value per parameter varied");
  const std::string problem = OptimizeRequestProblem(*m.model, r);
  Require(problem.empty(), problem);
  ObjectiveValue v;
  {
    py::gil_scoped_release release;
    v = EvaluateObjective(*m.model, r, values);
  }
  Require(v.ok, name + " cannot be evaluated there: " + v.problem);
  return py::make_tuple(v.value, v.gradient);
}

// A Motion with the model it was computed from (the layout refers to it).
struct PyMotion {
  std::shared_ptr<const Model> model;
  std::unique_ptr<Motion> motion;
};

TableOptions MakeTableOptions(int order, bool si, const std::optional<std::vector<std::string>>& bodies,
                              const std::optional<std::vector<std::string>>& outputs, bool forces) {
  TableOptions t;
  t.forces = forces;
  t.order = order;
  t.si = si;
  t.all_bodies = !bodies.has_value();
  t.all_outputs = !outputs.has_value();
  if (bodies) t.bodies = *bodies;
  if (outputs) t.outputs = *outputs;
  return t;
}

// The model with the analysis span replaced where start/end/steps are given.
std::shared_ptr<const Model> WithSpan(const std::shared_ptr<const Model>& model, std::optional<double> start,
                                      std::optional<double> end, std::optional<int> steps) {
  if (!start && !end && !steps) return model;
  auto copy = std::make_shared<Model>(*model);
  if (!copy->analysis) copy->analysis = Analysis{};
  if (start) copy->analysis->start = *start;
  if (end) copy->analysis->end = *end;
  if (steps) copy->analysis->steps = *steps;
  // The file's own limits and messages (model/model.hpp SpanProblem): steps=10**8 or end=inf are refused here.
  const std::string why = SpanProblem(copy->analysis->start, copy->analysis->end, copy->analysis->steps);
  if (!why.empty()) throw py::value_error(why);
  return copy;
}

// `mechkin run` from Python: the request validated and planned (ValueError with the
// CLI's message) before the GIL is released for the run.
std::shared_ptr<PyMotion> RunModel(const LoadedModel& m, RunRequest request, std::optional<double> start,
                                   std::optional<double> end, std::optional<int> steps) {
  auto model = WithSpan(m.model, start, end, steps);
  ValidateRequest(request);
  for (const auto& p : request.sensitivity)
    if (!model->FindParameter(p)) throw py::value_error("sensitivity: no parameter '" + p + "' in the model");
  request.keep_step_diagnostics = false;  // the table's diagnostic columns carry them
  RunPlan plan;
  try {
    plan = PlanRun(*model, request);  // selection errors as ValueError, before releasing the GIL
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  auto out = std::make_shared<PyMotion>();
  out->model = model;
  const PythonInterrupt interrupt;
  plan.analysis.interrupted = interrupt.Poll();
  {
    py::gil_scoped_release release;
    out->motion = std::make_unique<Motion>(RunPlanned(*model, plan));
  }
  interrupt.RethrowIfRaised();
  return out;
}

std::shared_ptr<PyMotion> MotionFromState(const LoadedModel& m, int order, bool si,
                                          const std::optional<std::vector<std::string>>& bodies,
                                          const std::optional<std::vector<std::string>>& outputs, bool forces,
                                          py::array_t<double, py::array::c_style | py::array::forcecast> values,
                                          bool complete, const std::string& stop, const std::string& message,
                                          const std::vector<std::string>& sensitivity) {
  auto out = std::make_shared<PyMotion>();
  out->model = m.model;
  TableOptions table = MakeTableOptions(order, si, bodies, outputs, forces);
  table.sensitivity = sensitivity;
  out->motion = std::make_unique<Motion>(MotionLayout(*m.model, table));
  if (values.ndim() != 2 || values.shape(1) != out->motion->cols()) throw py::value_error("values do not fit the layout");
  out->motion->mutable_values().assign(values.data(), values.data() + values.size());
  out->motion->complete = complete;
  out->motion->stop.kind = StopKind::SolveFailed;
  Parse(stop, &out->motion->stop.kind);
  out->motion->stop.message = message;
  out->motion->reductions = ComputeReductions(*out->model, *out->motion);  // the rows decide them
  return out;
}

py::list Columns(const PyMotion& pm) {
  py::list out;
  for (const auto& c : pm.motion->columns()) {
    py::dict d;
    d["name"] = c.name;
    d["unit"] = c.unit;
    d["quantity"] = ToString(c.quantity);
    d["subject"] = c.subject;
    d["component"] = c.component;
    d["order"] = c.order;
    // A sensitivity column names the parameter and the column it differentiates.
    const auto& params = pm.motion->layout().options().sensitivity;
    d["wrt"] = c.wrt >= 0 ? py::object(py::str(params[c.wrt])) : py::object(py::none());
    d["base"] = c.base >= 0 ? py::object(py::int_(c.base)) : py::object(py::none());
    out.append(d);
  }
  return out;
}

py::dict Report(const PyMotion& pm) {
  const Motion& m = *pm.motion;
  py::dict d;
  d["complete"] = m.complete;
  d["stop"] = ToString(m.stop.kind);
  d["message"] = m.stop.message;
  if (m.stop.singular) {
    py::dict s;
    s["t"] = m.stop.singular->t;
    s["driver_values"] = m.stop.singular->driver_values;
    s["joint_mobility"] = m.stop.singular->joint_mobility;
    s["involved"] = m.stop.singular->involved;
    d["singular"] = s;
  } else {
    d["singular"] = py::none();
  }
  if (m.report.limit) {
    py::dict l;
    l["t"] = m.report.limit->t;
    l["driver_values"] = m.report.limit->driver_values;
    l["fold"] = m.report.limit->fold;
    d["limit"] = l;
  } else {
    d["limit"] = py::none();
  }
  // First contacts of clearance outputs' bodies (analysis/contact_watch.hpp): the point
  // in the table's length unit, the driver values in SI (as the limit's).
  py::list contacts;
  for (const ContactHit& h : m.report.contacts) {
    py::dict c;
    c["t"] = h.t;
    c["output"] = h.output >= 0 ? py::object(py::str(pm.model->outputs[h.output].name)) : py::object(py::none());
    c["body1"] = pm.model->BodyName(h.body1);
    c["body2"] = pm.model->BodyName(h.body2);
    const double len = m.layout().length_factor();
    c["point"] = std::vector<double>{h.point.x() * len, h.point.y() * len, h.point.z() * len};
    c["clearance"] = h.clearance * len;
    c["at_start"] = h.at_start;
    c["driver_values"] = h.driver_values;
    contacts.append(c);
  }
  d["contacts"] = contacts;
  // The file's reductions (analysis/reduction_result.hpp), in the table's units.
  py::list reductions;
  for (const ReductionResult& r : m.reductions) {
    py::dict x;
    x["name"] = r.name;
    x["of"] = r.of;
    x["reduce"] = ReduceKindName(r.kind);
    x["value"] = r.value;
    x["unit"] = r.unit;
    x["t"] = r.t;
    x["located"] = r.located;
    py::dict g;
    for (size_t k = 0; k < r.wrt.size(); ++k) g[py::str(r.wrt[k])] = r.gradient[k];
    x["gradient"] = g;
    if (r.kind == ReduceKind::Sse) x["residuals"] = r.residuals;  // column − target per (t, column)
    x["problem"] = r.problem.empty() ? py::object(py::none()) : py::object(py::str(r.problem));
    reductions.append(x);
  }
  d["reductions"] = reductions;
  py::list reselections;
  for (const auto& r : m.report.reselections) reselections.append(py::make_tuple(r.t, r.set_aside));
  d["reselections"] = reselections;
  d["set_aside"] = m.report.set_aside;
  d["notes"] = m.report.notes;  // singular positions passed uniquely, one line each
  d["indeterminate_reactions"] = m.report.indeterminate_reactions;
  d["assembly_iterations"] = m.report.assembly_iterations;
  d["blocks"] = m.report.blocks;
  d["blocks_solved"] = m.report.blocks_solved;
  return d;
}

// rows × cols view of the core's buffer; `self` (the Python Motion) is its base.
py::array Values(py::object self) {
  const PyMotion& pm = self.cast<const PyMotion&>();
  const Motion& m = *pm.motion;
  const ssize_t rows = m.rows(), cols = m.cols();
  py::array a(py::dtype::of<double>(), {rows, cols}, {static_cast<ssize_t>(sizeof(double)) * cols, static_cast<ssize_t>(sizeof(double))},
              m.values().data(), self);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// `inputs`: files the table must not overwrite (the model's own file).
void ToTable(const PyMotion& pm, const std::string& path, const std::string& format,
             const std::vector<std::string>& inputs) {
  const TableFormat table_format = NamedOrThrow<TableFormat>("format", format);
  std::string why;
  bool ok;
  {
    py::gil_scoped_release release;
    ok = WriteMotion(*pm.motion, table_format, path, &why, inputs);
  }
  if (!ok) throw std::runtime_error(why);
}

// One sweep variant's summary (analysis/sweep.hpp), the GIL released while it runs;
// min/max per column of sweep_columns(order), in that order.
py::dict RunVariantSummary(const LoadedModel& lm, const ParameterOverrides& values, int order, double tol) {
  ValidateOrderAndTolerance(order, tol);
  SweepOptions options;
  options.request.order = order;
  options.request.tolerance = tol;
  VariantSummary v;
  const PythonInterrupt interrupt;
  options.request.interrupted = interrupt.Poll();
  {
    py::gil_scoped_release release;
    v = RunVariant(*lm.model, values, options);
  }
  interrupt.RethrowIfRaised();
  py::dict d, params;
  for (const auto& kv : values) params[py::str(kv.first)] = kv.second;
  d["parameters"] = params;
  d["status"] = v.status;
  d["message"] = v.message;
  d["rows"] = v.rows;
  d["t_stop"] = v.t_stop;
  d["max_condition"] = v.max_condition;
  d["t_max_condition"] = v.t_max_condition;
  d["min"] = v.min;
  d["max"] = v.max;
  return d;
}

// The summarised columns of a sweep: (names, units), the names as in a Motion of
// the same order (units separate, as Motion.units()).
py::tuple SweepColumnsOf(const LoadedModel& lm, int order) {
  ValidateOrderAndTolerance(order, 1e-10);
  std::vector<std::string> names, units;
  for (const ColumnDescriptor& c : SweepColumnDescriptors(*lm.model, order)) {
    names.push_back(c.name);
    units.push_back(c.unit);
  }
  return py::make_tuple(names, units);
}

// A dataset file of `variants`, the variants first + k·stride of a sweep of `total`
// (io/hdf5_dataset.hpp; mechkin.sweep(out=...) writes one per task), on `threads`, the
// GIL released: {status: count}. Raises ValueError for an unknown column or variants
// that vary different parameters, RuntimeError when the file cannot be written.
py::dict SweepDataset(const LoadedModel& lm, const std::vector<ParameterOverrides>& variants, int first, int stride,
                      int total, const std::vector<std::string>& curves, int order, double tol, int threads,
                      const std::string& path, const std::string& identity) {
  ValidateOrderAndTolerance(order, tol);
  ShardVariants shard;
  shard.total = total;
  if (!variants.empty())
    for (const auto& kv : variants.front()) shard.parameters.push_back(kv.first);
  for (size_t k = 0; k < variants.size(); ++k) {
    if (variants[k].size() != variants.front().size() ||
        !std::equal(variants[k].begin(), variants[k].end(), variants.front().begin(),
                    [](const auto& a, const auto& b) { return a.first == b.first; }))
      throw py::value_error("variant " + std::to_string(first + k * stride) +
                            " sets other parameters than the first: every variant must set the same ones");
    shard.Add(static_cast<int>(first + k * stride), variants[k]);
  }
  RunRequest request;
  request.order = order;
  request.tolerance = tol;
  const PythonInterrupt interrupt;
  request.interrupted = interrupt.Poll();
  CurveSelection selection;
  std::string why;
  if (!SelectCurves(*lm.model, request, curves, &selection, &why)) throw py::value_error(why);
  DatasetShape shape = ShapeOf(shard, selection);
  shape.first = first, shape.stride = stride;
  shape.identity = identity;
  shape.source = lm.source;
  std::map<std::string, int> statuses;
  bool ok = false;
  {
    py::gil_scoped_release release;
    DatasetWriter writer;
    ok = writer.Create(path, shape, &why) &&
         RunCurveSweep(*lm.model, shard, selection, threads, [&](VariantCurves&& v) {
           ++statuses[v.status];
           return writer.Write(v, &why);
         }) && writer.Finish(false, &why);
  }
  interrupt.RethrowIfRaised();
  int done = 0;
  for (const auto& kv : statuses) done += kv.second;
  if (!ok)
    throw std::runtime_error(why.empty() ? "the dataset sweep was interrupted after " + std::to_string(done) + " of " +
                                               std::to_string(variants.size()) + " variants"
                                         : why);
  py::dict out;
  for (const auto& [status, n] : statuses) out[py::str(status)] = n;
  return out;
}

// One dataset file over the parts (virtual datasets, io/hdf5_dataset.hpp).
void MergeDatasetParts(const std::vector<std::string>& parts, const std::string& out) {
  std::string why;
  bool ok;
  {
    py::gil_scoped_release release;
    ok = MergeDatasets(parts, out, &why);
  }
  if (!ok) throw std::runtime_error(why);
}

py::dict ModelInfo(const LoadedModel& lm) {
  const Model& m = *lm.model;
  py::dict d;
  d["name"] = m.name;
  d["source"] = lm.source;
  py::list bodies, joints, drivers, outputs;
  for (const auto& b : m.bodies) bodies.append(b.name);
  for (const auto& j : m.joints)
    joints.append(py::dict(py::arg("name") = j.name, py::arg("type") = j.type->name,
                           py::arg("body1") = m.BodyName(j.body1), py::arg("body2") = m.BodyName(j.body2)));
  py::list couplers;  // {name, type, joints}: the couplers between joint coordinates
  for (const auto& c : m.couplers) {
    py::list cj;
    for (const auto& cc : c.coordinates) cj.append(m.joints[cc.joint].name);
    couplers.append(py::dict(py::arg("name") = c.name, py::arg("type") = CouplerKindName(c.kind), py::arg("joints") = cj));
  }
  d["couplers"] = couplers;
  for (const auto& dr : m.drivers) drivers.append(dr.name);
  for (const auto& o : m.outputs) outputs.append(o.name);
  d["bodies"] = bodies;
  d["joints"] = joints;
  d["drivers"] = drivers;
  d["outputs"] = outputs;
  d["units"] = py::dict(py::arg("length") = m.units.length_name, py::arg("angle") = m.units.angle_name);
  d["warnings"] = DiagnosticList(lm.warnings);
  py::dict params;
  for (const auto& p : m.parameters) {
    py::dict e;
    e["value"] = p.value;
    e["tolerance"] = p.tolerance ? py::object(py::float_(*p.tolerance)) : py::object(py::none());
    e["min"] = p.min ? py::object(py::float_(*p.min)) : py::object(py::none());
    e["max"] = p.max ? py::object(py::float_(*p.max)) : py::object(py::none());
    e["expression"] = p.expression;
    params[py::str(p.name)] = e;
  }
  d["parameters"] = params;
  if (m.analysis)
    d["analysis"] = py::dict(py::arg("start") = m.analysis->start, py::arg("end") = m.analysis->end,
                             py::arg("steps") = m.analysis->steps);
  else
    d["analysis"] = py::none();
  return d;
}

}  // namespace

PYBIND11_MODULE(_mechkin, mod) {
  mod.doc() = "mechkin core (C++); use the `mechkin` package";
  BindRunRequest(mod);
  BindCheckReport(mod);
  mod.def("stop_all", [](bool stop) { StopAllFlag() = stop; },
          "While true, every running call of the core stops at its next step (a sweep's pool on Ctrl-C)");
  py::class_<LoadedModel, std::shared_ptr<LoadedModel>>(mod, "CoreModel", "A compiled model (mechkin.Model wraps it)")
      .def_readonly("text", &LoadedModel::text)
      .def_readonly("source", &LoadedModel::source)
      .def("info", &ModelInfo)
      .def("check", &CheckModel)
      .def("with_parameters", &ModelWithParameters, py::arg("values"))
      .def("optimize", &OptimizeModel, py::arg("vary"), py::arg("minimize"), py::arg("subject_to"), py::arg("starts"),
           py::arg("seed"), py::arg("max_iterations"), py::arg("order"), py::arg("tol"))
      .def("objective", &ObjectiveOfModel, py::arg("name"), py::arg("vary"), py::arg("values"), py::arg("order"),
           py::arg("tol"))
      .def("run", &RunModel, py::arg("request"), py::arg("start"), py::arg("end"), py::arg("steps"))
      .def_readonly("overrides", &LoadedModel::overrides)
      .def("run_variant", &RunVariantSummary, py::arg("values"), py::arg("order"), py::arg("tol"))
      .def("sweep_columns", &SweepColumnsOf, py::arg("order"))
      .def("sweep_dataset", &SweepDataset, py::arg("variants"), py::arg("first"), py::arg("stride"), py::arg("total"),
           py::arg("curves"), py::arg("order"), py::arg("tol"), py::arg("threads"), py::arg("path"),
           py::arg("identity"))
      .def("range", &RangeOfModel, py::arg("driver"), py::arg("steps"), py::arg("span"), py::arg("tol"))
      .def("tolerance", &ToleranceOfModel, py::arg("order"), py::arg("monte_carlo"), py::arg("seed"),
           py::arg("threads"), py::arg("tol"));
  py::class_<PyMotion, std::shared_ptr<PyMotion>>(mod, "CoreMotion", "A computed motion (mechkin.Motion wraps it)")
      .def_property_readonly("values", &Values)
      .def("columns", &Columns)
      .def("report", &Report)
      .def("write", &ToTable, py::arg("path"), py::arg("format") = "csv", py::arg("inputs") = std::vector<std::string>{})
      .def_property_readonly("order", [](const PyMotion& m) { return m.motion->layout().options().order; })
      .def_property_readonly("si", [](const PyMotion& m) { return m.motion->layout().options().si; })
      .def_property_readonly("forces", [](const PyMotion& m) { return m.motion->layout().options().forces; });
  mod.def("compile", &CompileText, py::arg("text"), py::arg("source"), py::arg("overrides") = ParameterOverrides{});
  mod.def("compile_file", &CompileFile, py::arg("path"), py::arg("overrides"), py::arg("drives"), py::arg("span"));
  mod.def("merge_dataset", &MergeDatasetParts, py::arg("parts"), py::arg("out"));
  mod.def("sweep_statuses", [] { return SweepStatusNames(); }, "status names in code order (a dataset's status)");
  mod.def("foreign_format", [](const std::string& path) { return importers::FormatName(ForeignFormatOf(path)); });
  mod.def("motion_from_state", &MotionFromState, py::arg("model"), py::arg("order"), py::arg("si"), py::arg("bodies"),
          py::arg("outputs"), py::arg("forces"), py::arg("values"), py::arg("complete"), py::arg("stop"),
          py::arg("message"), py::arg("sensitivity") = std::vector<std::string>{});
}
