#include "tsmframe/assembly/elimination_order.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <utility>

namespace tsm::assembly {
namespace {

constexpr int dead_end = -1;  // a path end without a joint (a node with one neighbour)

/// Joints in approximate minimum degree order on their own graph.
std::vector<int> order_joints(const std::vector<int>& joints, std::vector<std::pair<int, int>>& edges) {
  const int m = static_cast<int>(joints.size());
  if (m == 0) return {};
  for (int j = 0; j < m; ++j) edges.emplace_back(j, j);
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(2 * edges.size());
  for (const auto& [a, b] : edges) {
    entries.emplace_back(a, b, 1.0);
    entries.emplace_back(b, a, 1.0);
  }
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> pattern(m, m);
  pattern.setFromTriplets(entries.begin(), entries.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
  Eigen::AMDOrdering<int>()(pattern, order);
  std::vector<int> nodes(m);
  for (int k = 0; k < m; ++k) nodes[k] = joints[order.indices()[k]];
  return nodes;
}

}  // namespace

std::vector<int> elimination_order(const NodeGraph& g) {
  const int n = static_cast<int>(g.start.size()) - 1;
  // Neighbours other than the node itself (the graph lists each node among its own).
  std::vector<int> degree(n, 0);
  for (int k = 0; k < n; ++k)
    for (int p = g.start[k]; p < g.start[k + 1]; ++p) degree[k] += g.neighbours[p] != k;
  std::vector<char> joint(n), visited(n, 0);
  for (int k = 0; k < n; ++k) joint[k] = degree[k] == 0 || degree[k] >= 3;

  std::vector<int> order;
  order.reserve(n);
  std::vector<std::pair<int, int>> joint_pairs;  // (node, node) joined once the paths are gone
  std::vector<int> ahead, behind, path;

  // Follows a path from `start` (reached from `previous`) until a joint (returned), a dead end
  // (dead_end) or the node `origin` again (a ring: origin returned, flagged by `ring`).
  auto follow = [&](int origin, int previous, int start, std::vector<int>& out, bool& ring) {
    ring = false;
    for (int current = start;;) {
      if (current == origin) {
        ring = true;
        return origin;
      }
      if (joint[current]) return current;
      out.push_back(current);
      visited[current] = 1;
      int next = dead_end;
      for (int p = g.start[current]; p < g.start[current + 1]; ++p) {
        const int k = g.neighbours[p];
        if (k != current && k != previous) next = k;
      }
      if (next == dead_end) return dead_end;
      previous = current;
      current = next;
    }
  };

  for (int s = 0; s < n; ++s) {
    if (joint[s] || visited[s]) continue;
    visited[s] = 1;
    int sides[2] = {dead_end, dead_end}, count = 0;
    for (int p = g.start[s]; p < g.start[s + 1]; ++p)
      if (g.neighbours[p] != s) sides[count++] = g.neighbours[p];
    ahead.clear();
    behind.clear();
    bool ring = false;
    int front = dead_end, back = dead_end;
    back = follow(s, s, sides[0], ahead, ring);
    if (ring) {  // a closed ring of elements: s becomes its joint, the rest a path from s to s
      joint[s] = 1;
      front = back = s;
      path = ahead;
    } else {
      if (count == 2) front = follow(s, s, sides[1], behind, ring);
      path.assign(behind.rbegin(), behind.rend());
      path.push_back(s);
      path.insert(path.end(), ahead.begin(), ahead.end());
    }
    const int m = static_cast<int>(path.size());
    if (front == dead_end && back != dead_end) {  // from the dead end toward the joint: no fill
      order.insert(order.end(), path.begin(), path.end());
    } else if (back == dead_end && front != dead_end) {
      order.insert(order.end(), path.rbegin(), path.rend());
    } else {  // both ends alike: from both ends toward the middle, two branches
      const int h = m / 2;
      for (int i = 0; i < h; ++i) order.push_back(path[i]);
      for (int i = m - 1; i > h; --i) order.push_back(path[i]);
      order.push_back(path[h]);
      if (front != dead_end && front != back) joint_pairs.emplace_back(front, back);
    }
  }

  // The joints, by minimum degree on the graph of joints: elements between joints and the
  // members (paths) that joined two of them.
  std::vector<int> joints, joint_index(n, -1);
  for (int k = 0; k < n; ++k)
    if (joint[k]) {
      joint_index[k] = static_cast<int>(joints.size());
      joints.push_back(k);
    }
  std::vector<std::pair<int, int>> edges;
  for (const int k : joints)
    for (int p = g.start[k]; p < g.start[k + 1]; ++p) {
      const int other = g.neighbours[p];
      if (other > k && joint[other]) edges.emplace_back(joint_index[k], joint_index[other]);
    }
  for (const auto& [a, b] : joint_pairs) edges.emplace_back(joint_index[a], joint_index[b]);
  const std::vector<int> ordered_joints = order_joints(joints, edges);
  order.insert(order.end(), ordered_joints.begin(), ordered_joints.end());
  return order;
}

}  // namespace tsm::assembly
