// `mechkin view --live` (issue 30): the page that re-solves in the browser. The
// WebAssembly core (tools/build_live.sh, src/io/live/) is inlined into the viewer
// page with the file's text and what the sliders need; src/io/viewer/live.js runs it.
#pragma once

#include <string>

#include "model/model.hpp"

namespace mechkin {

/// Where `view --live` reads the module: $MECHKIN_LIVE_MODULE when set, else the
/// build's build/live/mechkin_live.js (CMake's MECHKIN_LIVE).
std::string LiveModulePath();
/// The module's text; false with a message saying what is missing and how to build it.
bool ReadLiveModule(std::string* text, std::string* error);

/// The rows the live page re-solves: the file's steps + 1, at most `max_frames`.
int LiveSteps(const Model& model, int max_frames);

/// window.MECHKIN_LIVE's JSON: the file's text, the solved order, the steps, a slider
/// per number parameter (its min/max, else ±20 % of its value) and per driver (its
/// values along the run, file units).
std::string LiveData(const Model& model, const std::string& spec_text, int order, int max_frames);

}  // namespace mechkin
