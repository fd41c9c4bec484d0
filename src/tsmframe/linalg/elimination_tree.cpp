#include "tsmframe/linalg/elimination_tree.hpp"

namespace tsm::linalg {

std::vector<int> elimination_tree(const std::vector<int>& start, const std::vector<int>& lower, int n) {
  std::vector<int> parent(n, -1), ancestor(n, -1);
  for (int k = 0; k < n; ++k)
    for (int t = start[k]; t < start[k + 1]; ++t)
      for (int i = lower[t]; i != -1 && i < k;) {
        const int next = ancestor[i];
        ancestor[i] = k;
        if (next == -1) {
          parent[i] = k;
          break;
        }
        i = next;
      }
  return parent;
}

}  // namespace tsm::linalg
