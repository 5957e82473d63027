#include "io/viewer_live.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#ifndef MECHKIN_LIVE_MODULE_PATH
#define MECHKIN_LIVE_MODULE_PATH ""
#endif

namespace mechkin {

std::string LiveModulePath() {
  const char* env = std::getenv("MECHKIN_LIVE_MODULE");
  return env && *env ? env : MECHKIN_LIVE_MODULE_PATH;
}

bool ReadLiveModule(std::string* text, std::string* error) {
  const std::string path = LiveModulePath();
  std::ifstream f(path, std::ios::binary);
  if (path.empty() || !f) {
    *error = "--live: the WebAssembly module " + (path.empty() ? std::string("mechkin_live.js") : path) +
             " is not there (not built yet, or this build leaves it out: CMake option MECHKIN_LIVE); install Debian's "
             "emscripten (apt-get install emscripten) and build it with tools/build_live.sh (or configure with "
             "-DMECHKIN_LIVE=ON and build), "
             "or point MECHKIN_LIVE_MODULE at a built mechkin_live.js";
    return false;
  }
  std::stringstream s;
  s << f.rdbuf();
  *text = s.str();
  return true;
}

int LiveSteps(const Model& model, int max_frames) {
  const int steps = model.analysis ? model.analysis->steps : 0;
  return std::max(1, std::min(steps, max_frames - 1));
}

namespace {

// A slider per number parameter: its min/max, else ±20 % of its value (±1 for 0).
nlohmann::json ParameterSliders(const Model& model) {
  nlohmann::json out = nlohmann::json::array();
  for (const Parameter& p : model.parameters) {
    if (!p.expression.empty()) continue;
    const double span = p.value != 0 ? 0.2 * std::abs(p.value) : 1.0;
    out.push_back({{"name", p.name}, {"value", p.value}, {"min", p.min.value_or(p.value - span)},
                   {"max", p.max.value_or(p.value + span)}, {"set", p.overridden}});
  }
  return out;
}

// A slider per driver: its value (file units) at the live run's times.
nlohmann::json DriverSliders(const Model& model, int steps) {
  nlohmann::json out = nlohmann::json::array();
  if (!model.analysis) return out;
  const Analysis& an = *model.analysis;
  for (const Driver& d : model.drivers) {
    const bool angle = d.kind == DriverKind::JointRotation || d.kind == DriverKind::BodyRotation;
    const double to_file = 1 / (angle ? model.units.angle_to_si : model.units.length_to_si);
    nlohmann::json values = nlohmann::json::array();
    for (int k = 0; k <= steps; ++k) values.push_back(d.function.Eval(an.start + k * ((an.end - an.start) / steps)).c[0] * to_file);
    out.push_back({{"name", d.name}, {"unit", angle ? model.units.angle_name : model.units.length_name}, {"values", values}});
  }
  return out;
}

}  // namespace

std::string LiveData(const Model& model, const std::string& spec_text, int order, int max_frames) {
  const int steps = LiveSteps(model, max_frames);
  nlohmann::json j = {{"spec", spec_text},
                      {"order", order},
                      {"steps", steps},
                      {"parameters", ParameterSliders(model)},
                      {"drivers", DriverSliders(model, steps)}};
  return j.dump();
}

}  // namespace mechkin
