// The events a run's plots mark (the viewer's page and the live page alike).
#pragma once

#include <string>
#include <vector>

#include "analysis/motion.hpp"
#include "model/model.hpp"

namespace mechkin {

struct PlotMark {
  double t = 0;        // s
  std::string kind;    // reselection, singular, limit, contact, stop
  std::string label;   // what the legend says
};

/// Where a partial run stopped: its singular position, else its last row's time (s).
double StopTime(const Motion& m);

/// Re-selections of the redundant equations, a singular position or limit of motion,
/// first contacts (naming the bodies) and, for a partial run, where it stopped.
std::vector<PlotMark> PlotMarks(const Model& model, const Motion& m);

}  // namespace mechkin
