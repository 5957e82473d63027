// Joints assembled from primitives (constraints.md §5) and the assembled system.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <filesystem>
#include <random>

#include "constraints/system.hpp"
#include "joints/registry.hpp"
#include "model/frames.hpp"
#include "model/loader.hpp"
#include "kinematics/position.hpp"

namespace mechkin {
namespace joints_test {

// The conformance harness of the joint types (docs/joints.md): two free bodies at
// random poses joined by one joint assembled at a random origin/axis: the kernel of
// the joint's Jacobian (12 columns) has dimension 6 (rigid motions of the pair) +
// the freedoms the joint allows, and its rows are 6 − freedoms.
int KernelDimension(const JointDescriptor& type, int freedoms, std::mt19937& g) {
  std::uniform_real_distribution<double> u(-1, 1);
  Model m;
  for (int b = 0; b < 2; ++b) {
    Body body;
    body.name = "b" + std::to_string(b);
    body.position = Vec3(u(g), u(g), u(g));
    body.euler = Vec4(u(g), u(g), u(g), u(g)).normalized();
    m.bodies.push_back(body);
  }
  Joint j;
  j.name = "j";
  j.type = &type;
  j.body1 = 0;
  j.body2 = 1;
  j.pitch = 0.05;
  const Vec3 origin(u(g), u(g), u(g)), axis = Vec3(u(g), u(g), u(g)).normalized();
  JointFrame global = MakeFrame(origin, axis);
  auto local = [&](int b, const JointFrame& gf) {
    return ToLocal(gf, m.bodies[b].position, CalcA(m.bodies[b].euler));
  };
  j.frame1 = local(0, global);
  j.frame2 = local(1, global);
  if (type.frames == JointFrameRule::CrossAxes) j.frame2 = local(1, MakeFrame(origin, global.f, axis));
  if (type.frames == JointFrameRule::TwoPoints) {
    j.frame2.origin = local(1, MakeFrame(origin + 0.3 * axis, axis)).origin;
    j.length = 0.3;
  }
  m.joints.push_back(j);
  m.characteristic_length = 1;
  const ConstraintSystem sys(m, false);
  const SystemState s(sys);
  Eigen::VectorXd phi;
  CalcPhi(sys, s, &phi);
  EXPECT_LT(phi.cwiseAbs().maxCoeff(), 1e-13) << type.name;  // assembled as built
  EXPECT_EQ(sys.num_rows(), 6 - freedoms) << type.name;
  EXPECT_EQ(sys.num_rows(), type.Rows()) << type.name;
  Eigen::MatrixXd J;
  CalcJacobianDense(sys, s, Formulation::Omega, &J);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J);
  int rank = 0;
  for (int k = 0; k < svd.singularValues().size(); ++k) rank += svd.singularValues()[k] > 1e-9 * svd.singularValues()[0];
  return 12 - rank;
}

// One line a joint type: its name and the freedoms it allows. Every registered type
// must have its line.
const std::pair<const char*, int> kConformance[] = {
    {"revolute", 1},  {"prismatic", 1}, {"screw", 1},  {"cylindrical", 2},
    {"universal", 2}, {"spherical", 3}, {"planar", 3}, {"distance", 5},
};

TEST(Joints, KernelDimensionIsTheFreedomsAllowed) {
  std::mt19937 g(42);
  for (int trial = 0; trial < 50; ++trial)
    for (const auto& [name, freedoms] : kConformance)
      EXPECT_EQ(KernelDimension(JointTypeNamed(name), freedoms, g), 6 + freedoms) << name;
}

TEST(Joints, EveryRegisteredTypeHasAConformanceLine) {
  std::vector<std::string> listed;
  for (const auto& [name, freedoms] : kConformance) listed.push_back(name);
  for (const JointDescriptor* d : JointTypes())
    EXPECT_NE(std::find(listed.begin(), listed.end(), d->name), listed.end()) << d->name << " has no line";
  EXPECT_EQ(JointTypes().size(), listed.size());
}

// Φ = 0 to 1e-12 (relative to the mechanism size) at the design pose of every
// bundled mechanism: the files are assembled as written (a file placed by markers
// is assembled by analysis/load.hpp, above this layer: tests/analysis checks those).
TEST(Joints, BundledMechanismsAreAssembledAtTheDesignPose) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms")) {
    if (entry.path().extension() != ".json") continue;
    const LoadResult r = LoadFileUnassembled(entry.path().string());
    ASSERT_TRUE(r.ok()) << entry.path();
    if (r.model->assembly) continue;
    const ConstraintSystem sys(*r.model, false);
    const SystemState s(sys);
    Eigen::VectorXd phi;
    CalcPhi(sys, s, &phi);
    const std::vector<int> rows = AllRows(sys);
    EXPECT_LT(ScaledResidual(phi, rows, RowScales(sys, rows)), 1e-12) << entry.path();
    ++files;
  }
  EXPECT_GE(files, 12);
}

// The fixed-pattern sparse Jacobian equals the dense one, in both versions.
TEST(System, SparseJacobianMatchesDense) {
  const LoadResult r = LoadFileUnassembled(std::string(MECHKIN_SOURCE_DIR) + "/mechanisms/spatial-slider-crank.json");
  ASSERT_TRUE(r.ok());
  const ConstraintSystem sys(*r.model, true);
  SystemState s(sys);
  ApplyStep(Eigen::VectorXd::Constant(6 * sys.num_bodies(), 0.01), &s);  // off the design pose
  for (Formulation f : {Formulation::Omega, Formulation::P}) {
    SparseJacobian sp(sys, f, AllRows(sys));
    sp.Fill(sys, s);
    Eigen::MatrixXd dense;
    CalcJacobianDense(sys, s, f, &dense);
    EXPECT_LT((Eigen::MatrixXd(sp.matrix()) - dense).norm(), 1e-15);
  }
}

TEST(System, UnwrapAngleIsContinuousOverManyTurns) {
  double ref = 0;
  const int steps_per_turn = 7;
  for (int k = 1; k <= 1000 * steps_per_turn; ++k) {
    const double theta = 2 * M_PI * k / steps_per_turn;
    ref = UnwrapAngle(std::sin(theta), std::cos(theta), ref);
  }
  EXPECT_NEAR(ref, 2000 * M_PI, 1e-9);
}

}  // namespace
}  // namespace mechkin
