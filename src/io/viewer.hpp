// `mechkin view`: the motion as one self-contained HTML page (three.js from
// Debian's libjs-three inlined, the scene and the table embedded; no network)
// and as a glTF 2.0 file (nodes with one keyframe animation per body).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/motion.hpp"

namespace mechkin {

/// What the scene draws, from the model alone: per body its points (joint,
/// output, driver, load points and the centre of mass, body coordinates).
struct SceneOptions {
  int max_frames = 2000;     // longer motions are decimated for the page
  std::string three_js_dir;  // where three.min.js and OrbitControls.js are; empty: the default
  // Drawn upwards: this when given (--up), else the file's "view"."up", else −gravity,
  // else y.
  std::optional<Vec3> up;
  // Panels of column names (--plots); empty: the file's "view"."plots", else its outputs.
  std::vector<std::vector<std::string>> plots;
  // `view --live` (io/viewer_live.hpp): the WebAssembly module's text and
  // window.MECHKIN_LIVE's JSON; both empty: the page plays its precomputed run.
  std::string live_module, live_data;
};

/// "a,b;c" (columns by name, ',' within a plot, ';' between plots) → panels;
/// false with a message naming the columns for an unknown name.
bool ParsePlots(const Motion& motion, const std::string& spec, std::vector<std::vector<std::string>>* panels,
                std::string* error);
/// Every name in `panels` a plottable column of `motion`; false with a message
/// "<where>: no column 'x'; the columns are: …" otherwise.
bool CheckPlots(const Motion& motion, const std::vector<std::vector<std::string>>& panels, const std::string& where,
                std::string* error);

class OutputFile;

/// The Motion must hold every body (TableOptions::all_bodies). `page`: opened
/// (io/output_file.hpp) before the work; committed here, dropped on an error.
bool WriteViewerHtml(const Model& model, const Motion& motion, const SceneOptions& options, OutputFile* page,
                     std::string* error);
/// .glb (binary) or .gltf (JSON with the buffer embedded), lengths in metres;
/// `path` says which (its extension), `file` (opened on it) receives it.
bool WriteGltf(const Model& model, const Motion& motion, const std::string& path, OutputFile* file, std::string* error);

/// Default location of Debian's libjs-three.
std::string DefaultThreeJsDir();

}  // namespace mechkin
