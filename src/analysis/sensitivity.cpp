#include "analysis/sensitivity.hpp"

#include <cmath>
#include <stdexcept>

#include "analysis/load.hpp"

namespace mechkin {

struct SensitivitySolver::Side {
  std::unique_ptr<Model> model;
  std::unique_ptr<ConstraintSystem> sys;
  std::unique_ptr<SystemState> state;
  std::unique_ptr<SparseJacobian> jac;
};

struct SensitivitySolver::Variant {
  std::string name;
  double h = 0;
  Side plus, minus;
  std::vector<Eigen::VectorXd> delta;  // per order: (δr^(k), δω'^(k−1)) per body; order 0: (δr, δπ')
};

SensitivitySolver::~SensitivitySolver() = default;

double SensitivityStep(const Parameter& p) {
  double scale = std::abs(p.value);
  if (!(scale > 0) && p.tolerance) scale = *p.tolerance;
  if (!(scale > 0) && p.min && p.max) scale = *p.max - *p.min;
  if (!(scale > 0)) scale = 1;
  return 5e-6 * scale;
}

namespace {

std::unique_ptr<Model> Compile(const Model& model, const std::string& name, double value) {
  LoadResult r = WithParameters(model, {{name, value}});
  if (!r.ok()) {
    const std::string why = r.errors.empty() ? "" : ": " + r.errors.front().ToString();
    throw std::invalid_argument("the file does not compile with " + name + " = " + std::to_string(value) + why);
  }
  return std::make_unique<Model>(std::move(*r.model));
}

// The variants must be the same mechanism with other numbers, on the same time grid.
void CheckSameStructure(const Model& a, const Model& b, const std::string& name) {
  const bool same = a.num_bodies() == b.num_bodies() && a.joints.size() == b.joints.size() &&
                    a.drivers.size() == b.drivers.size() && a.outputs.size() == b.outputs.size() &&
                    a.analysis.has_value() == b.analysis.has_value();
  if (!same) throw std::invalid_argument("parameter '" + name + "' changes the mechanism's structure");
  if (a.analysis && (a.analysis->start != b.analysis->start || a.analysis->end != b.analysis->end ||
                     a.analysis->steps != b.analysis->steps))
    throw std::invalid_argument("parameter '" + name +
                                "' changes the analysis span or steps: sensitivities are per row at fixed times");
}

// The derivative unknowns of order k at s, in the ω' column layout.
void OrderUnknowns(const SystemState& s, int k, Eigen::VectorXd* x) {
  x->resize(6 * s.bodies.size());
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    x->segment<3>(6 * b) = s.bodies[b].r[k];
    x->segment<3>(6 * b + 3) = s.bodies[b].w[k - 1];
  }
}

}  // namespace

SensitivitySolver::SensitivitySolver(const Model& model, const std::vector<std::string>& names, int order)
    : order_(order) {
  for (const auto& name : names) {
    const Parameter* p = model.FindParameter(name);
    if (!p) {
      std::string known;
      for (const auto& q : model.parameters) known += (known.empty() ? "" : ", ") + q.name;
      throw std::invalid_argument("no parameter '" + name + "' in the file" +
                                  (known.empty() ? " (it declares none)" : " (parameters: " + known + ")"));
    }
    auto v = std::make_unique<Variant>();
    v->name = name;
    v->h = SensitivityStep(*p);
    v->plus.model = Compile(model, name, p->value + v->h);
    v->minus.model = Compile(model, name, p->value - v->h);
    for (Side* side : {&v->plus, &v->minus}) {
      CheckSameStructure(model, *side->model, name);
      side->sys = std::make_unique<ConstraintSystem>(*side->model, true);
      side->state = std::make_unique<SystemState>(*side->sys);
    }
    v->delta.resize(order + 1);
    variants_.push_back(std::move(v));
  }
}

const std::string& SensitivitySolver::name(int k) const { return variants_[k]->name; }
double SensitivitySolver::step(int k) const { return variants_[k]->h; }
const Model& SensitivitySolver::model(int k, int sign) const {
  return *(sign > 0 ? variants_[k]->plus.model : variants_[k]->minus.model);
}
const SystemState& SensitivitySolver::state(int k, int sign) const {
  return *(sign > 0 ? variants_[k]->plus.state : variants_[k]->minus.state);
}

// side.state = s moved by sign·h·δ in the pose and the derivative orders 1..upto
// (upto = −1: not moved at all), in the ω' chart.
void SensitivitySolver::PerturbedState(const SystemState& s, const Variant& v, int upto, double sign,
                                       Side& side) const {
  SystemState& out = *side.state;
  out.t = s.t;
  out.bodies = s.bodies;
  out.angle_ref = s.angle_ref;
  const double e = sign * v.h;
  for (size_t b = 0; b < out.bodies.size() && upto >= 0; ++b) {
    BodyKinematics& bk = out.bodies[b];
    bk.r[0] += e * v.delta[0].segment<3>(6 * b);
    bk.p = QuatRetractBody(bk.p, e * v.delta[0].segment<3>(6 * b + 3));
    bk.A = CalcA(bk.p);
    bk.AD[0] = bk.AB[0] = bk.A;
    for (int k = 1; k <= upto; ++k) {
      bk.r[k] += e * v.delta[k].segment<3>(6 * b);
      bk.w[k - 1] += e * v.delta[k].segment<3>(6 * b + 3);
    }
    bk.UpdateDerived(order_);
  }
}

// Φ_q δq^(k) = −[R_k(model₊, s₊) − R_k(model₋, s₋)] / 2h, R_0 = Φ, R_k = Φ_q q^(k) − RHS_k,
// the states moved in the lower orders only.
void SensitivitySolver::SolveOrder(KinematicsWorkspace& ws, const SystemState& s, Variant& v, int k) {
  if (k > 0) OrderUnknowns(s, k, &x_);
  for (Side* side : {&v.plus, &v.minus}) {
    PerturbedState(s, v, k - 1, side == &v.plus ? 1.0 : -1.0, *side);
    Eigen::VectorXd& residual = side == &v.plus ? plus_ : minus_;
    if (k == 0) {
      CalcPhi(*side->sys, *side->state, &full_);
      residual.resize(rows_.size());
      for (size_t r = 0; r < rows_.size(); ++r) residual[r] = full_[rows_[r]];
      continue;
    }
    side->jac->Fill(*side->sys, *side->state);
    CalcRhs(*side->sys, *side->state, k, Formulation::Omega, &full_);
    residual = side->jac->matrix() * x_;
    for (size_t r = 0; r < rows_.size(); ++r) residual[r] -= full_[rows_[r]];
  }
  rhs_ = (minus_ - plus_) / (2 * v.h);
  if (!ws.factorization().SolveLinear(rhs_, &dx_)) throw std::runtime_error("sensitivity: no solve");
  v.delta[k] = dx_;
}

bool SensitivitySolver::Solve(KinematicsWorkspace& ws, const SystemState& s) {
  if (rows_ != ws.active()) {
    rows_ = ws.active();
    for (auto& v : variants_)
      for (Side* side : {&v->plus, &v->minus})
        side->jac = std::make_unique<SparseJacobian>(*side->sys, Formulation::Omega, rows_);
  }
  try {
    for (auto& v : variants_) {
      for (Side* side : {&v->plus, &v->minus}) EvalDriverFunctions(*side->model, s.t, side->state.get());
      for (int k = 0; k <= order_; ++k) SolveOrder(ws, s, *v, k);
      PerturbedState(s, *v, order_, 1.0, v->plus);
      PerturbedState(s, *v, order_, -1.0, v->minus);
    }
  } catch (const std::runtime_error&) {
    return false;
  }
  return true;
}

}  // namespace mechkin
