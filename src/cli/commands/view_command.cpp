#include "cli/commands/view_command.hpp"

#include <cmath>

#include "analysis/run_request.hpp"
#include "cli/commands/load_for_command.hpp"
#include "cli/commands/request_options.hpp"
#include "io/output_file.hpp"
#include "io/viewer.hpp"
#include "io/viewer_live.hpp"
#include "model/loader.hpp"

namespace mechkin {

void SetupViewCommand(CLI::App& app, ViewOptions* o) {
  CLI::App* cmd = app.add_subcommand("view", "Run the analysis and write an animated 3D page with plots (and glTF)");
  cmd->add_option("file", o->file, "Mechanism file")->required();
  cmd->add_option("-o,--output", o->output, "The page (default: FILE's name with .html, in the current folder)");
  cmd->add_option("--gltf", o->gltf, "Also write the scene and its animation as glTF 2.0 (.glb or .gltf)");
  AddOrderOption(cmd, &o->request, "Highest time derivative (plots; default 2)");
  AddToleranceOption(cmd, &o->request, "Position tolerance (default 1e-10)");
  AddSolverOption(cmd, &o->request);
  cmd->add_option("--max-frames", o->max_frames, "Rows shown in the page (longer runs are decimated)")->check(CLI::Range(2, 1000000));
  cmd->add_flag("--forces", o->forces,
                "Also compute efforts and reactions (default when the file has inertia or loads; solved with "
                "accelerations whatever --order shows)");
  cmd->add_flag("--no-forces", o->no_forces, "Kinematics only");
  cmd->add_option("--set", o->set, "Parameter value replacing the file's: NAME=NUMBER (repeatable)");
  cmd->add_option("--up", o->up, "Axis drawn upwards (default: the file's view.up, else against gravity, else y)")->check(CLI::IsMember({"x", "y", "z"}));
  cmd->add_option("--plots", o->plots, "Plotted columns: names separated by ',' within a plot, ';' between plots");
  AddKeepPartialOption(cmd, &o->keep_partial, "the page of the rows computed");
  cmd->add_flag("--live", o->live,
                "A live page: sliders for the parameters and drivers, the mechanism re-solved in the browser "
                "(WebAssembly core, offline); needs the module tools/build_live.sh builds");
  AddForeignOptions(cmd, &o->foreign);
}

namespace {

std::string DefaultPage(const std::string& file) {
  std::string stem = file.substr(file.find_last_of('/') + 1);
  stem = stem.substr(0, stem.rfind('.'));
  return (stem.empty() ? "mechanism" : stem) + ".html";
}

// Keeps only the rows the page shows, as the run makes them: the max_frames evenly
// spaced rows of the planned run (io/viewer.cpp Frames: index round(k (N−1)/(M−1)),
// first and last included) and, for a run that stops early, its last row. A 1e7-step
// view so holds ~2000 rows instead of the whole table (the glTF, a keyframe per row,
// still takes the whole motion). A complete run gives the page it gave before.
class PageRowSink : public RowSink {
 public:
  PageRowSink(Motion* motion, long long planned_rows, int max_frames)
      : motion_(motion), planned_(planned_rows), frames_(std::max(2, max_frames)), last_(motion->cols()) {}
  bool Append(const double* row, int size) override {
    const bool keep = planned_ <= frames_ || index_ == Target();
    if (keep) {
      motion_->Append(row, size);
      ++frame_;
    } else {
      std::copy(row, row + size, last_.begin());
    }
    pending_ = !keep;
    ++index_;
    return true;
  }
  /// The stop row of a run that ended between two kept rows.
  void Finish() {
    if (pending_) motion_->Append(last_.data(), static_cast<int>(last_.size()));
  }

 private:
  long long Target() const { return std::llround(double(frame_) * (planned_ - 1) / (frames_ - 1)); }
  Motion* motion_;
  long long planned_, index_ = 0, frame_ = 0;
  int frames_;
  std::vector<double> last_;
  bool pending_ = false;
};

// The run for the page alone (no glTF): only the page's rows kept (PageRowSink).
Motion RunForPage(const Model& model, const RunRequest& request, int max_frames) {
  const RunPlan plan = PlanRun(model, request);
  Motion motion{MotionLayout(model, plan.table)};
  PageRowSink sink(&motion, model.analysis ? model.analysis->steps + 1LL : 0, max_frames);
  motion.report = RunIntoSink(model, plan.analysis, motion.layout(), &sink);
  sink.Finish();
  motion.complete = motion.report.complete;
  motion.stop = StopOf(motion.report);
  return motion;
}

// `--live`: the module and the file's own text (a format-v1 file: the page compiles it
// as `--set` does), or false with the reason printed. Checked before anything is written.
bool PrepareLive(const ViewOptions& o, const importers::ImportOptions& foreign, std::string* module, std::string* text,
                 std::ostream& err) {
  std::string why;
  if (!ReadLiveModule(module, &why)) {
    err << "mechkin view: " << why << "\n";
    return false;
  }
  Diagnostic problem;
  if (!ReadMechanismFileText(o.file, text, &problem)) {
    err << "mechkin view: " << o.file << ": " << problem.ToString() << "\n";
    return false;
  }
  if (importers::DetectForeignFormat(o.file, text->substr(0, 4096)) != importers::ForeignFormat::None ||
      !foreign.drives.empty()) {
    err << "mechkin view: --live: " << o.file << " is not a mechkin file; the live page compiles format-v1 files: "
        << "convert it first (mechkin import " << o.file << " -o FILE.json) and view that\n";
    return false;
  }
  return true;
}

// What the live page's core leaves out (src/io/live/live_stubs.cpp) refused before
// anything is written, by place: clearance outputs (FCL is not in the module).
bool LiveCanRun(const ViewOptions& o, const Model& model, std::ostream& err) {
  for (size_t i = 0; i < model.outputs.size(); ++i) {
    if (model.outputs[i].kind != OutputKind::Clearance) continue;
    err << "mechkin view: --live: " << o.file << ": output `" << model.outputs[i].name
        << "`: the live page cannot measure clearance outputs (FCL is not in its WebAssembly core); "
        << "view the file without --live, or remove its clearance outputs for the live page\n";
    return false;
  }
  return true;
}

}  // namespace

RunRequest ViewOptions::Request() const {
  RunRequest r = request;
  r.forces = no_forces ? ForcesChoice::Off : forces ? ForcesChoice::On : ForcesChoice::Auto;
  return r;
}

int RunView(const ViewOptions& o, std::ostream& out, std::ostream& err) {
  ParameterOverrides overrides;
  importers::ImportOptions foreign;
  if (!ParseOverrides(o.set, &overrides, err) || !ParseForeignOptions(o.foreign, &foreign, err)) return 2;
  const std::optional<Model> loaded = LoadForCommand(o.file, err, overrides, foreign);
  if (!loaded || !ForeignHasDrives(o.file, foreign, *loaded, "view", err)) return 1;
  const Model& model = *loaded;
  std::string live_module, live_text;
  if (o.live && (!LiveCanRun(o, model, err) || !PrepareLive(o, foreign, &live_module, &live_text, err))) return 1;
  RunRequest request = o.Request();
  std::string why;
  if (!request.IsValid(&why)) {
    err << "mechkin view: " << why << "\n";
    return 2;
  }
  // The destinations first: refused (the input, one path twice, unwritable) before the run.
  const std::string page = o.output.empty() ? DefaultPage(o.file) : o.output;
  OutputFile page_file, gltf_file;
  if (!DistinctOutputs({page, o.gltf}, {"-o", "--gltf"}, &why) || !page_file.Open(page, {o.file}, &why, nullptr, "the page") ||
      (!o.gltf.empty() && !gltf_file.Open(o.gltf, {o.file}, &why, nullptr, "the glTF scene"))) {
    err << "mechkin view: " << why << "\n";
    return 1;
  }
  request.interrupted = InstallInterruptPoll(o.keep_partial);
  const Motion motion = o.gltf.empty() ? RunForPage(model, request, o.max_frames) : RunMotion(model, request);
  const bool interrupted = motion.stop.kind == StopKind::Interrupted;
  if (!motion.complete) err << "mechkin view: " << o.file << ": " << motion.stop.message << "\n";
  if (motion.rows() == 0) return 1;  // nothing to show
  SceneOptions scene;
  scene.max_frames = o.max_frames;
  if (o.live) {
    scene.live_module = std::move(live_module);
    // The page re-solves as `mechkin run` does (its default order 3, or the view's when higher).
    scene.live_data = LiveData(model, live_text, std::max(request.order, RunRequest().order), o.max_frames);
  }
  if (!o.up.empty()) scene.up = o.up == "x" ? Vec3::UnitX() : o.up == "z" ? Vec3::UnitZ() : Vec3::UnitY();
  if (!o.plots.empty() && !ParsePlots(motion, o.plots, &scene.plots, &why)) {
    err << "mechkin view: " << why << "\n";
    return 2;
  }
  if (!WriteViewerHtml(model, motion, scene, &page_file, &why)) {
    err << "mechkin view: " << why << "\n";
    return 1;
  }
  out << "page written to " << page << (motion.complete ? "" : " (partial motion: the stop is marked)") << "\n";
  if (!o.gltf.empty()) {
    if (!WriteGltf(model, motion, o.gltf, &gltf_file, &why)) {
      err << "mechkin view: " << why << "\n";
      return 1;
    }
    out << "glTF written to " << o.gltf << "\n";
  }
  return motion.complete ? 0 : interrupted ? kInterruptedExit : 1;
}

}  // namespace mechkin
