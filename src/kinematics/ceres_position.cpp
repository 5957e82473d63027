#include "kinematics/ceres_position.hpp"

#include <ceres/ceres.h>
#include <ceres/manifold.h>

namespace mechkin {
namespace {

class EntryCost : public ceres::CostFunction {
 public:
  EntryCost(const ConstraintSystem& sys, const SystemState& s, int entry, std::vector<int> local_rows, std::vector<double> scales)
      : sys_(sys), s_(s), entry_(entry), local_rows_(std::move(local_rows)), scales_(std::move(scales)) {
    const Constraint& c = *sys.entries()[entry].constraint;
    set_num_residuals(static_cast<int>(local_rows_.size()));
    for (int side = 0; side < c.num_sides(); ++side)
      if (c.body(side) != kGround) {
        mutable_parameter_block_sizes()->push_back(3);
        mutable_parameter_block_sizes()->push_back(4);
      }
  }

  bool Evaluate(double const* const* params, double* residuals, double** jacobians) const override {
    const Constraint& c = *sys_.entries()[entry_].constraint;
    BodyKinematics kin[kMaxSides];
    double inv_norm[kMaxSides] = {1, 1, 1, 1, 1, 1};
    int block = 0;
    const int sides = c.num_sides();
    for (int side = 0; side < sides; ++side) {
      if (c.body(side) == kGround) continue;
      const Vec3 r(params[block][0], params[block][1], params[block][2]);
      const Vec4 p(params[block + 1][0], params[block + 1][1], params[block + 1][2], params[block + 1][3]);
      kin[side].SetPose(r, p.normalized());
      inv_norm[side] = 1 / p.norm();
      block += 2;
    }
    const auto side_kin = [&](int side) -> const BodyKinematics& {
      return c.body(side) == kGround ? GroundKinematics() : kin[side];
    };
    const ConstraintEntry& entry = sys_.entries()[entry_];
    ConstraintInput in{side_kin(0), side_kin(1), entry.from_driver ? s_.driver_values[entry.source] : Jet{},
                       s_.angle_ref[entry_]};
    for (int side = 2; side < sides; ++side) in.more[side - 2] = &side_kin(side);
    for (int a = 1; a < c.NumAngles(); ++a) in.more_angle_refs[a - 1] = s_.angle_ref[entry.extra_angle_slot + a - 1];
    double phi[kMaxRows];
    c.CalcPhi(in, phi);
    for (size_t k = 0; k < local_rows_.size(); ++k) residuals[k] = phi[local_rows_[k]] * scales_[k];
    if (!jacobians) return true;
    JacobianBlocks J;
    c.CalcJacobian(in, &J);
    block = 0;
    for (int side = 0; side < sides; ++side) {
      if (c.body(side) == kGround) continue;
      const RowBlock& Br = J.R(side);
      const Eigen::Matrix<double, kMaxRows, 4> Bp = PVersionBlock(in, J, side);
      for (size_t k = 0; k < local_rows_.size(); ++k) {
        const int r = local_rows_[k];
        if (jacobians[block])
          for (int a = 0; a < 3; ++a) jacobians[block][3 * k + a] = Br(r, a) * scales_[k];
        // Φ_p = 2Φ_π'G is the gradient of Φ(p/|p|) at unit p; at |p| ≠ 1 (normalization-
        // residual variant) the gradient is Φ_p(p̂)/|p|, since Φ_p(p̂) p̂ = 0.
        if (jacobians[block + 1])
          for (int a = 0; a < 4; ++a) jacobians[block + 1][4 * k + a] = Bp(r, a) * scales_[k] * inv_norm[side];
      }
      block += 2;
    }
    return true;
  }

 private:
  const ConstraintSystem& sys_;
  const SystemState& s_;
  int entry_;
  std::vector<int> local_rows_;
  std::vector<double> scales_;
};

}  // namespace

// pᵀp − 1 for one body (the normalization-residual variant).
class NormalizationCost : public ceres::SizedCostFunction<1, 4> {
 public:
  bool Evaluate(double const* const* params, double* residual, double** jacobians) const override {
    const double* p = params[0];
    residual[0] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3] - 1;
    if (jacobians && jacobians[0])
      for (int a = 0; a < 4; ++a) jacobians[0][a] = 2 * p[a];
    return true;
  }
};

SolveSummary SolvePositionCeres(const ConstraintSystem& sys, const std::vector<int>& rows, const SolveOptions& options,
                                SystemState* s, CeresUnitQuaternion unit) {
  const int n = sys.num_bodies();
  std::vector<double> params(7 * n);
  for (int b = 0; b < n; ++b) {
    for (int a = 0; a < 3; ++a) params[7 * b + a] = s->bodies[b].r[0][a];
    for (int a = 0; a < 4; ++a) params[7 * b + 3 + a] = s->bodies[b].p[a];
  }
  ceres::Problem::Options popt;
  popt.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(popt);
  ceres::QuaternionManifold quaternion;
  const Eigen::VectorXd w = RowScales(sys, rows);
  std::vector<std::vector<int>> entry_rows(sys.entries().size());
  std::vector<std::vector<double>> entry_scales(sys.entries().size());
  for (size_t k = 0; k < rows.size(); ++k) {
    const auto [e, r] = sys.Locate(rows[k]);
    entry_rows[e].push_back(r);
    entry_scales[e].push_back(w[k]);
  }
  for (size_t e = 0; e < sys.entries().size(); ++e) {
    if (entry_rows[e].empty()) continue;
    const Constraint& c = *sys.entries()[e].constraint;
    std::vector<double*> blocks;
    for (int side = 0; side < c.num_sides(); ++side)
      if (c.body(side) != kGround) {
        blocks.push_back(&params[7 * c.body(side)]);
        blocks.push_back(&params[7 * c.body(side) + 3]);
      }
    problem.AddResidualBlock(new EntryCost(sys, *s, static_cast<int>(e), entry_rows[e], entry_scales[e]), nullptr, blocks);
  }
  for (int b = 0; b < n; ++b) {
    if (!problem.HasParameterBlock(&params[7 * b + 3])) continue;
    if (unit == CeresUnitQuaternion::Manifold) problem.SetManifold(&params[7 * b + 3], &quaternion);
    else problem.AddResidualBlock(new NormalizationCost, nullptr, &params[7 * b + 3]);
  }
  ceres::Solver::Options opt;
  opt.linear_solver_type = n > 40 ? ceres::SPARSE_NORMAL_CHOLESKY : ceres::DENSE_QR;
  opt.max_num_iterations = std::max(options.max_iterations, 50);
  opt.function_tolerance = 1e-30;
  opt.gradient_tolerance = 1e-30;
  opt.parameter_tolerance = 1e-16;
  opt.num_threads = 1;
  // Parameters are in metres and unit quaternions: a modest first trust region keeps
  // Levenberg–Marquardt on the branch the predictor starts from.
  opt.trust_region_strategy_type = ceres::DOGLEG;
  opt.dogleg_type = ceres::SUBSPACE_DOGLEG;
  opt.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(opt, &problem, &summary);
  for (int b = 0; b < n; ++b) {
    const Vec4 p(params[7 * b + 3], params[7 * b + 4], params[7 * b + 5], params[7 * b + 6]);
    s->bodies[b].SetPose(Vec3(params[7 * b], params[7 * b + 1], params[7 * b + 2]), p.normalized());
  }
  SolveSummary sum;
  Eigen::VectorXd phi;
  CalcPhi(sys, *s, &phi);
  sum.residual = ScaledResidual(phi, rows, w);
  sum.iterations = static_cast<int>(summary.iterations.size());
  sum.success = sum.residual <= options.tolerance;
  sum.message = sum.success ? "converged (ceres)" : "ceres ended with scaled residual " + std::to_string(sum.residual) +
                                                        " (" + summary.message + ")";
  return sum;
}

}  // namespace mechkin
