// `mechkin view FILE`: runs the analysis and writes an animated 3D page (and a glTF file).
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/run_request.hpp"
#include "cli/commands/foreign.hpp"

namespace mechkin {

struct ViewOptions {
  std::string file;
  std::string output;          // -o; default: the file's stem + .html
  std::string gltf;            // --gltf: .glb or .gltf
  RunRequest request = DefaultViewRequest();  // --order (default 2), --tol, --solver
  int max_frames = 2000;
  bool forces = false, no_forces = false;
  bool live = false;          // --live: the page re-solves in the browser (io/viewer_live.hpp)
  bool keep_partial = false;  // SIGINT writes the page of the rows so far (the stop marked), exit 130
  /// `request` with the forces choice.
  RunRequest Request() const;
  static RunRequest DefaultViewRequest() {
    RunRequest r;
    r.order = 2;  // the plots: positions, velocities, accelerations
    r.keep_step_diagnostics = false;
    return r;
  }
  std::vector<std::string> set;  // --set NAME=NUMBER, as `run`
  std::string up;                // --up x|y|z (empty: the file's view.up, else against gravity, else y)
  std::string plots;             // --plots "a,b;c": panels of columns
  ForeignOptions foreign;        // --drive, --span: for an imported file
};

void SetupViewCommand(CLI::App& app, ViewOptions* options);
int RunView(const ViewOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
