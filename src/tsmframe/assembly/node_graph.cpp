#include "tsmframe/assembly/node_graph.hpp"

#include <algorithm>

#include "tsmframe/util/first_touch.hpp"

namespace tsm::assembly {

NodeGraph node_graph(const Model& model, const std::vector<std::pair<int, int>>& extra) {
  const int n = model.node_count();
  NodeGraph g;
  util::assign_touched(g.start, n + 1, 0);
  for (int k = 0; k < n; ++k) g.start[k + 1] = 1;  // itself
  for (const Element& e : model.elements) {
    ++g.start[e.start + 1];
    ++g.start[e.end + 1];
  }
  for (const auto& [a, b] : extra) {
    ++g.start[a + 1];
    ++g.start[b + 1];
  }
  for (int k = 0; k < n; ++k) g.start[k + 1] += g.start[k];
  util::resize_touched(g.neighbours, g.start[n]);
  std::vector<int> fill(g.start.begin(), g.start.end() - 1);
  for (int k = 0; k < n; ++k) g.neighbours[fill[k]++] = k;
  for (const Element& e : model.elements) {
    g.neighbours[fill[e.start]++] = e.end;
    g.neighbours[fill[e.end]++] = e.start;
  }
  for (const auto& [a, b] : extra) {
    g.neighbours[fill[a]++] = b;
    g.neighbours[fill[b]++] = a;
  }
  // Sort and drop duplicates (two elements between the same nodes) in place, compacting.
  int write = 0;
  for (int k = 0; k < n; ++k) {
    const int begin = g.start[k], end = g.start[k + 1];
    std::sort(g.neighbours.begin() + begin, g.neighbours.begin() + end);
    const int first = write;
    for (int p = begin; p < end; ++p)
      if (p == begin || g.neighbours[p] != g.neighbours[p - 1]) g.neighbours[write++] = g.neighbours[p];
    g.start[k] = first;
  }
  g.start[n] = write;
  g.neighbours.resize(write);
  g.neighbours.shrink_to_fit();
  return g;
}

}  // namespace tsm::assembly
