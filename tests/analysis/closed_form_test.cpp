// The driven analysis against closed forms (issue: driven kinematic analysis).
// Closed forms are differentiated with the test-only Taylor jets of
// tests/constraints/test_jet.hpp, independent of the code under test.
#include <gtest/gtest.h>

#include <map>

#include "../constraints/test_jet.hpp"
#include "analysis/kinematic_analysis.hpp"
#include "analysis/load.hpp"
#include "analysis/motion.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace closed_form_test {

using testing::TJet;

Model Load(const std::string& name) {
  LoadResult r = LoadMechanismFile(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/" + name);
  EXPECT_TRUE(r.ok()) << name;
  return std::move(*r.model);
}

// Runs the analysis and returns the table (SI units) as column name → values.
struct Table {
  std::map<std::string, std::vector<double>> col;
  AnalysisReport report;
  const std::vector<double>& operator[](const std::string& name) const {
    auto it = col.find(name);
    if (it == col.end()) throw std::out_of_range("no column " + name);
    return it->second;
  }
};

Table RunTable(const Model& m, AnalysisOptions opt = {}) {
  TableOptions topt;
  topt.order = opt.order;
  topt.si = true;
  MotionRecorder table(m, topt);
  Table out;
  out.report = RunKinematicAnalysis(m, opt, [&](const SystemState& s, const StepDiagnostics& d) {
    return table.Record(s, d);
  });
  for (size_t c = 0; c < testing_files::HeaderOf(table.motion()).size(); ++c) {
    std::string name = testing_files::HeaderOf(table.motion())[c].substr(0, testing_files::HeaderOf(table.motion())[c].find(" ["));
    for (const auto& row : testing_files::RowsOf(table.motion())) out.col[name].push_back(row[c]);
  }
  return out;
}

// Relative error against a reference series, scaled by the series' magnitude.
double MaxRelErr(const std::vector<double>& got, const std::vector<double>& want) {
  double scale = 0, err = 0;
  for (double w : want) scale = std::max(scale, std::abs(w));
  for (size_t k = 0; k < got.size(); ++k) err = std::max(err, std::abs(got[k] - want[k]));
  return err / scale;
}

TJet CrankAngle(double theta0, double omega, double t) {
  TJet th(theta0 + omega * t);
  th.c[1] = omega;
  return th;
}

// Offset slider-crank R-R-R-P (3 redundant equations): x = a cosθ + √(b² − (a sinθ − e)²).
TEST(ClosedForm, OffsetSliderCrankPiston) {
  const Model m = Load("offset-slider-crank.json");
  const Table tab = RunTable(m);
  ASSERT_TRUE(tab.report.complete) << tab.report.message;
  EXPECT_EQ(tab.report.set_aside.size(), 3u);
  const double a = 0.040, b = 0.120, e = 0.010, th0 = M_PI / 6, w = 2 * M_PI;
  std::vector<double> want[4];
  for (double t : tab["t"]) {
    const TJet th = CrankAngle(th0, w, t);
    const TJet s = testing::Sin(th), c = testing::Cos(th);
    const TJet x = a * c + testing::Sqrt(TJet(b * b) - (a * s - TJet(e)) * (a * s - TJet(e)));
    for (int k = 0; k < 4; ++k) want[k].push_back(x.D(k));
  }
  ASSERT_GE(want[0].size(), 100u);
  const char* cols[] = {"piston.x", "piston.x_t", "piston.x_tt", "piston.x_ttt"};
  for (int k = 0; k < 4; ++k) EXPECT_LT(MaxRelErr(tab[cols[k]], want[k]), 1e-9) << cols[k];
  // Redundant equations stay satisfied every step.
  for (const auto& s : tab.report.steps) EXPECT_LT(s.set_aside_residual, 1e-10);
}

// Spatial slider-crank R-S-U-P: x = a cosθ + √(b² − (e_y − a sinθ)² − e_z²).
TEST(ClosedForm, SpatialSliderCrankPiston) {
  const Model m = Load("spatial-slider-crank.json");
  const Table tab = RunTable(m);
  ASSERT_TRUE(tab.report.complete) << tab.report.message;
  const double a = 0.10, b = 0.30, ey = 0.02, ez = 0.05, w = 2 * M_PI;
  std::vector<double> want[4];
  for (double t : tab["t"]) {
    const TJet th = CrankAngle(0, w, t);
    const TJet s = testing::Sin(th), c = testing::Cos(th);
    const TJet dy = TJet(ey) - a * s;
    const TJet x = a * c + testing::Sqrt(TJet(b * b - ez * ez) - dy * dy);
    for (int k = 0; k < 4; ++k) want[k].push_back(x.D(k));
  }
  const char* cols[] = {"piston.x", "piston.x_t", "piston.x_tt", "piston.x_ttt"};
  for (int k = 0; k < 4; ++k) EXPECT_LT(MaxRelErr(tab[cols[k]], want[k]), 1e-9) << cols[k];
}

// Planar four-bar crank-rocker: rocker angle from the closed-form solution of
// Freudenstein's loop equation (intersection of the coupler and rocker circles).
TEST(ClosedForm, FourBarRockerFreudenstein) {
  const Model m = Load("planar-four-bar.json");
  AnalysisOptions opt;
  opt.order = 4;
  const Table tab = RunTable(m, opt);
  ASSERT_TRUE(tab.report.complete) << tab.report.message;
  const double a = 0.040, b = 0.120, c = 0.080, d = 0.100, w = 2 * M_PI;
  auto rocker = [&](const TJet& th) {
    const TJet bx = a * testing::Cos(th), by = a * testing::Sin(th);
    const TJet dx = TJet(d) - bx, dy = TJet(0.0) - by;
    const TJet dist = testing::Sqrt(dx * dx + dy * dy);
    const TJet al = (TJet(b * b - c * c) + dist * dist) / (2.0 * dist);
    const TJet h = testing::Sqrt(TJet(b * b) - al * al);
    const TJet cx = bx + (al * dx - h * dy) / dist, cy = by + (al * dy + h * dx) / dist;
    return testing::Angle(cy, cx - TJet(d));
  };
  const double phi0 = rocker(CrankAngle(M_PI / 3, 0, 0)).c[0];
  std::vector<double> want[5];
  for (double t : tab["t"]) {
    TJet phi = rocker(CrankAngle(M_PI / 3, w, t));
    phi.c[0] = std::remainder(phi.c[0] - phi0, 2 * M_PI);
    for (int k = 0; k < 5; ++k) want[k].push_back(phi.D(k));
  }
  const char* cols[] = {"rocker_angle", "rocker_angle_t", "rocker_angle_tt", "rocker_angle_ttt", "rocker_angle_tttt"};
  for (int k = 0; k < 4; ++k) EXPECT_LT(MaxRelErr(tab[cols[k]], want[k]), 1e-9) << cols[k];
  EXPECT_LT(MaxRelErr(tab[cols[4]], want[4]), 1e-8) << "snap";
}

// Hooke joint at β = 30°: tan θ2 = cos β tan θ1, speed ratio cos β / (1 − sin²β sin²θ1).
TEST(ClosedForm, HookeJoint) {
  const Model m = Load("hooke-joint-30deg.json");
  const Table tab = RunTable(m);
  ASSERT_TRUE(tab.report.complete) << tab.report.message;
  const double beta = M_PI / 6, w = 2 * M_PI;
  double ref = 0;
  std::vector<double> angle, ratio;
  for (double t : tab["t"]) {
    const double th1 = w * t;
    ref = UnwrapAngle(std::cos(beta) * std::sin(th1), std::cos(th1), ref);
    angle.push_back(ref);
    ratio.push_back(std::cos(beta) / (1 - std::pow(std::sin(beta) * std::sin(th1), 2)));
  }
  EXPECT_LT(MaxRelErr(tab["output_angle"], angle), 1e-10);
  std::vector<double> got_ratio;
  for (double v : tab["output_angle_t"]) got_ratio.push_back(v / w);
  EXPECT_LT(MaxRelErr(got_ratio, ratio), 1e-10);
}

// Screw jack: over 10 turns the nut moves pitch × turns. The thread is right-handed
// (positive pitch): the nut turns −θ relative to the screw, so it moves by −pitch per turn.
TEST(ClosedForm, ScrewJackPitchTimesTurns) {
  const Model m = Load("screw-jack.json");
  const Table tab = RunTable(m);
  ASSERT_TRUE(tab.report.complete) << tab.report.message;
  const auto& lift = tab["lift"];
  const auto& turns = tab["turns"];
  EXPECT_NEAR(turns.back(), 10 * 2 * M_PI, 1e-9);
  for (size_t k = 0; k < lift.size(); ++k) EXPECT_NEAR(lift[k], -0.005 * turns[k] / (2 * M_PI), 1e-13);
  EXPECT_NEAR(lift.back(), -0.050, 1e-12);
}

TEST(Formulations, OmegaAndPGiveTheSameTable) {
  for (const char* file : {"spatial-slider-crank.json", "bennett-linkage.json", "planar-xy-table.json"}) {
    const Model m = Load(file);
    AnalysisOptions o;
    o.order = 4;
    const Table a = RunTable(m, o);
    o.formulation = Formulation::P;
    const Table b = RunTable(m, o);
    ASSERT_TRUE(a.report.complete && b.report.complete) << file;
    // Relative to the largest value of the same kind and order in the table, so that
    // columns that are zero by symmetry (z of a planar motion) compare sensibly.
    auto kind = [](const std::string& name) {  // derivative order and angular/linear
      const auto us = name.find("_t");
      const std::string order = us == std::string::npos ? "" : name.substr(us);
      const auto dot = name.rfind('.');
      const bool angular = dot != std::string::npos && name[dot + 1] == 'w';
      const bool euler = dot != std::string::npos && name[dot + 1] == 'e' && name.size() == dot + 3;
      return (euler ? "e" : angular ? "w" : "x") + order;
    };
    std::map<std::string, double> scale;
    for (const auto& [name, values] : a.col)
      for (double v : values) scale[kind(name)] = std::max(scale[kind(name)], std::abs(v));
    for (const auto& [name, values] : a.col) {
      if (name == "newton_iterations" || name == "residual" || name == "t" || name == "condition" ||
          name.rfind("error_bound", 0) == 0)
        continue;
      double err = 0;
      for (size_t k = 0; k < values.size(); ++k) err = std::max(err, std::abs(b[name][k] - values[k]));
      EXPECT_LT(err / std::max(scale[kind(name)], 1e-6), 1e-10) << file << " " << name;  // floor: zero columns agree to 1e-16 SI
    }
  }
}

TEST(Solvers, CeresAndNewtonAgree) {
  for (const char* file : {"spatial-slider-crank.json", "bennett-linkage.json", "offset-slider-crank.json",
                           "spatial-four-bar-rusr.json"}) {
    const Model m = Load(file);
    AnalysisOptions o;
    const Table a = RunTable(m, o);
    o.solver = PositionSolver::Ceres;
    const Table b = RunTable(m, o);
    ASSERT_TRUE(a.report.complete && b.report.complete) << file << ": " << b.report.message;
    // Both satisfy the scaled residual ≤ tol = 1e-10, so positions may differ by up
    // to cond(Φ_q) · tol · L (lengths) or cond · tol (angles).
    double cond = 0;
    for (const auto& st : a.report.steps) cond = std::max(cond, st.condition);
    for (const auto& [name, values] : a.col) {
      if (name == "newton_iterations" || name == "residual" || name == "condition" || name.rfind("error_bound", 0) == 0 ||
          name.find(".e") != std::string::npos)
        continue;
      if (name.find("_t") != std::string::npos || name.find(".w") != std::string::npos) continue;  // positions only
      const bool angle = name.find("angle") != std::string::npos;
      double err = 0;
      for (size_t k = 0; k < values.size(); ++k) err = std::max(err, std::abs(b[name][k] - values[k]));
      EXPECT_LT(err, cond * 1e-10 * (angle ? 1.0 : m.characteristic_length)) << file << " " << name;
    }
  }
}

// A crank turned 1000 times reads 2000π: angles are continuous, never wrapped.
TEST(Angles, ThousandTurnsReadContinuously) {
  Model m = Load("planar-four-bar.json");
  m.analysis = Analysis{};
  m.analysis->end = 1000;
  m.analysis->steps = 8000;
  Output crank_angle;
  crank_angle.name = "crank_angle";
  crank_angle.kind = OutputKind::JointCoordinate;
  crank_angle.body2 = 0;
  crank_angle.joint = 0;
  m.outputs.push_back(crank_angle);
  AnalysisOptions o;
  o.order = 1;
  const Table tab = RunTable(m, o);
  ASSERT_TRUE(tab.report.complete) << tab.report.message;
  EXPECT_NEAR(tab["crank_angle"].back(), 2000 * M_PI, 1e-8);
  // The rocker returns to its starting angle after each revolution.
  EXPECT_NEAR(tab["rocker_angle"].back(), 0.0, 1e-9);
}

}  // namespace
}  // namespace mechkin
