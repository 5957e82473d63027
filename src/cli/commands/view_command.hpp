// `mechkin view FILE`: runs the analysis and writes an animated 3D page (and a glTF file).
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace mechkin {

struct ViewOptions {
  std::string file;
  std::string output;          // -o; default: the file's stem + .html
  std::string gltf;            // --gltf: .glb or .gltf
  int order = 2;
  double tolerance = 1e-10;
  std::string solver = "newton";
  int max_frames = 2000;
  bool forces = false, no_forces = false;
  std::vector<std::string> set;  // --set NAME=NUMBER, as `run`
  std::string up = "y";          // --up x|y|z when the file has no gravity
  std::string plots;             // --plots "a,b;c": panels of columns
};

void SetupViewCommand(CLI::App& app, ViewOptions* options);
int RunView(const ViewOptions& options, std::ostream& out, std::ostream& err);

}  // namespace mechkin
