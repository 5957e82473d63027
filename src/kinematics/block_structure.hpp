// Block-triangular structure of a square constraint system (issue: speed —
// solve only what the question needs).
//
// A maximum matching pairs each equation with an unknown; the strongly connected
// components of the "equation needs the unknown matched to another equation"
// graph (Tarjan) are the diagonal blocks of the block-triangular form
// (Dulmage–Mendelsohn fine decomposition of a structurally nonsingular matrix).
// Tarjan emits a component after every component it depends on, so `blocks` is
// already in solve order.
#pragma once

#include <Eigen/Sparse>
#include <vector>

namespace mechkin {

struct BlockStructure {
  std::vector<std::vector<int>> rows;  // per block: positions in the matrix's rows
  std::vector<std::vector<int>> cols;  // per block: matched columns
  std::vector<std::vector<int>> deps;  // per block: earlier blocks it reads
  std::vector<int> block_of_col;
  int size() const { return static_cast<int>(rows.size()); }
};

/// Fails (returns false) when the pattern is structurally singular.
bool FindBlockStructure(const Eigen::SparseMatrix<double>& pattern, BlockStructure* out);

/// Blocks needed to know `cols`: the blocks owning them and everything they depend on.
std::vector<char> NeededBlocks(const BlockStructure& bs, const std::vector<int>& cols);

}  // namespace mechkin
