#include "analysis/kinematic_analysis.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "mobility/mobility.hpp"
#include "solvers/block_solver.hpp"
#include "solvers/ceres_position.hpp"
#include "solvers/newton.hpp"

namespace mechkin {

bool AnalysisOptions::IsValid(std::string* error) const {
  if (order < 0 || order > 4) { *error = "order must be 0..4"; return false; }
  if (!(tolerance > 0 && tolerance < 1e-2)) { *error = "tolerance must be in (0, 1e-2)"; return false; }
  if (max_iterations < 1) { *error = "max_iterations must be >= 1"; return false; }
  if (predictor_order < 0 || predictor_order > 3) { *error = "predictor order must be 0..3"; return false; }
  return true;
}

namespace {

using Clock = std::chrono::steady_clock;

// The value each driver has at the design pose: angles and slides are 0 there
// (format-v1), a distance driver gives the design distance itself.
double DesignDriverValue(const Model& m, const Driver& d) {
  if (d.kind != DriverKind::Distance) return 0;
  auto global = [&](BodyIndex b, const Vec3& s) -> Vec3 {
    return b == kGround ? s : Vec3(m.bodies[b].position + CalcA(m.bodies[b].euler) * s);
  };
  return (global(d.body2, d.point2) - global(d.body1, d.point1)).norm();
}

// Points the multi-turn angle of rotation drivers at their target f(t).
void AimRotationDrivers(const ConstraintSystem& sys, SystemState* s) {
  for (size_t e = 0; e < sys.entries().size(); ++e) {
    const ConstraintEntry& en = sys.entries()[e];
    if (en.from_driver && en.constraint->HasAngle()) s->angle_ref[e] = s->driver_values[en.source].c[0];
  }
}

// Everything the step loop reuses: no allocation per step.
struct Workspace {
  Eigen::VectorXd rhs_full, rhs, x, phi;
  std::vector<std::array<Vec4, 5>> pd;  // p-version Euler parameter derivatives per body
};

std::string Describe(const ConstraintSystem& sys, const SystemState& s, const Eigen::VectorXd& phi,
                     const std::vector<int>& rows, const Eigen::VectorXd& scales, int count) {
  std::vector<std::pair<double, int>> r;
  for (size_t k = 0; k < rows.size(); ++k) r.emplace_back(std::abs(phi[rows[k]]) * scales[k], rows[k]);
  std::sort(r.rbegin(), r.rend());
  const Units& u = sys.model().units;
  std::ostringstream o;
  for (int k = 0; k < count && k < static_cast<int>(r.size()); ++k) {
    const auto [e, local] = sys.Locate(r[k].second);
    const Constraint& c = *sys.entries()[e].constraint;
    const double miss = c.Misfit(MakeInput(sys, s, e), local, phi[r[k].second]);
    o << "\n    " << sys.DescribeRow(r[k].second) << ": misses by ";
    if (c.LengthPower() == 0) o << std::abs(miss) / u.angle_to_si << " " << u.angle_name;
    else o << std::abs(miss) / u.length_to_si << " " << u.length_name;
  }
  return o.str();
}

double SmallestSingularValue(const ConstraintSystem& sys, const SystemState& s, const std::vector<int>& rows) {
  if (6 * sys.num_bodies() > 1200) return std::nan("");
  const Eigen::MatrixXd J = ScaledJacobian(sys, s);
  Eigen::MatrixXd Js(rows.size(), J.cols());
  for (size_t k = 0; k < rows.size(); ++k) Js.row(k) = J.row(rows[k]);
  Eigen::BDCSVD<Eigen::MatrixXd> svd(Js);
  return svd.singularValues().size() ? svd.singularValues().tail(1)[0] : 0.0;
}

// Taylor predictor: moves every body by dt along its r and p series, using the
// derivatives up to `order` held in the state (from the previous step).
void PredictPose(double dt, int order, SystemState* s) {
  static constexpr double kFact[] = {1, 1, 2, 6, 24};
  for (auto& b : s->bodies) {
    Vec4 pd[5];
    b.CalcEulerDerivatives(order, pd);
    Vec3 r = b.r[0];
    Vec4 p = pd[0];
    double hk = 1;
    for (int k = 1; k <= order; ++k) {
      hk *= dt;
      r += hk / kFact[k] * b.r[k];
      p += hk / kFact[k] * pd[k];
    }
    b.r[0] = r;
    b.p = p.normalized();
    b.A = CalcA(b.p);
    b.AD[0] = b.AB[0] = b.A;
  }
}

// Bisection in time for the root of det Φ_q between t_lo (sign_lo, state s_lo)
// and t_hi, each probe a tight Newton solve from the last state on the lo side.
SingularPosition LocateSingularity(const ConstraintSystem& sys, NewtonSolver* newton, const SystemState& base,
                                   double t_lo, double t_hi, double sign_lo, double step, int order) {
  // Every probe starts from the Taylor prediction off the last regular step, so it
  // follows the same branch as the run did.
  SystemState s_lo = base;
  const Model& model = sys.model();
  SolveOptions tight;
  tight.tolerance = 1e-14;
  tight.max_iterations = 100;
  while (t_hi - t_lo > 1e-9 * step) {
    const double mid = 0.5 * (t_lo + t_hi);
    SystemState probe = base;
    PredictPose(mid - base.t, order, &probe);
    EvalDriverFunctions(model, mid, &probe);
    AimRotationDrivers(sys, &probe);
    newton->Solve(tight, &probe);
    if (newton->Factorize(probe) && newton->JacobianSign() == sign_lo) {
      t_lo = mid;
      s_lo = probe;
    } else {
      t_hi = mid;
    }
  }
  SingularPosition sp;
  sp.t = 0.5 * (t_lo + t_hi);
  EvalDriverFunctions(model, sp.t, &s_lo);
  for (const Jet& j : s_lo.driver_values) sp.driver_values.push_back(j.c[0]);
  // Instantaneous mobility of the joints and the equations of the vanishing direction.
  if (6 * sys.num_bodies() <= 1200) {
    const ConstraintSystem joints(model, false);
    SystemState js(joints);
    js.bodies = s_lo.bodies;
    const Eigen::MatrixXd Jj = ScaledJacobian(joints, js);
    Eigen::BDCSVD<Eigen::MatrixXd> sj(Jj);
    int rank = 0;
    for (int k = 0; k < sj.singularValues().size(); ++k) rank += sj.singularValues()[k] > 1e-6 * sj.singularValues()[0];
    sp.joint_mobility = 6 * sys.num_bodies() - rank;
    const std::vector<int>& rows = newton->rows();
    const Eigen::MatrixXd J = ScaledJacobian(sys, s_lo);
    Eigen::MatrixXd Ja(rows.size(), J.cols());
    for (size_t k = 0; k < rows.size(); ++k) Ja.row(k) = J.row(rows[k]);
    Eigen::BDCSVD<Eigen::MatrixXd> svd(Ja, Eigen::ComputeFullU);
    const Eigen::VectorXd u = svd.matrixU().col(Ja.rows() - 1);  // left singular vector of σ_min
    std::vector<std::pair<double, int>> w;
    for (int k = 0; k < u.size(); ++k) w.emplace_back(std::abs(u[k]), rows[k]);
    std::sort(w.rbegin(), w.rend());
    std::vector<std::string> names;
    for (const auto& [mag, row] : w) {
      if (mag < 0.1 * w[0].first || names.size() >= 4) break;
      const std::string src = sys.SourceName(row);
      if (std::find(names.begin(), names.end(), src) == names.end()) names.push_back(src);
    }
    sp.involved = names;
  }
  return sp;
}

}  // namespace

StepStatistics SummarizeSteps(const std::vector<StepDiagnostics>& steps) {
  StepStatistics st;
  if (steps.empty()) return st;
  std::vector<double> us;
  us.reserve(steps.size());
  for (const auto& d : steps) {
    us.push_back(d.solve_seconds * 1e6);
    st.mean_iterations += d.iterations;
    st.max_residual = std::max(st.max_residual, d.residual);
    st.max_set_aside_residual = std::max(st.max_set_aside_residual, d.set_aside_residual);
  }
  std::nth_element(us.begin(), us.begin() + us.size() / 2, us.end());
  st.median_us = us[us.size() / 2];
  st.mean_iterations /= steps.size();
  return st;
}

AnalysisReport RunKinematicAnalysis(const Model& model, const AnalysisOptions& options, const StepCallback& on_step) {
  AnalysisReport rep;
  std::string why;
  if (!options.IsValid(&why)) { rep.message = why; return rep; }
  if (!model.analysis) { rep.message = "the file has no 'analysis' block: add {\"start\": 0, \"end\": 1, \"steps\": 100}"; return rep; }
  const ConstraintSystem sys(model, true);
  const int n = sys.num_bodies();
  SystemState s(sys);
  SolveOptions solve;
  solve.tolerance = options.tolerance;
  solve.max_iterations = options.max_iterations;

  // 1. Assemble the design pose with every driver held at its design value.
  for (size_t d = 0; d < model.drivers.size(); ++d) s.driver_values[d] = Jet::Constant(DesignDriverValue(model, model.drivers[d]));
  AimRotationDrivers(sys, &s);
  const bool dense_ok = 6 * n <= 1200;
  std::vector<int> all = AllRows(sys);
  if (dense_ok) {
    SolveOptions rough = solve;
    rough.max_iterations = 100;
    const SolveSummary a = AssembleMinNorm(sys, all, rough, &s);
    rep.assembly_iterations = a.iterations;
    if (!a.success) {
      Eigen::VectorXd phi;
      CalcPhi(sys, s, &phi);
      rep.message = "the design pose cannot be assembled (scaled residual " + std::to_string(a.residual) +
                    "); the equations that cannot close:" + Describe(sys, s, phi, all, RowScales(sys, all), 3) +
                    "\n  Check the lengths and joint positions in the file.";
      return rep;
    }
  }

  // 2. Redundant equations: keep an independent subset (greedy in file order, joints first).
  std::vector<int> active = all, set_aside;
  if (dense_ok) active = IndependentRows(ScaledJacobian(sys, s), 1e-7, &set_aside);
  std::vector<std::string> conflicting;
  for (int row : set_aside) {
    if (row >= sys.num_joint_rows()) conflicting.push_back(sys.SourceName(row));
    else rep.set_aside.push_back(sys.DescribeRow(row));
  }
  if (!conflicting.empty()) {
    rep.message = "over-driven: driver(s) ";
    for (size_t k = 0; k < conflicting.size(); ++k) rep.message += (k ? ", `" : "`") + conflicting[k] + "`";
    rep.message += " conflict with the joints or other drivers. Remove or change them (mechkin check names the freedoms).";
    return rep;
  }
  if (static_cast<int>(active.size()) != 6 * n) {
    const MobilityReport mob = CalcMobility(model);
    rep.message = "under-driven: " + std::to_string(6 * n - static_cast<int>(active.size())) +
                  " freedom(s) are not driven";
    for (const auto& f : mob.remaining_freedoms) rep.message += "\n    " + f;
    for (const auto& f : mob.idle) rep.message += "\n    idle: " + f.description;
    rep.message += "\n  Add drivers, or remove the idle freedoms (see mechkin check).";
    return rep;
  }
  NewtonSolver newton(sys, active);
  // Block-triangular structure (once per model), and the block path when the
  // selection needs only part of the mechanism.
  BlockStructure blocks;
  std::unique_ptr<BlockSolver> block_solver;
  if (FindBlockStructure(newton.jacobian(), &blocks)) {
    rep.blocks = rep.blocks_solved = blocks.size();
    // Block by block only when the selection skips blocks: for a full run one LU
    // of the whole Φ_q is faster (slider-crank: 3.5 µs per step against 5.8 µs in
    // two blocks) and is what the singular-position location uses.
    if (!options.needed_bodies.empty() && options.formulation == Formulation::Omega &&
        options.solver == PositionSolver::Newton) {
      std::vector<int> cols;
      for (int b : options.needed_bodies)
        for (int q = 0; q < 6; ++q) cols.push_back(6 * b + q);
      const std::vector<char> needed = NeededBlocks(blocks, cols);
      const int count = static_cast<int>(std::count(needed.begin(), needed.end(), 1));
      if (count < blocks.size()) {
        block_solver = std::make_unique<BlockSolver>(sys, active, blocks, needed);
        rep.blocks_solved = count;
      }
    }
  }
  std::unique_ptr<SparseJacobian> jac_p;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_p;
  if (options.formulation == Formulation::P && options.order > 0) {
    jac_p = std::make_unique<SparseJacobian>(sys, Formulation::P, active);
    lu_p.analyzePattern(jac_p->matrix());
  }
  const Eigen::VectorXd aside_scales = RowScales(sys, set_aside);
  Workspace ws;
  ws.rhs.resize(active.size() + (jac_p ? n : 0));
  ws.pd.resize(n);

  // 3. Continue from the design driver values to those at `start`, in small
  //    increments, so that the branch connected to the design pose is kept.
  const Analysis& an = *model.analysis;
  {
    EvalDriverFunctions(model, an.start, &s);
    std::vector<Jet> target = s.driver_values;
    double worst = 0;
    for (size_t d = 0; d < model.drivers.size(); ++d) {
      const double delta = std::abs(target[d].c[0] - DesignDriverValue(model, model.drivers[d]));
      const double limit = model.drivers[d].kind == DriverKind::JointRotation || model.drivers[d].kind == DriverKind::BodyRotation
                               ? 10 * M_PI / 180 : 0.05 * model.characteristic_length;
      worst = std::max(worst, delta / limit);
    }
    const int substeps = std::max(1, static_cast<int>(std::ceil(worst)));
    for (int k = 1; k <= substeps; ++k) {
      const double lambda = static_cast<double>(k) / substeps;
      for (size_t d = 0; d < model.drivers.size(); ++d) {
        const double v0 = DesignDriverValue(model, model.drivers[d]);
        s.driver_values[d] = Jet::Constant(v0 + lambda * (target[d].c[0] - v0));
      }
      AimRotationDrivers(sys, &s);
      SolveOptions o = solve;
      o.max_iterations = 50;
      const SolveSummary r = newton.Solve(o, &s);
      rep.assembly_iterations += r.iterations;
      if (!r.success) {
        Eigen::VectorXd phi;
        CalcPhi(sys, s, &phi);
        rep.message = "cannot reach the drivers' values at t = start from the design pose (" + r.message +
                      "); largest residuals:" + Describe(sys, s, phi, active, newton.scales(), 3);
        return rep;
      }
      UpdateAngleReferences(sys, &s);
    }
  }

  // 4. The time steps.
  const double h = (an.end - an.start) / an.steps;
  const int order = options.order, pred = std::min(options.predictor_order, order);
  // The sub-steps (below) need derivatives for their predictor even at --order 0.
  double prev_sign = 0;
  bool have_sign = false;
  SystemState prev_state = s, predicted = s, good_state = s;
  SolveSummary last;

  // Derivative solves at the current pose: one factorization, `order` back-solves.
  auto derivatives = [&]() {
    if (block_solver) {
      block_solver->Derivatives(order, &s);
      return;
    }
    for (auto& b : s.bodies) {
      for (int k = 1; k <= kMaxOrder; ++k) b.r[k].setZero();
      for (int k = 0; k < kMaxOrder; ++k) b.w[k].setZero();
    }
    if (jac_p) {
      jac_p->Fill(sys, s);
      lu_p.factorize(jac_p->matrix());
      for (int b = 0; b < n; ++b) ws.pd[b][0] = s.bodies[b].p;
    }
    for (int k = 1; k <= order; ++k) {
      for (auto& b : s.bodies) b.PrepareOrder(k);
      CalcRhs(sys, s, k, options.formulation, &ws.rhs_full);
      for (size_t r = 0; r < active.size(); ++r) ws.rhs[r] = ws.rhs_full[active[r]];
      if (!jac_p) {
        newton.BackSolve(ws.rhs, &ws.x);
        for (int b = 0; b < n; ++b) {
          s.bodies[b].r[k] = ws.x.segment<3>(6 * b);
          s.bodies[b].w[k - 1] = ws.x.segment<3>(6 * b + 3);
        }
      } else {
        for (int b = 0; b < n; ++b) ws.rhs[active.size() + b] = ws.rhs_full[sys.num_rows() + b];
        ws.x = lu_p.solve(ws.rhs);
        for (int b = 0; b < n; ++b) {
          BodyKinematics& bk = s.bodies[b];
          auto& pd = ws.pd[b];
          bk.r[k] = ws.x.segment<3>(7 * b);
          pd[k] = ws.x.segment<4>(7 * b + 3);
          // ω'^(k−1) from p^(k) (§1.3): ω' = 2Gṗ, ω̇' = 2Gp̈, ω̈' = 2Gp⃛ + 2G(ṗ)p̈, ω⃛' = 2Gp⁗ + 4G(ṗ)p⃛.
          const Mat34 G = CalcG(pd[0]);
          Vec3 w = 2 * G * pd[k];
          if (k == 3) w += 2 * CalcG(pd[1]) * pd[2];
          if (k == 4) w += 4 * CalcG(pd[1]) * pd[3];
          bk.w[k - 1] = w;
        }
      }
    }
    for (auto& b : s.bodies) b.CompleteOrder(order);
  };
  // Largest move between two poses: |Δr| / L and the rotation angle, per body.
  auto distance = [&](const SystemState& a, const SystemState& b) {
    double d = 0;
    for (int k = 0; k < n; ++k) {
      d = std::max(d, (a.bodies[k].r[0] - b.bodies[k].r[0]).norm() / model.characteristic_length);
      d = std::max(d, 2 * std::acos(std::min(1.0, std::abs(a.bodies[k].p.dot(b.bodies[k].p)))));
    }
    return d;
  };
  enum class Outcome { Ok, Failed, Suspect };
  // One attempt from the accepted state in `s` to time t (predictor over dt).
  // Suspect: det Φ_q changed sign, or the solution is far (> 0.1 L or rad) from the
  // prediction — the marks of a jump to another assembly branch or of a singular
  // position between the two times.
  auto attempt = [&](double t, double dt, bool reuse) -> Outcome {
    EvalDriverFunctions(model, t, &s);
    AimRotationDrivers(sys, &s);
    if (dt > 0 && pred > 0) PredictPose(dt, pred, &s);
    predicted.bodies = s.bodies;
    if (block_solver) {
      last = block_solver->Solve(solve, &s);
      if (!last.success || !block_solver->Factorize(s)) return Outcome::Failed;
    } else {
      last = options.solver == PositionSolver::Ceres
                 ? SolvePositionCeres(sys, active, solve, &s,
                                      options.ceres_normalization_residual ? CeresUnitQuaternion::NormalizationResidual
                                                                           : CeresUnitQuaternion::Manifold)
                 : newton.Solve(solve, &s, reuse && options.modified_newton);
      if (!last.success || !newton.Factorize(s)) return Outcome::Failed;
    }
    const double sign = block_solver ? block_solver->Sign() : newton.JacobianSign();
    if (options.branch_guard) {
      if (have_sign && sign != prev_sign) return Outcome::Suspect;
      if (dt > 0 && distance(predicted, s) > 0.1) return Outcome::Suspect;
    }
    derivatives();
    prev_sign = sign;
    have_sign = true;
    return Outcome::Ok;
  };
  auto failure_message = [&](double t, const std::string& why) {
    CalcPhi(sys, s, &ws.phi);
    const double smin = SmallestSingularValue(sys, s, active);
    std::ostringstream o;
    o << "position solve failed at t = " << t << " s after " << rep.steps.size() << " rows: " << why
      << "\n  largest residuals:" << Describe(sys, s, ws.phi, active, newton.scales(), 3)
      << "\n  smallest singular value of the scaled Φ_q: " << smin
      << (smin < 1e-6 ? " (singular: a toggle, dead centre or lock-up position)" : "")
      << "\n  Try: keep the drivers inside the reachable range, start the motion away from the singular "
         "position, or use more steps.";
    return o.str();
  };

  for (int step = 0; step <= an.steps; ++step) {
    const double t = an.start + step * h;
    const auto t0 = Clock::now();
    StepDiagnostics diag;
    diag.t = t;
    Outcome out;
    try {
      out = attempt(t, step > 0 ? h : 0, step > 0);
      diag.iterations = last.iterations;
      if (out != Outcome::Ok && step > 0) {
        // Adaptive sub-stepping between the table rows: halve until every sub-step
        // is regular. A sign change that survives 1/1024 of the step is a genuine
        // singular position.
        double bad_t = t, good_t = prev_state.t, good_sign = prev_sign;
        for (int parts = 2; parts <= 1024 && out != Outcome::Ok; parts *= 2) {
          s = prev_state;
          prev_sign = good_sign;
          good_state = prev_state;
          good_t = prev_state.t;
          for (int i = 1; i <= parts; ++i) {
            const double ti = prev_state.t + (t - prev_state.t) * i / parts;
            out = attempt(ti, (t - prev_state.t) / parts, true);
            diag.iterations += last.iterations;
            if (out != Outcome::Ok) { bad_t = ti; break; }
            UpdateAngleReferences(sys, &s);
            good_state = s;
            good_t = ti;
          }
          if (out == Outcome::Ok) ++diag.substeps_refinements;
        }
        if (out == Outcome::Suspect) {
          const SingularPosition sp = LocateSingularity(sys, &newton, good_state, good_t, bad_t, prev_sign,
                                                        (t - prev_state.t) / 1024, std::max(pred, 1));
          std::ostringstream o;
          o.precision(12);
          o << "singular position at t = " << sp.t << " s";
          for (size_t d = 0; d < model.drivers.size(); ++d) {
            const bool angle = model.drivers[d].kind == DriverKind::JointRotation || model.drivers[d].kind == DriverKind::BodyRotation;
            o << ", driver `" << model.drivers[d].name << "` = "
              << sp.driver_values[d] / (angle ? model.units.angle_to_si : model.units.length_to_si) << " "
              << (angle ? model.units.angle_name : model.units.length_name);
          }
          o << "\n  instantaneous mobility of the joints there: " << sp.joint_mobility
            << " (a dead centre, toggle or change point where branches meet)";
          if (!sp.involved.empty()) {
            o << "\n  equations that become dependent: ";
            for (size_t k = 0; k < sp.involved.size(); ++k) o << (k ? ", `" : "`") << sp.involved[k] << "`";
          }
          o << "\n  The run stops here instead of choosing a branch. Try: end the motion before this time, or change "
               "the geometry so that the mechanism does not pass through this position.";
          rep.message = o.str();
          rep.singular = sp;
          return rep;
        }
      }
    } catch (const std::exception& e) {
      rep.message = e.what();
      return rep;
    }
    if (out == Outcome::Failed) {
      rep.message = failure_message(t, last.message);
      return rep;
    }
    diag.residual = last.residual;
    if (!set_aside.empty()) {
      CalcPhi(sys, s, &ws.phi);
      diag.set_aside_residual = ScaledResidual(ws.phi, set_aside, aside_scales);
    }
    diag.condition = block_solver ? block_solver->ConditionEstimate() : newton.ConditionEstimate();
    {
      const double u = std::numeric_limits<double>::epsilon() / 2, kappa = diag.condition;
      diag.error_bound[0] = kappa * std::max(diag.residual, 4 * u);
      double kk = 1;
      for (int k = 1; k <= kMaxOrder; ++k) {
        kk *= kappa;
        diag.error_bound[k] = 8 * u * kk + kappa * diag.error_bound[0];
      }
    }
    diag.solve_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    UpdateAngleReferences(sys, &s);
    rep.steps.push_back(diag);
    on_step(s, diag);
    prev_state = s;
  }
  rep.complete = true;
  return rep;
}

}  // namespace mechkin
