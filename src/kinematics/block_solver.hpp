// Block-by-block solves along the block-triangular structure (block_structure.hpp):
// Newton on each needed diagonal block in order (a small dense LU per block), and
// the derivative solves by forward substitution, x_b = J_bb⁻¹ (RHS_b − Σ J_bc x_c).
// Blocks nothing requested depends on are never evaluated.
#pragma once

#include <memory>

#include "kinematics/factorization.hpp"
#include "math/small_lu.hpp"
#include "kinematics/block_structure.hpp"
#include "kinematics/position.hpp"

namespace mechkin {

class BlockSolver : public Factorization {
 public:
  /// `active`: the independent rows (6n of them); `needed`: per block, from NeededBlocks().
  BlockSolver(const ConstraintSystem& sys, const std::vector<int>& active, const BlockStructure& bs,
              std::vector<char> needed);

  /// Newton on every needed block, in order. Returns the worst block's summary.
  SolveSummary Solve(const SolveOptions& options, SystemState* s);
  /// Factorizes every needed block at the current pose (for the derivative solves).
  bool Factorize(const SystemState& s) override;
  /// Velocity … up to `order` (ω' version) into the bodies of the needed blocks.
  void Derivatives(int order, SystemState* s);
  /// sign(det) of the needed diagonal blocks' product, and a condition estimate
  /// (largest over the blocks).
  double Sign() override;
  double ConditionEstimate() override;
  double SharperConditionEstimate(int) override { return last_condition_; }
  /// The block path serves partial selections only: whole-system solves are
  /// done by the full factorization (NewtonSolver).
  bool SolveLinear(const Eigen::VectorXd&, Eigen::VectorXd*) override { return false; }
  bool SolveLinearTranspose(const Eigen::VectorXd&, Eigen::VectorXd*) override { return false; }
  int blocks() const { return static_cast<int>(blocks_.size()); }
  int solved_blocks() const { return solved_; }

 private:
  double last_condition_ = 0;  // the last ConditionEstimate
  struct Block {
    std::vector<int> rows;                          // global constraint rows
    std::vector<int> cols;                          // global columns (6 per body)
    std::vector<std::pair<int, int>> entries;       // (entry, local row in entry) per block row
    std::vector<int> entry_list;                    // distinct entries
    std::vector<int> bodies;                        // bodies whose columns the block owns
    std::vector<double> scales;
    Eigen::MatrixXd J, lu;                          // block Jacobian and its factors
    Eigen::MatrixXd coupling;                       // J(rows, all columns of the entries' bodies)
    std::vector<int> coupling_cols;                 // the global columns of `coupling`
    SmallLU solver;
    Eigen::VectorXd rhs, x, cond_x, cond_y, cond_b;
    Eigen::VectorXd row_scale, col_scale;           // the dimensionless block W J_bb D (condition)
  };
  void FillBlock(Block& b, const SystemState& s, bool coupling);
  double BlockResidual(Block& b, const SystemState& s);

  const ConstraintSystem& sys_;
  std::vector<Block> blocks_;
  std::vector<int> col_pos_;  // global column → position in its block's cols
  Eigen::VectorXd xk_;        // current order's unknowns (6n)
  int solved_ = 0;
};

}  // namespace mechkin
