// The run request (analysis/run_request.hpp): one valid range per field with one
// message, the forces policy decided once, and the enum names in one header.
#include "analysis/run_request.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "analysis/enum_names.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace run_request_test {

using nlohmann::json;

// The bundled four-bar with masses and gravity (as in forces_test.cpp): a file
// that computes forces by default.
json FourBarWithInertia() {
  json j = testing_files::ReadJson("planar-four-bar.json");
  j["units"]["mass"] = "kg";
  j["gravity"] = {0, -9810, 0};  // mm/s²
  for (auto& b : j["bodies"])
    b["inertia"] = {{"mass", 1.5}, {"center", b["position"]}, {"moments", {{200, 0, 0}, {0, 300, 0}, {0, 0, 400}}}};
  j["analysis"]["steps"] = 24;
  return j;
}

TEST(RunRequest, ToleranceHasOneRangeAndOneMessage) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case { double tol; bool valid; const char* shown; };
  for (const Case c : {Case{1e-16, false, "1e-16"}, Case{1e-15, true, ""}, Case{1e-10, true, ""},
                       Case{1e-3, true, ""}, Case{5e-3, false, "0.005"}, Case{0, false, "0"},
                       Case{-1, false, "-1"}, Case{nan, false, "nan"}}) {
    RunRequest r;
    r.tolerance = c.tol;
    std::string why;
    EXPECT_EQ(r.IsValid(&why), c.valid) << c.tol;
    if (!c.valid) {
      EXPECT_EQ(why, RunRequest::ToleranceProblem(c.shown)) << why;
    }
  }
  EXPECT_NE(RunRequest::ToleranceProblem("x").find("[1e-15, 1e-3]"), std::string::npos);
}

TEST(RunRequest, OrderIsZeroToFour) {
  for (int order = -1; order <= 5; ++order) {
    RunRequest r;
    r.order = order;
    std::string why;
    EXPECT_EQ(r.IsValid(&why), order >= 0 && order <= 4) << order;
    if (order < 0 || order > 4) {
      EXPECT_EQ(why, RunRequest::OrderProblem(std::to_string(order)));
    }
  }
}

TEST(RunRequest, SensitivitiesNeedTheDefaultSolver) {
  RunRequest r;
  r.sensitivity = {"crank"};
  std::string why;
  EXPECT_TRUE(r.IsValid(&why));
  r.formulation = Formulation::P;
  EXPECT_FALSE(r.IsValid(&why));
  EXPECT_NE(why.find("omega, newton"), std::string::npos) << why;
}

TEST(RunRequest, ForcesRaiseTheSolvedOrderNotTheShownOne) {
  EXPECT_EQ(SolvedOrder(0, true), 2);
  EXPECT_EQ(SolvedOrder(1, true), 2);
  EXPECT_EQ(SolvedOrder(3, true), 3);
  EXPECT_EQ(SolvedOrder(1, false), 1);
  const Model with = testing_files::FromJson(FourBarWithInertia());
  const Model without = testing_files::FromJson(testing_files::ReadJson("planar-four-bar.json"));
  RunRequest r;
  r.order = 1;
  const RunPlan plan = PlanRun(with, r);
  EXPECT_EQ(plan.table.order, 1);
  EXPECT_TRUE(plan.table.forces);
  EXPECT_EQ(plan.analysis.order, 2);
  EXPECT_TRUE(plan.analysis.forces);
  EXPECT_FALSE(PlanRun(without, r).table.forces);
  EXPECT_EQ(PlanRun(without, r).analysis.order, 1);
  r.forces = ForcesChoice::Off;
  EXPECT_FALSE(PlanRun(with, r).table.forces);
  EXPECT_EQ(PlanRun(with, r).analysis.order, 1);
}

// --order 1 on a file with inertia: the derivative columns of order 1 and the force
// columns, whose numbers are exactly those of an --order 2 run (the same solve).
TEST(RunRequest, OrderOneWithInertiaShowsTheForcesOfAnOrderTwoRun) {
  const Model model = testing_files::FromJson(FourBarWithInertia());
  RunRequest r;
  r.order = 1;
  const Motion one = RunMotion(model, r);
  r.order = 2;
  const Motion two = RunMotion(model, r);
  ASSERT_TRUE(one.complete) << one.stop.message;
  ASSERT_TRUE(two.complete) << two.stop.message;
  ASSERT_EQ(one.rows(), two.rows());
  int force_columns = 0;
  for (int c = 0; c < one.cols(); ++c) {
    const ColumnDescriptor& d = one.columns()[c];
    EXPECT_LE(d.order, 1) << d.name;
    const int in_two = two.layout().Find(d.name);
    ASSERT_GE(in_two, 0) << d.name;  // every order-1 column is in the order-2 table
    if (d.quantity < Quantity::DriverEffort || d.quantity > Quantity::EnergyBalance) continue;
    ++force_columns;
    for (int row = 0; row < one.rows(); ++row) ASSERT_EQ(one.at(row, c), two.at(row, in_two)) << d.name << " row " << row;
  }
  // 1 driver (effort, power) + 4 joints × 12 reaction components + 3 energies.
  EXPECT_EQ(force_columns, 2 + 4 * 12 + 3);
  // The effort is a real number: the crank is held against gravity.
  const int effort = one.layout().Find(model.drivers[0].name + ".effort");
  ASSERT_GE(effort, 0);
  EXPECT_GT(std::abs(one.at(0, effort)), 1.0);
}

TEST(RunRequest, InvalidRequestOrSelectionThrowsWithTheMessage) {
  const Model model = testing_files::FromJson(testing_files::ReadJson("planar-four-bar.json"));
  RunRequest r;
  r.tolerance = 5e-3;
  EXPECT_THROW(RunMotion(model, r), std::invalid_argument);
  r.tolerance = 1e-10;
  r.bodies = std::vector<std::string>{"no_such_body"};
  try {
    RunMotion(model, r);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no body named 'no_such_body'"), std::string::npos) << e.what();
  }
}

TEST(EnumNames, DrivingNamesAgreeWithTheMobilityLayer) {
  for (const auto& e : EnumNames<DrivingStatus>::kAll) EXPECT_STREQ(ToString(e.value), DrivingStatusName(e.value));
  PositionSolver s = PositionSolver::Newton;
  EXPECT_TRUE(Parse("ceres", &s));
  EXPECT_EQ(s, PositionSolver::Ceres);
  EXPECT_FALSE(Parse("Ceres", &s));  // exact names only
  EXPECT_EQ(s, PositionSolver::Ceres);
  EXPECT_EQ(NameList<Formulation>(), "omega, p");
  EXPECT_EQ(NamesOf<TableFormat>(), (std::vector<std::string>{"csv", "json"}));
  EXPECT_STREQ(ToString(StopKind::SingularPosition), "singular_position");
  EXPECT_STREQ(ToString(Quantity::PointPosition), "point");
}

}  // namespace
}  // namespace mechkin
