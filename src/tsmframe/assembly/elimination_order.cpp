#include "tsmframe/assembly/elimination_order.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <iterator>
#include <utility>

#include "tsmframe/linalg/elimination_tree.hpp"

namespace tsm::assembly {
namespace {

constexpr int dead_end = -1;  // a path end without a joint (a node with one neighbour)

/// Per node: a joint (no neighbour other than itself, or three or more) or a node on a path.
std::vector<char> joint_nodes(const NodeGraph& g, int n) {
  // Neighbours other than the node itself (the graph lists each node among its own).
  std::vector<int> degree(n, 0);
  for (int k = 0; k < n; ++k)
    for (int p = g.start[k]; p < g.start[k + 1]; ++p) degree[k] += g.neighbours[p] != k;
  std::vector<char> joint(n);
  for (int k = 0; k < n; ++k) joint[k] = degree[k] == 0 || degree[k] >= 3;
  return joint;
}

/// The paths between joints, each in its elimination order: path q's nodes are
/// nodes[start[q] .. start[q + 1]), the joints at its ends ends[q] (dead_end where it has none).
struct Paths {
  std::vector<int> nodes, start = std::vector<int>(1, 0);
  std::vector<std::pair<int, int>> ends;
  std::vector<std::pair<int, int>> joint_pairs;  // (node, node) joined once the paths are gone

  /// Appends `path` (its nodes from front to back) in its elimination order. From a dead end
  /// toward a joint no fill arises; both ends alike, it goes from both toward its middle.
  void add(const std::vector<int>& path, int front, int back) {
    const int m = static_cast<int>(path.size());
    if (front == dead_end && back != dead_end) {  // from the dead end toward the joint: no fill
      nodes.insert(nodes.end(), path.begin(), path.end());
    } else if (back == dead_end && front != dead_end) {
      nodes.insert(nodes.end(), path.rbegin(), path.rend());
    } else if (front != dead_end && front != back) {
      // A member between two joints: kept from front to back here, and placed (order_nodes) from
      // the side of the joint eliminated first — its row takes the member's fill, the later
      // joint's row only the member's last node.
      nodes.insert(nodes.end(), path.begin(), path.end());
      joint_pairs.emplace_back(front, back);
    } else {  // both ends alike (a ring, or no joint at all): from both ends toward the middle, two branches
      const int h = m / 2;
      for (int i = 0; i < h; ++i) nodes.push_back(path[i]);
      for (int i = m - 1; i > h; --i) nodes.push_back(path[i]);
      nodes.push_back(path[h]);
    }
    start.push_back(static_cast<int>(nodes.size()));
    ends.emplace_back(front, back);
  }
};

/// Walks the node graph along the paths between joints, each path node once. A closed ring of
/// elements with no joint is opened at the node the walk starts from, which becomes its joint.
class PathWalker {
 public:
  PathWalker(const NodeGraph& g, std::vector<char>& joint) : g_(g), joint_(joint), visited_(joint.size(), 0) {}

  bool visited(int node) const { return visited_[node]; }

  /// The path through the path node `s` into `paths`, with its end joints.
  void trace(int s, Paths& paths) {
    visited_[s] = 1;
    int sides[2] = {dead_end, dead_end}, count = 0;
    for (int p = g_.start[s]; p < g_.start[s + 1]; ++p)
      if (g_.neighbours[p] != s) sides[count++] = g_.neighbours[p];
    ahead_.clear();
    behind_.clear();
    bool ring = false;
    int front = dead_end, back = dead_end;
    back = follow(s, s, sides[0], ahead_, ring);
    if (ring) {  // a closed ring of elements: s becomes its joint, the rest a path from s to s
      joint_[s] = 1;
      front = back = s;
      path_ = ahead_;
    } else {
      if (count == 2) front = follow(s, s, sides[1], behind_, ring);
      path_.assign(behind_.rbegin(), behind_.rend());
      path_.push_back(s);
      path_.insert(path_.end(), ahead_.begin(), ahead_.end());
    }
    paths.add(path_, front, back);
  }

 private:
  /// Follows a path from `start` (reached from `previous`) until a joint (returned), a dead end
  /// (dead_end) or the node `origin` again (a ring: origin returned, flagged by `ring`).
  int follow(int origin, int previous, int start, std::vector<int>& out, bool& ring) {
    ring = false;
    for (int current = start;;) {
      if (current == origin) {
        ring = true;
        return origin;
      }
      if (joint_[current]) return current;
      out.push_back(current);
      visited_[current] = 1;
      int next = dead_end;
      for (int p = g_.start[current]; p < g_.start[current + 1]; ++p) {
        const int k = g_.neighbours[p];
        if (k != current && k != previous) next = k;
      }
      if (next == dead_end) return dead_end;
      previous = current;
      current = next;
    }
  }

  const NodeGraph& g_;
  std::vector<char>& joint_;
  std::vector<char> visited_;
  std::vector<int> ahead_, behind_, path_;
};

/// Every path of the graph, in node order of the path node each is first met at. Rings without
/// a joint get one (`joint` is updated).
Paths trace_paths(const NodeGraph& g, std::vector<char>& joint) {
  const int n = static_cast<int>(joint.size());
  Paths paths;
  paths.nodes.reserve(n);
  PathWalker walker(g, joint);
  for (int s = 0; s < n; ++s) {
    if (joint[s] || walker.visited(s)) continue;
    walker.trace(s, paths);
  }
  return paths;
}

/// The joints (ascending node) and each node's index among them (−1 for a path node).
struct Joints {
  std::vector<int> nodes, index;
};

Joints number_joints(const std::vector<char>& joint) {
  const int n = static_cast<int>(joint.size());
  Joints joints;
  joints.index.assign(n, -1);
  for (int k = 0; k < n; ++k)
    if (joint[k]) {
      joints.index[k] = static_cast<int>(joints.nodes.size());
      joints.nodes.push_back(k);
    }
  return joints;
}

/// The graph of joints, in joint indices: elements between joints, then the members (paths)
/// that joined two of them.
std::vector<std::pair<int, int>> joint_graph(const NodeGraph& g, const std::vector<char>& joint, const Joints& joints,
                                             const std::vector<std::pair<int, int>>& joint_pairs) {
  std::vector<std::pair<int, int>> edges;
  for (const int k : joints.nodes)
    for (int p = g.start[k]; p < g.start[k + 1]; ++p) {
      const int other = g.neighbours[p];
      if (other > k && joint[other]) edges.emplace_back(joints.index[k], joints.index[other]);
    }
  for (const auto& [a, b] : joint_pairs) edges.emplace_back(joints.index[a], joints.index[b]);
  return edges;
}

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

/// Where the top path of the joints' elimination tree starts, in the joints' order: the last
/// joints each of which is the only child of the next (a separator that ends up one dense block,
/// BlockLDLT's dense path). `ordered` is the joints' elimination order (nodes), `joint_index`
/// maps a node to its joint index, `edges` is the joints' graph in joint indices.
int top_path_start(const std::vector<int>& ordered, const std::vector<int>& joint_index,
                   const std::vector<std::pair<int, int>>& edges) {
  const int m = static_cast<int>(ordered.size());
  if (m == 0) return 0;
  std::vector<int> rank_of(m);  // joint index -> place in the order
  for (int r = 0; r < m; ++r) rank_of[joint_index[ordered[r]]] = r;
  std::vector<int> start(m + 1, 0), lower;  // per rank: the neighbours of lower rank
  for (const auto& [a, b] : edges) {
    const int ra = rank_of[a], rb = rank_of[b];
    if (ra != rb) ++start[std::max(ra, rb) + 1];
  }
  for (int r = 0; r < m; ++r) start[r + 1] += start[r];
  lower.resize(start[m]);
  std::vector<int> next(start.begin(), start.end() - 1);
  for (const auto& [a, b] : edges) {
    const int ra = rank_of[a], rb = rank_of[b];
    if (ra != rb) lower[next[std::max(ra, rb)]++] = std::min(ra, rb);
  }
  const std::vector<int> parent = linalg::elimination_tree(start, lower, m);
  std::vector<int> children(m, 0);
  for (int r = 0; r < m; ++r)
    if (parent[r] >= 0) ++children[parent[r]];
  int r = m - 1;
  while (r > 0 && children[r] == 1 && parent[r - 1] == r) --r;
  return r;
}

/// Each path's anchor: the place in the joints' order of the first of its end joints to be
/// eliminated, the path going right before it; −1 for a path without a joint. Its nodes touch
/// only one another and those joints, so anywhere before both gives the same fill and the same
/// tree, and there the factorisation forms the joint's row while the path's columns are still in
/// cache (a lattice's joints read their members' columns scattered over the whole factor
/// otherwise).
std::vector<int> path_anchors(const Paths& paths, const std::vector<int>& rank, int top_start) {
  std::vector<int> anchor(paths.ends.size(), -1);
  for (size_t q = 0; q < paths.ends.size(); ++q) {
    const auto [front, back] = paths.ends[q];
    int first = -1;
    for (const int end : {front, back})
      if (end != dead_end && (first < 0 || rank[end] < first)) first = rank[end];
    // Not between the joints of the top path: they stay consecutive, so that BlockLDLT factorises
    // them as one dense block (a lattice's last separator); its members come before all of them.
    if (first > top_start) first = top_start;
    anchor[q] = first;
  }
  return anchor;
}

/// All nodes in elimination order: the paths without a joint first, then per joint in its order
/// the paths anchored to it (ascending path) and the joint. A member between two joints goes
/// from the side of the joint eliminated first: that joint's row takes the member's fill while
/// its columns are hot, the later joint's row (far from them) only the last node — the same fill
/// as from both ends, 2–4 % less time factorising the lattice.
std::vector<int> order_nodes(const Paths& paths, const std::vector<int>& anchor, const std::vector<int>& ordered_joints,
                             const std::vector<int>& rank, int n) {
  const int count = static_cast<int>(paths.ends.size());
  std::vector<int> order;
  order.reserve(n);
  std::vector<int> anchored_start(ordered_joints.size() + 1, 0), anchored;
  for (int q = 0; q < count; ++q) {
    if (anchor[q] < 0) order.insert(order.end(), paths.nodes.begin() + paths.start[q], paths.nodes.begin() + paths.start[q + 1]);
    else ++anchored_start[anchor[q] + 1];
  }
  for (size_t r = 0; r < ordered_joints.size(); ++r) anchored_start[r + 1] += anchored_start[r];
  anchored.resize(anchored_start.back());
  std::vector<int> next(anchored_start.begin(), anchored_start.end() - 1);
  for (int q = 0; q < count; ++q)
    if (anchor[q] >= 0) anchored[next[anchor[q]]++] = q;  // ascending q within a joint
  for (size_t r = 0; r < ordered_joints.size(); ++r) {
    for (int e = anchored_start[r]; e < anchored_start[r + 1]; ++e) {
      const int q = anchored[e];
      const auto [front, back] = paths.ends[q];
      const auto begin = paths.nodes.begin() + paths.start[q], end = paths.nodes.begin() + paths.start[q + 1];
      if (front != dead_end && back != dead_end && front != back && rank[back] < rank[front])
        order.insert(order.end(), std::make_reverse_iterator(end), std::make_reverse_iterator(begin));
      else
        order.insert(order.end(), begin, end);
    }
    order.push_back(ordered_joints[r]);
  }
  return order;
}

}  // namespace

std::vector<int> elimination_order(const NodeGraph& g) {
  const int n = static_cast<int>(g.start.size()) - 1;
  std::vector<char> joint = joint_nodes(g, n);
  const Paths paths = trace_paths(g, joint);
  // The joints, by minimum degree on the graph of joints: elements between joints and the
  // members (paths) that joined two of them.
  const Joints joints = number_joints(joint);
  std::vector<std::pair<int, int>> edges = joint_graph(g, joint, joints, paths.joint_pairs);
  const std::vector<int> ordered_joints = order_joints(joints.nodes, edges);
  const int top_start = top_path_start(ordered_joints, joints.index, edges);
  // Each path just before the first of its end joints to be eliminated; paths without a joint first.
  std::vector<int> rank(n, -1);
  for (size_t r = 0; r < ordered_joints.size(); ++r) rank[ordered_joints[r]] = static_cast<int>(r);
  return order_nodes(paths, path_anchors(paths, rank, top_start), ordered_joints, rank, n);
}

}  // namespace tsm::assembly
