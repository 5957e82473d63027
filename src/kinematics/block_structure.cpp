#include "kinematics/block_structure.hpp"

#include <algorithm>
#include <functional>

namespace mechkin {

bool FindBlockStructure(const Eigen::SparseMatrix<double>& J, BlockStructure* out) {
  const int m = static_cast<int>(J.rows()), n = static_cast<int>(J.cols());
  if (m != n) return false;
  std::vector<std::vector<int>> adj(m);
  for (int c = 0; c < n; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, c); it; ++it) adj[it.row()].push_back(c);
  // Maximum matching: greedy start, then augmenting paths (Kuhn).
  std::vector<int> row_of_col(n, -1), col_of_row(m, -1), seen(n, -1);
  for (int r = 0; r < m; ++r)
    for (int c : adj[r])
      if (row_of_col[c] < 0) { row_of_col[c] = r; col_of_row[r] = c; break; }
  std::function<bool(int, int)> augment = [&](int r, int stamp) {
    for (int c : adj[r]) {
      if (seen[c] == stamp) continue;
      seen[c] = stamp;
      if (row_of_col[c] < 0 || augment(row_of_col[c], stamp)) {
        row_of_col[c] = r;
        col_of_row[r] = c;
        return true;
      }
    }
    return false;
  };
  for (int r = 0; r < m; ++r)
    if (col_of_row[r] < 0 && !augment(r, r)) return false;
  // Tarjan's strongly connected components on rows: r → row_of_col[c] for c in adj[r].
  std::vector<int> index(m, -1), low(m, 0), comp(m, -1), stack;
  std::vector<char> on_stack(m, 0);
  int counter = 0;
  out->rows.clear();
  std::function<void(int)> visit = [&](int r) {
    index[r] = low[r] = counter++;
    stack.push_back(r);
    on_stack[r] = 1;
    for (int c : adj[r]) {
      const int q = row_of_col[c];
      if (q == r) continue;
      if (index[q] < 0) { visit(q); low[r] = std::min(low[r], low[q]); }
      else if (on_stack[q]) low[r] = std::min(low[r], index[q]);
    }
    if (low[r] == index[r]) {
      std::vector<int> block;
      int q;
      do {
        q = stack.back();
        stack.pop_back();
        on_stack[q] = 0;
        comp[q] = static_cast<int>(out->rows.size());
        block.push_back(q);
      } while (q != r);
      std::sort(block.begin(), block.end());
      out->rows.push_back(block);
    }
  };
  for (int r = 0; r < m; ++r)
    if (index[r] < 0) visit(r);
  const int B = static_cast<int>(out->rows.size());
  out->cols.assign(B, {});
  out->deps.assign(B, {});
  out->block_of_col.assign(n, -1);
  for (int b = 0; b < B; ++b) {
    for (int r : out->rows[b]) {
      out->cols[b].push_back(col_of_row[r]);
      out->block_of_col[col_of_row[r]] = b;
    }
    std::sort(out->cols[b].begin(), out->cols[b].end());
  }
  for (int b = 0; b < B; ++b) {
    for (int r : out->rows[b])
      for (int c : adj[r]) {
        const int d = comp[row_of_col[c]];
        if (d != b) out->deps[b].push_back(d);
      }
    std::sort(out->deps[b].begin(), out->deps[b].end());
    out->deps[b].erase(std::unique(out->deps[b].begin(), out->deps[b].end()), out->deps[b].end());
  }
  return true;
}

std::vector<char> NeededBlocks(const BlockStructure& bs, const std::vector<int>& cols) {
  std::vector<char> need(bs.size(), 0);
  std::vector<int> todo;
  for (int c : cols)
    if (c >= 0 && c < static_cast<int>(bs.block_of_col.size()) && !need[bs.block_of_col[c]]) {
      need[bs.block_of_col[c]] = 1;
      todo.push_back(bs.block_of_col[c]);
    }
  while (!todo.empty()) {
    const int b = todo.back();
    todo.pop_back();
    for (int d : bs.deps[b])
      if (!need[d]) { need[d] = 1; todo.push_back(d); }
  }
  return need;
}

}  // namespace mechkin
