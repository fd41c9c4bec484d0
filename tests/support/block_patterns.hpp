#pragma once
// Block patterns like a frame's for the block factorisations' tests (block_ldlt, block_lu).

#include <algorithm>
#include <random>
#include <set>
#include <vector>

namespace tsm::test {

// `chains` chains of n / chains blocks, each with n / 3 / chains random couplings inside it, and
// `bridges` couplings between chains (which put rows above the factorisation's subtrees); then
// `top` blocks numbered last, each coupled to all the others and to three random chain blocks
// (a dense separator at the top of the elimination tree, like a frame lattice's last one).
inline std::vector<std::set<int>> chain_pattern(int n, int chains, int bridges, std::mt19937& random, int top = 0) {
  const int length = n / chains;
  std::uniform_int_distribution<int> block(0, length - 1), chain(0, chains - 1), any(0, n - 1);
  std::vector<std::set<int>> rows(n + top);  // rows ≥ c of column c
  for (int t = n; t < n + top; ++t) {
    for (int u = t; u < n + top; ++u) rows[t].insert(u);
    for (int extra = 0; extra < 3; ++extra) rows[any(random)].insert(t);
  }
  for (int c = 0; c < n; ++c) {
    rows[c].insert(c);
    if (c + 1 < n && (c + 1) % length != 0) rows[c].insert(c + 1);
  }
  for (int k = 0; k < chains; ++k)
    for (int extra = 0; extra < length / 3; ++extra) {
      const int a = k * length + block(random), b = k * length + block(random);
      rows[std::min(a, b)].insert(std::max(a, b));
    }
  for (int extra = 0; extra < bridges; ++extra) {
    const int a = chain(random) * length + block(random), b = chain(random) * length + block(random);
    rows[std::min(a, b)].insert(std::max(a, b));
  }
  return rows;
}

}  // namespace tsm::test
