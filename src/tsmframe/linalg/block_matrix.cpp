#include "tsmframe/linalg/block_matrix.hpp"

#include "tsmframe/linalg/elimination_tree.hpp"
#include "tsmframe/util/first_touch.hpp"

#include <stdexcept>

namespace tsm::linalg {
namespace {

/// Blocks i < k on the paths from each entry (k, i) up the elimination tree: the pattern of row
/// k of L, written to stack[top .. n); returns top (cs_ereach).
int reach(const BlockRows& rows, int k, const std::vector<int>& parent, std::vector<int>& flag, std::vector<int>& stack) {
  const int n = static_cast<int>(parent.size());
  int top = n;
  flag[k] = k;
  for (int t = rows.start[k]; t < rows.start[k + 1]; ++t) {
    int i = rows.column[t];
    int len = 0;
    for (; flag[i] != k; i = parent[i]) {
      stack[len++] = i;  // the path goes to the front of stack (its tail is not yet used)
      flag[i] = k;
    }
    while (len > 0) stack[--top] = stack[--len];
  }
  return top;
}

}  // namespace

BlockRows lower_rows(const BlockMatrix& a) {
  const int n = a.size;
  BlockRows r;
  util::assign_touched(r.start, n + 1, 0);
  for (int c = 0; c < n; ++c)
    for (int p = a.column[c]; p < a.column[c + 1]; ++p)
      if (a.row[p] > c) ++r.start[a.row[p] + 1];
  for (int k = 0; k < n; ++k) r.start[k + 1] += r.start[k];
  util::resize_touched(r.column, r.start[n]);
  util::resize_touched(r.position, r.start[n]);
  std::vector<int> next(r.start.begin(), r.start.end() - 1);
  for (int c = 0; c < n; ++c)  // ascending c: every row lists its columns ascending
    for (int p = a.column[c]; p < a.column[c + 1]; ++p)
      if (a.row[p] > c) {
        r.column[next[a.row[p]]] = c;
        r.position[next[a.row[p]]++] = p;
      }
  return r;
}

FilledPattern filled_pattern(const BlockMatrix& a) {
  const int n = a.size;
  FilledPattern f;
  f.rows = lower_rows(a);
  // Closed under elimination: each column's rows below its first one (the column's parent in
  // the elimination tree) are rows of the parent's column too — checked by one merge per
  // column, and the tree read off the pattern.
  f.parent.assign(n, -1);
  for (int c = 0; c < n; ++c) {
    if (a.row[a.column[c]] != c) throw std::logic_error("block factorisation: a column does not start with its diagonal");
    if (a.column[c + 1] - a.column[c] < 2) continue;
    const int p = f.parent[c] = a.row[a.column[c] + 1];
    int q = a.column[p];
    for (int e = a.column[c] + 2; e < a.column[c + 1]; ++e) {
      while (q < a.column[p + 1] && a.row[q] < a.row[e]) ++q;
      if (q == a.column[p + 1] || a.row[q] != a.row[e])
        throw std::logic_error("block factorisation: the block pattern lacks the fill of its factor (add_fill)");
    }
  }
  if (!a.fill.empty()) {
    f.row_fill.resize(f.rows.position.size());
    for (size_t t = 0; t < f.rows.position.size(); ++t) f.row_fill[t] = a.fill[f.rows.position[t]];
  }
  return f;
}

void add_fill(BlockMatrix& a) {
  const int n = a.size;
  const BlockRows rows = lower_rows(a);
  const std::vector<int> parent = elimination_tree(rows.start, rows.column, n);
  // Row k of L, for every k: (k, i) pairs, k ascending; then counted into columns.
  std::vector<int> flag(n, -1), stack(n, 0), column(n + 1, 0), entries_row, entries_column;
  for (int k = 0; k < n; ++k) {
    const int top = reach(rows, k, parent, flag, stack);
    for (int t = top; t < n; ++t) {
      entries_row.push_back(k);
      entries_column.push_back(stack[t]);
      ++column[stack[t] + 1];
    }
  }
  for (int c = 0; c < n; ++c) column[c + 1] += column[c] + 1;  // + the diagonal
  std::vector<int> row, next(n);
  util::resize_touched(row, column[n]);
  for (int c = 0; c < n; ++c) {
    row[column[c]] = c;  // diagonal first
    next[c] = column[c] + 1;
  }
  for (size_t e = 0; e < entries_row.size(); ++e) row[next[entries_column[e]]++] = entries_row[e];  // rows ascending
  // The fill: the entries of the new pattern that the old one lacks (both ascending per column).
  std::vector<unsigned char> fill;
  util::assign_touched(fill, row.size(), static_cast<unsigned char>(1));
  bool any = false;
  for (int c = 0; c < n; ++c) {
    int q = column[c];
    for (int p = a.column[c]; p < a.column[c + 1]; ++p) {
      for (; row[q] < a.row[p]; ++q) any = true;
      fill[q++] = 0;
    }
    any = any || q < column[c + 1];
  }
  a.column = std::move(column);
  a.row = std::move(row);
  util::resize_touched(a.value, a.row.size());  // the tangent's largest array: its pages mapped in at once
  for (Block& b : a.value) b.setZero();
  if (any) a.fill = std::move(fill);
  else a.fill.clear();
}
}  // namespace tsm::linalg
