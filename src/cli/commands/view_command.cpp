#include "cli/commands/view_command.hpp"

#include "analysis/run_request.hpp"
#include "cli/commands/load_for_command.hpp"
#include "cli/commands/request_options.hpp"
#include "io/output_file.hpp"
#include "io/viewer.hpp"

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
}

namespace {

std::string DefaultPage(const std::string& file) {
  std::string stem = file.substr(file.find_last_of('/') + 1);
  stem = stem.substr(0, stem.rfind('.'));
  return (stem.empty() ? "mechanism" : stem) + ".html";
}

}  // namespace

RunRequest ViewOptions::Request() const {
  RunRequest r = request;
  r.forces = no_forces ? ForcesChoice::Off : forces ? ForcesChoice::On : ForcesChoice::Auto;
  return r;
}

int RunView(const ViewOptions& o, std::ostream& out, std::ostream& err) {
  ParameterOverrides overrides;
  if (!ParseOverrides(o.set, &overrides, err)) return 2;
  const std::optional<Model> loaded = LoadForCommand(o.file, err, overrides);
  if (!loaded) return 1;
  const Model& model = *loaded;
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
  const Motion motion = RunMotion(model, request);
  const bool interrupted = motion.stop.kind == StopKind::Interrupted;
  if (!motion.complete) err << "mechkin view: " << o.file << ": " << motion.stop.message << "\n";
  if (motion.rows() == 0) return 1;  // nothing to show
  SceneOptions scene;
  scene.max_frames = o.max_frames;
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
