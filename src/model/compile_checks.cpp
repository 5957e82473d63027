// The warning passes of a valid model (a slipped digit or unit) and the check
// that every driver can be evaluated over the analysis span.
#include <algorithm>
#include <cmath>
#include <limits>

#include "model/compiler.hpp"
#include "model/stray_points.hpp"

namespace mechkin {

void Compiler::WarnFarPoints() {
  struct Place { Vec3 p; std::string ptr; };
  std::vector<Place> pts;
  for (size_t b = 0; b < model_.bodies.size(); ++b)
    pts.push_back({model_.bodies[b].position, "/bodies/" + std::to_string(b) + "/position"});
  for (size_t j = 0; j < model_.joints.size(); ++j) {
    const Joint& jt = model_.joints[j];
    auto [r, A] = Pose(jt.body1);
    pts.push_back({r + A * jt.frame1.origin, "/joints/" + std::to_string(j) + (jt.type->frames == JointFrameRule::TwoPoints ? "/point1" : "/origin")});
  }
  if (pts.size() < 4) return;
  Vec3 middle;
  for (int a = 0; a < 3; ++a) {
    std::vector<double> c;
    for (const auto& q : pts) c.push_back(q.p[a]);
    std::nth_element(c.begin(), c.begin() + c.size() / 2, c.end());
    middle[a] = c[c.size() / 2];
  }
  std::vector<double> d;
  for (const auto& q : pts) d.push_back((q.p - middle).norm());
  std::vector<double> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double typical = sorted[sorted.size() / 2];
  if (!(typical > 0)) return;
  for (size_t k = 0; k < pts.size(); ++k)
    if (d[k] > 1000 * typical)
      Warn(pts[k].ptr, "this point is " + FormatNumber(d[k] / typical) + " times farther from the middle of the mechanism than its typical point",
               "check the number and the unit: a far point sets the characteristic length and so every tolerance");
}

// A unit slip: `2*pi*t` in a file whose angles are degrees turns 6.28°, not a turn.
void Compiler::WarnRadiansInDegrees(const Driver& drv, const std::string& ptr, double swing) {
  const bool angle = drv.kind == DriverKind::JointRotation || drv.kind == DriverKind::BodyRotation;
  const std::string text = drv.function.Describe();
  if (!angle || model_.units.angle_name != "deg" || drv.function.is_table() || !(swing < 10)) return;
  if (text.find("pi") == std::string::npos) return;
  Warn(ptr, "driver '" + drv.name + "' uses pi but swings only " + FormatNumber(swing) +
                    " deg over the analysis: the file's angles are degrees",
           "for a turn write 360*t (not 2*pi*t), or set \"units\": {\"angle\": \"rad\"}");
}

// A joint point far from every other joint point of both its bodies (1352 typed for
// 135.2): over 5 times the median of the other joints' link lengths.
void Compiler::WarnStrayJointPoints() {
  std::vector<JointEnds> ends(model_.joints.size());
  for (size_t j = 0; j < model_.joints.size(); ++j) {
    const Joint& jt = model_.joints[j];
    for (int side = 0; side < 2; ++side) {
      const BodyIndex b = side ? jt.body2 : jt.body1;
      auto [r, A] = Pose(b);
      ends[j].body[side] = b;
      ends[j].point[side] = r + A * (side ? jt.frame2.origin : jt.frame1.origin);
    }
  }
  // FindStrayJointPoints is n log n in the joints (the all-pairs form was cubic).
  for (const StrayJointPoint& s : FindStrayJointPoints(ends))
    Warn("/joints/" + std::to_string(s.joint), "joint '" + model_.joints[s.joint].name + "' lies " +
                                                   FormatNumber(s.nearest / s.typical) +
                                                   " times the other links' typical length from every other "
                                                   "joint of both its bodies",
         "check its coordinates (a slipped digit or unit)");
}

// A distance link 1000 times longer or shorter than the mechanism: a slipped unit or digit.
void Compiler::WarnOddLengths() {
  const double L = model_.characteristic_length;
  for (size_t j = 0; j < model_.joints.size(); ++j) {
    const Joint& jt = model_.joints[j];
    if (jt.type->scalar != JointScalar::Length || !(L > 0)) continue;
    if (jt.length > 1000 * L || jt.length < L / 1000)
      Warn("/joints/" + std::to_string(j), "distance link '" + jt.name + "' is " + FormatNumber(jt.length / length_) +
                                                   " " + model_.units.length_name + " long, " +
                                                   (jt.length > L ? "over 1000 times" : "under 1/1000 of") +
                                                   " the mechanism's size (" + FormatNumber(L / length_) + ")",
               "check the number and its unit");
  }
}

// Every driver function over the analysis span, on the table's own grid (at most
// 2001 points, both ends included): where it or one of its four derivatives is
// undefined or not finite, `run` could not go on, so the file is refused here.
// A driver that turns more than 90° (or moves more than the mechanism's size)
// between two rows gets a warning: the steps cannot follow it.
void Compiler::CheckDriverSpans() {
  if (!model_.analysis) return;
  const Analysis& an = *model_.analysis;
  const int points = std::min(an.steps, 2000);
  for (size_t d = 0; d < model_.drivers.size(); ++d) {
    const Driver& drv = model_.drivers[d];
    const std::string ptr = driver_pointers_[d] + "/function";
    const bool angle = drv.kind == DriverKind::JointRotation || drv.kind == DriverKind::BodyRotation;
    double worst_rate = 0, worst_t = an.start;
    double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
    for (int k = 0; k <= points; ++k) {
      const double t = k == points ? an.end : an.start + (an.end - an.start) * k / points;
      std::string why;
      try {
        const Jet j = drv.function.Eval(t);
        for (int o = 0; o <= kMaxOrder && why.empty(); ++o)
          if (!std::isfinite(j.c[o])) why = o == 0 ? "its value is not finite" : "its derivative of order " + std::to_string(o) + " is not finite";
        if (why.empty() && std::abs(j.c[1]) > worst_rate) { worst_rate = std::abs(j.c[1]); worst_t = t; }
        if (why.empty()) lowest = std::min(lowest, j.c[0]), highest = std::max(highest, j.c[0]);
      } catch (const std::exception& e) {
        why = e.what();
      }
      if (!why.empty()) {
        Error(ptr, "driver '" + drv.name + "' cannot be evaluated at t = " + FormatNumber(t) + " s of the analysis span: " + why,
                  "change the function, or start or end the analysis where it is defined (and differentiable)");
        break;
      }
    }
    WarnRadiansInDegrees(drv, ptr, (highest - lowest) / angle_);
    const double per_step = worst_rate * (an.end - an.start) / an.steps;
    const double limit = angle ? M_PI / 2 : model_.characteristic_length;
    if (per_step > limit)
      Warn(ptr, "driver '" + drv.name + "' moves " + FormatNumber(per_step / (angle ? angle_ : length_)) + " " +
                        (angle ? model_.units.angle_name : model_.units.length_name) + " between two rows near t = " +
                        FormatNumber(worst_t) + " s",
               "use more steps (analysis/steps) so that each step follows the motion");
  }
}

// Every force and torque component over the analysis span, on the grid of
// CheckDriverSpans: a component undefined or not finite at a row's time stops a run
// with forces there ("division by zero" and no place), so the file is refused here.
void Compiler::CheckLoadSpans() {
  if (!model_.analysis || model_.loads.size() != spec_.loads.size()) return;
  const Analysis& an = *model_.analysis;
  const int points = std::min(an.steps, 2000);
  for (size_t l = 0; l < model_.loads.size(); ++l) {
    const Load& load = model_.loads[l];
    if (load.kind == LoadKind::Spring) continue;
    for (int c = 0; c < 3; ++c) {
      std::string why;
      double t = an.start;
      for (int k = 0; k <= points && why.empty(); ++k) {
        t = k == points ? an.end : an.start + (an.end - an.start) * k / points;
        try {
          if (!std::isfinite(load.components[c].Eval(t).c[0])) why = "its value is not finite";
        } catch (const std::exception& e) {
          why = e.what();
        }
      }
      if (!why.empty())
        Error(spec_.loads[l].pointer + "/components/" + std::to_string(c),
              "load '" + load.name + "' cannot be evaluated at t = " + FormatNumber(t) + " s of the analysis span: " + why,
              "change the expression, or start or end the analysis where it is defined");
    }
  }
}

}  // namespace mechkin
