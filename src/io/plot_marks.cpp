#include "io/plot_marks.hpp"

namespace mechkin {

double StopTime(const Motion& m) {
  return m.stop.singular ? m.stop.singular->t : (m.rows() ? m.at(m.rows() - 1, 0) : 0);
}

std::vector<PlotMark> PlotMarks(const Model& model, const Motion& m) {
  std::vector<PlotMark> marks;
  for (const Reselection& r : m.report.reselections) marks.push_back({r.t, "reselection", "redundant equations re-selected"});
  const auto& singular = m.stop.singular ? m.stop.singular : m.report.singular;
  if (singular) marks.push_back({singular->t, "singular", "singular position"});
  if (m.report.limit) marks.push_back({m.report.limit->t, "limit", "limit of motion"});
  for (const ContactHit& hit : m.report.contacts)
    marks.push_back({hit.t, "contact",
                     "first contact of `" + model.BodyName(hit.body1) + "` and `" + model.BodyName(hit.body2) + "`"});
  if (!m.complete) marks.push_back({StopTime(m), "stop", "run stopped"});
  return marks;
}

}  // namespace mechkin
