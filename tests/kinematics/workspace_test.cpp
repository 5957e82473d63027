// The step engine's free functions against independent references: the
// transpose solve against a dense solve with Φ_qᵀ, the velocity solve against a
// central difference of two position solves.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include "analysis/assembly.hpp"
#include "analysis/row_selection.hpp"
#include "kinematics/workspace.hpp"
#include "test_files.hpp"

namespace mechkin {
namespace workspace_test {

// A tight position solve (named fields, not positional).
SolveOptions Tight(double tolerance) {
  SolveOptions o;
  o.tolerance = tolerance;
  o.max_iterations = 50;
  return o;
}

struct Solved {
  Model model;
  std::unique_ptr<ConstraintSystem> sys;
  std::unique_ptr<SystemState> s;
  RowSelection rows;
};

// The mechanism assembled at its design pose (t = 0) with the drivers' values there.
void Assemble(const std::string& file, Solved* out) {
  out->model = testing_files::FromJson(testing_files::ReadJson(file));
  out->sys = std::make_unique<ConstraintSystem>(out->model, true);
  out->s = std::make_unique<SystemState>(*out->sys);
  std::string why;
  int iters = 0;
  ASSERT_TRUE(AssembleDesignPose(*out->sys, Tight(1e-13), out->s.get(), &iters, &why)) << why;
  out->rows = SelectRows(*out->sys, *out->s);
}

class WorkspaceTest : public ::testing::TestWithParam<std::string> {};

TEST_P(WorkspaceTest, TransposeSolveMatchesDenseTranspose) {
  Solved m;
  Assemble(GetParam(), &m);
  KinematicsWorkspace ws(*m.sys, m.rows.active, WorkspaceOptions{});
  ASSERT_TRUE(SolvePosition(ws, Tight(1e-13), m.s.get(), false).success);
  Eigen::MatrixXd J;
  CalcJacobianDense(*m.sys, *m.s, Formulation::Omega, &J);
  Eigen::MatrixXd Ja(m.rows.active.size(), J.cols());
  for (size_t k = 0; k < m.rows.active.size(); ++k) Ja.row(k) = J.row(m.rows.active[k]);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(Ja.cols(), -1.0, 2.0);
  Eigen::VectorXd x;
  ASSERT_TRUE(SolveTranspose(ws, b, &x));
  const Eigen::VectorXd want = Ja.transpose().fullPivLu().solve(b);
  EXPECT_LT((x - want).norm(), 1e-10 * want.norm());
  EXPECT_LT((Ja.transpose() * x - b).norm(), 1e-12 * b.norm() * Ja.norm());
}

TEST_P(WorkspaceTest, VelocityMatchesCentralDifferenceOfPositions) {
  Solved m;
  Assemble(GetParam(), &m);
  KinematicsWorkspace ws(*m.sys, m.rows.active, WorkspaceOptions{});
  const double t = 0.3 * m.model.analysis->end, h = 1e-5 * m.model.analysis->end;
  std::string why;
  int iters = 0;
  ASSERT_TRUE(ContinueToStart(ws, t, Tight(1e-13), m.s.get(), &iters, &why)) << why;
  SystemState at = *m.s;
  auto position_at = [&](double tt) {
    SystemState s = at;
    EvalDriverFunctions(m.model, tt, &s);
    AimRotationDrivers(*m.sys, &s);
    EXPECT_TRUE(SolvePosition(ws, Tight(1e-14), &s, false).success);
    return s;
  };
  const SystemState plus = position_at(t + h), minus = position_at(t - h);
  EvalDriverFunctions(m.model, t, &at);
  ASSERT_TRUE(SolvePosition(ws, Tight(1e-14), &at, false).success);
  SolveDerivatives(ws, 2, &at);
  for (size_t b = 0; b < at.bodies.size(); ++b) {
    const Vec3 fd = (plus.bodies[b].r[0] - minus.bodies[b].r[0]) / (2 * h);
    EXPECT_LT((fd - at.bodies[b].r[1]).norm(), 1e-6 * (1 + at.bodies[b].r[1].norm())) << "body " << b;
  }
}

INSTANTIATE_TEST_SUITE_P(Bundled, WorkspaceTest,
                         ::testing::Values("spatial-slider-crank.json", "bennett-linkage.json", "stewart-platform.json",
                                           "five-bar.json"));

}  // namespace
}  // namespace mechkin
