// The live page's stand-ins (issue 30) for the parts of mechkin the WebAssembly core
// leaves out: Ceres (the `--solver ceres` option), SuiteSparseQR (the sparse rank of
// models with more than 200 bodies; the mobility report's naming of redundant rows
// gets a dense equivalent below) and FCL (clearance outputs). Each other one throws a
// message naming what the page cannot do and what to use instead; the run and the
// mobility report pass it on to the page. Linked only by tools/build_live.sh.
#include <algorithm>
#include <limits>
#include <stdexcept>

#include <Eigen/SVD>

#include "analysis/clearance.hpp"
#include "kinematics/ceres_position.hpp"
#include "kinematics/sparse_rank.hpp"

namespace mechkin {
namespace {

[[noreturn]] void NotInPage(const char* what) {
  throw std::runtime_error(std::string("the live page cannot ") + what +
                           ": it runs mechkin's core without it; use the command line (mechkin run, mechkin view)");
}

}  // namespace

SolveSummary SolvePositionCeres(const ConstraintSystem&, const std::vector<int>&, const SolveOptions&, SystemState*,
                                CeresUnitQuaternion) {
  NotInPage("solve with Ceres (--solver ceres)");
}

// SparseRowRank by a dense greedy Gram–Schmidt of the rows in file order (twice
// orthogonalised): a row is dependent when its component orthogonal to the rows kept
// before it is at most rel_tol × the largest row norm — the rule the SuiteSparseQR
// path applies (kinematics/sparse_rank.hpp). The mobility report names its redundant
// equations with it; the page's models are small, so dense is fine.
struct SparseRowRank::Factors {
  Eigen::MatrixXd J;    // the scaled Jacobian
  Eigen::MatrixXd ind;  // its independent rows
};
SparseRowRank::SparseRowRank(const Eigen::SparseMatrix<double>& scaled_J, double rel_tol)
    : f_(std::make_unique<Factors>()) {
  f_->J = Eigen::MatrixXd(scaled_J);
  const Eigen::MatrixXd& J = f_->J;
  const double tol = rel_tol * (J.rows() ? J.rowwise().norm().maxCoeff() : 0.0);
  Eigen::MatrixXd Q(J.cols(), 0);
  smallest_pivot_ = J.rows() ? std::numeric_limits<double>::infinity() : 0.0;
  for (int i = 0; i < J.rows(); ++i) {
    Eigen::VectorXd v = J.row(i).transpose();
    for (int pass = 0; pass < 2; ++pass) v -= Q * (Q.transpose() * v);
    const double r = v.norm();
    if (r > tol) {
      Q.conservativeResize(Eigen::NoChange, Q.cols() + 1);
      Q.col(Q.cols() - 1) = v / r;
      independent_.push_back(i);
      smallest_pivot_ = std::min(smallest_pivot_, r);
    } else {
      dependent_.push_back(i);
      largest_dead_ = std::max(largest_dead_, r);
    }
  }
  if (independent_.empty()) smallest_pivot_ = 0;
  f_->ind = J(independent_, Eigen::all);
  rank_ = static_cast<int>(independent_.size());
  ok_ = true;
}
SparseRowRank::~SparseRowRank() = default;
Eigen::VectorXd SparseRowRank::MinNormSolve(const Eigen::VectorXd& b) const {
  return f_->ind.completeOrthogonalDecomposition().solve(b(independent_));
}
Eigen::VectorXd SparseRowRank::DependentCombination(int d) const {
  return f_->ind.transpose().colPivHouseholderQr().solve(f_->J.row(d).transpose());
}
Eigen::MatrixXd SparseRowRank::NullSpace(int max_count) const {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(f_->J, Eigen::ComputeFullV);
  const int count = std::min<int>(max_count, static_cast<int>(f_->J.cols()) - rank_);
  return svd.matrixV().rightCols(std::max(0, static_cast<int>(f_->J.cols()) - rank_)).leftCols(std::max(0, count));
}
Eigen::SparseMatrix<double> ScaledSparseJacobian(const ConstraintSystem&, const SystemState&, const std::vector<int>&) {
  NotInPage("rank models of more than 200 bodies (SuiteSparseQR)");
}
SolveSummary AssembleMinNormSparse(const ConstraintSystem&, const SolveOptions&, SystemState*) {
  NotInPage("assemble models of more than 200 bodies (SuiteSparseQR)");
}

// The clearance outputs' pairs, so that a file with one is refused by name.
std::vector<ClearancePair> ClearanceOutputPairs(const Model& model) {
  std::vector<ClearancePair> out;
  for (size_t o = 0; o < model.outputs.size(); ++o)
    if (model.outputs[o].kind == OutputKind::Clearance) out.push_back({model.outputs[o].body1, model.outputs[o].body2, int(o)});
  return out;
}
struct ClearanceEvaluator::Geometry {};
ClearanceEvaluator::ClearanceEvaluator(const Model&, std::vector<ClearancePair>) {
  NotInPage("measure clearance outputs (FCL)");
}
ClearanceEvaluator::~ClearanceEvaluator() = default;
ClearanceValue ClearanceEvaluator::Evaluate(const SystemState&, int, bool) const { return {}; }
double ClearanceEvaluator::Reach(BodyIndex) const { return 0; }

}  // namespace mechkin
