// The elimination order by members (assembly/elimination_order): a permutation for any node
// graph (chains, rings, stars, isolated nodes, repeated elements, a lattice), members' paths
// from both ends toward their middle with no fill, each right before the first of its joints.
#include <gtest/gtest.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <numeric>
#include <vector>

#include "tsmframe/assembly/elimination_order.hpp"
#include "tsmframe/linalg/block_ldlt.hpp"

namespace {

using tsm::assembly::NodeGraph;

// A node graph (each node among its own neighbours, sorted) from an edge list.
NodeGraph graph(int n, const std::vector<std::pair<int, int>>& edges) {
  std::vector<std::vector<int>> adjacent(n);
  for (int k = 0; k < n; ++k) adjacent[k].push_back(k);
  for (const auto& [a, b] : edges) {
    adjacent[a].push_back(b);
    adjacent[b].push_back(a);
  }
  NodeGraph g;
  g.start.push_back(0);
  for (auto& list : adjacent) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    g.neighbours.insert(g.neighbours.end(), list.begin(), list.end());
    g.start.push_back(static_cast<int>(g.neighbours.size()));
  }
  return g;
}

std::vector<std::pair<int, int>> chain(int first, int last) {
  std::vector<std::pair<int, int>> edges;
  for (int k = first; k < last; ++k) edges.emplace_back(k, k + 1);
  return edges;
}

void expect_permutation(const std::vector<int>& order, int n) {
  ASSERT_EQ(static_cast<int>(order.size()), n);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (int k = 0; k < n; ++k) ASSERT_EQ(sorted[k], k);
}

// Blocks in the given order: the lower pattern of the graph, with its fill (add_fill); `entries`
// gets the count before the fill.
tsm::linalg::BlockMatrix pattern_in(const NodeGraph& g, const std::vector<int>& order, size_t* entries = nullptr) {
  const int n = static_cast<int>(order.size());
  std::vector<int> position(n);
  for (int k = 0; k < n; ++k) position[order[k]] = k;
  std::vector<std::vector<int>> rows(n);
  for (int node = 0; node < n; ++node)
    for (int p = g.start[node]; p < g.start[node + 1]; ++p) {
      const int a = position[node], b = position[g.neighbours[p]];
      if (b >= a) rows[a].push_back(b);
    }
  tsm::linalg::BlockMatrix m;
  m.size = n;
  m.column.push_back(0);
  for (auto& r : rows) {
    std::sort(r.begin(), r.end());
    m.row.insert(m.row.end(), r.begin(), r.end());
    m.column.push_back(static_cast<int>(m.row.size()));
  }
  if (entries) *entries = m.row.size();
  tsm::linalg::add_fill(m);
  return m;
}

// How many entries elimination in the given order adds.
size_t fill_of(const NodeGraph& g, const std::vector<int>& order) {
  size_t entries = 0;
  const tsm::linalg::BlockMatrix m = pattern_in(g, order, &entries);
  return m.row.size() - entries;
}

// A grid of bays × bays members of `divisions` elements each, its joints numbered first.
NodeGraph lattice(int bays, int divisions) {
  const int joints = (bays + 1) * (bays + 1);
  std::vector<std::pair<int, int>> edges;
  int next = joints;
  auto member = [&](int a, int b) {
    int previous = a;
    for (int d = 1; d < divisions; ++d) {
      edges.emplace_back(previous, next);
      previous = next++;
    }
    edges.emplace_back(previous, b);
  };
  for (int y = 0; y <= bays; ++y)
    for (int x = 0; x < bays; ++x) member(y * (bays + 1) + x, y * (bays + 1) + x + 1);
  for (int y = 0; y < bays; ++y)
    for (int x = 0; x <= bays; ++x) member(y * (bays + 1) + x, (y + 1) * (bays + 1) + x);
  return graph(next, edges);
}

TEST(EliminationOrder, AChainGoesFromBothEndsToItsMiddleWithoutFill) {
  const int n = 1001;
  const NodeGraph g = graph(n, chain(0, n - 1));
  const std::vector<int> order = tsm::assembly::elimination_order(g);
  expect_permutation(order, n);
  EXPECT_EQ(order.front(), 0);
  EXPECT_EQ(order[n / 2], n - 1);  // the second branch starts at the far end
  EXPECT_EQ(order.back(), n / 2);  // the middle last
  EXPECT_EQ(fill_of(g, order), 0u);
  // Its elimination tree has two branches of ~n/2: two parallel tasks.
  tsm::linalg::BlockLDLT ldlt;
  ldlt.analyze(pattern_in(g, order));
  EXPECT_EQ(ldlt.task_count(), 2);
  EXPECT_EQ(ldlt.rows_above_tasks(), 1);
}

TEST(EliminationOrder, AChainWithoutJointsGoesFromBothEndsTowardItsMiddle) {
  // 0–1–2–3–4: the first half from node 0, the second from node 4, the middle last.
  EXPECT_EQ(tsm::assembly::elimination_order(graph(5, chain(0, 4))), (std::vector<int>{0, 1, 4, 3, 2}));
}

TEST(EliminationOrder, MembersWithADeadEndGoFromItTowardTheirJoint) {
  // Joint 0 with three members of two elements: 0–1–2, 0–3–4, 0–5–6. Each from its free end
  // toward the joint (no fill), in the order of their first nodes, then the joint.
  const NodeGraph g = graph(7, {{0, 1}, {1, 2}, {0, 3}, {3, 4}, {0, 5}, {5, 6}});
  EXPECT_EQ(tsm::assembly::elimination_order(g), (std::vector<int>{2, 1, 4, 3, 6, 5, 0}));
}

TEST(EliminationOrder, ARingIsOpenedAtItsFirstNodeWhichGoesLast) {
  // 0–1–2–3–4–5–0: node 0 becomes the ring's joint, the path 1 … 5 goes from both ends toward
  // its middle node 3.
  std::vector<std::pair<int, int>> edges = chain(0, 5);
  edges.emplace_back(5, 0);
  EXPECT_EQ(tsm::assembly::elimination_order(graph(6, edges)), (std::vector<int>{1, 2, 5, 4, 3, 0}));
}

TEST(EliminationOrder, PathsWithoutAJointComeBeforeTheJoints) {
  // Node 0 has no element (a joint of its own); the chain 1–2–3 has no joint: it comes first.
  EXPECT_EQ(tsm::assembly::elimination_order(graph(4, chain(1, 3))), (std::vector<int>{1, 3, 2, 0}));
}

TEST(EliminationOrder, AMemberBetweenTwoJointsGoesFromTheSideOfTheFirstJoint) {
  // Joint 0 (ends 1, 2 hanging off it) and joint 6 (ends 7, 8) joined by the member 0–3–4–5–6.
  // Two joints form the top path: every member goes before both, in the order of their first
  // nodes, the member between them starting next to whichever joint minimum degree takes first.
  const NodeGraph g = graph(9, {{0, 1}, {0, 2}, {0, 3}, {3, 4}, {4, 5}, {5, 6}, {6, 7}, {6, 8}});
  const std::vector<int> order = tsm::assembly::elimination_order(g);
  ASSERT_EQ(order.size(), 9u);
  if (order[7] == 0) EXPECT_EQ(order, (std::vector<int>{1, 2, 3, 4, 5, 7, 8, 0, 6}));
  else EXPECT_EQ(order, (std::vector<int>{1, 2, 5, 4, 3, 7, 8, 6, 0}));
}

TEST(EliminationOrder, AnyGraphGivesAPermutation) {
  // A ring (no joint), a star, isolated nodes, two elements between the same nodes, a chain
  // hanging off a joint, a single element: all in one graph.
  std::vector<std::pair<int, int>> edges = chain(0, 9);
  edges.emplace_back(9, 0);                                              // ring 0..9
  for (int k = 11; k < 16; ++k) edges.emplace_back(10, k);               // star around 10
  edges.emplace_back(20, 21), edges.emplace_back(21, 20);                // a doubled element
  for (const auto& e : chain(30, 40)) edges.push_back(e);                // a chain 30..40 …
  edges.emplace_back(40, 41), edges.emplace_back(40, 42);                // … ending at a joint
  edges.emplace_back(50, 51);                                            // one element
  const int n = 55;                                                      // 16..19, 22..29, 43..49, 52..54 isolated
  const NodeGraph g = graph(n, edges);
  const std::vector<int> order = tsm::assembly::elimination_order(g);
  expect_permutation(order, n);
  // The ring is opened at a node that becomes its joint; each of its other 9 nodes, eliminated
  // from both ends, joins the joint once — except the two next to it (already joined) and the
  // middle (whose edge to the joint its neighbour made): 7 fill entries. Nothing else fills.
  EXPECT_EQ(fill_of(g, order), 7u);
}

TEST(EliminationOrder, ALatticesMembersComeRightBeforeTheirFirstJointWithNoMoreFillThanMinimumDegree) {
  // A 12 × 12-bay grid of members of 5 elements each.
  const int bays = 12, divisions = 5;
  const NodeGraph g = lattice(bays, divisions);
  const int next = static_cast<int>(g.start.size()) - 1;
  const std::vector<int> order = tsm::assembly::elimination_order(g);
  expect_permutation(order, next);
  // Corner joints have two neighbours: they lie on paths. Every member node comes before both
  // joints its member ends at (no fill beyond joining them), and the first joint after it in the
  // order is one of those two: each member right before its first joint, for the cache; and
  // along the member from that joint's side. Except where that joint is one of the joints the
  // order ends with (the last separator, kept consecutive for its dense factorisation): then
  // the member comes before all of those.
  std::vector<int> position(next);
  for (int k = 0; k < next; ++k) position[order[k]] = k;
  auto degree = [&](int k) { return g.start[k + 1] - g.start[k] - 1; };
  std::vector<int> next_joint(next + 1, -1);  // by position: the first joint at or after it
  for (int q = next - 1; q >= 0; --q) next_joint[q] = degree(order[q]) >= 3 ? order[q] : next_joint[q + 1];
  int last_joints = next;  // where the order's final run of joints starts
  while (last_joints > 0 && degree(order[last_joints - 1]) >= 3) --last_joints;
  EXPECT_GE(next - last_joints, bays / 2);  // a separator's worth (11 of the 13 × 13 joints' grid)
  int members_checked = 0;
  for (int k = 0; k < next; ++k) {
    if (degree(k) >= 3) continue;
    std::vector<int> ends, towards;  // the joints reached walking the path both ways, and the first step to each
    for (int p = g.start[k]; p < g.start[k + 1]; ++p) {
      int previous = k, current = g.neighbours[p];
      if (current == k) continue;
      const int first_step = current;
      while (degree(current) < 3) {
        int step = -1;
        for (int r = g.start[current]; r < g.start[current + 1]; ++r)
          if (g.neighbours[r] != current && g.neighbours[r] != previous) step = g.neighbours[r];
        if (step < 0) break;  // a dead end
        previous = current;
        current = step;
      }
      if (degree(current) >= 3) {
        ends.push_back(current);
        towards.push_back(first_step);
      }
    }
    for (const int joint : ends) EXPECT_LT(position[k], position[joint]) << "node " << k;
    if (ends.empty()) continue;
    const int first_end = ends.size() == 2 && position[ends[1]] < position[ends[0]] ? ends[1] : ends[0];
    if (position[first_end] >= last_joints) EXPECT_EQ(next_joint[position[k]], order[last_joints]) << "node " << k;
    else EXPECT_TRUE(std::find(ends.begin(), ends.end(), next_joint[position[k]]) != ends.end()) << "node " << k;
    // Eliminated from the first joint's side: the member's nodes come in order along it, so the
    // later joint's row holds only the member's last node (the earlier joint's, all of them).
    if (ends.size() == 2) {
      const int later = position[ends[0]] > position[ends[1]] ? 0 : 1;
      EXPECT_GT(position[towards[later]], position[k]) << "node " << k;
    }
    ++members_checked;
  }
  EXPECT_GT(members_checked, 2 * bays * bays * (divisions - 1));
  // Against minimum degree on the whole node graph (Eigen's AMD, the order before this one).
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> pattern(next, next);
  std::vector<Eigen::Triplet<double, int>> entries;
  for (int k = 0; k < next; ++k)
    for (int p = g.start[k]; p < g.start[k + 1]; ++p) entries.emplace_back(g.neighbours[p], k, 1.0);
  pattern.setFromTriplets(entries.begin(), entries.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> amd;
  Eigen::AMDOrdering<int>()(pattern, amd);
  const std::vector<int> amd_order(amd.indices().data(), amd.indices().data() + next);
  const size_t fill = fill_of(g, order), amd_fill = fill_of(g, amd_order);
  std::printf("[figure] 12x12 lattice, 5 elements per member: fill %zu (minimum degree: %zu) for %d nodes\n", fill,
              amd_fill, next);
  EXPECT_LE(fill, amd_fill * 11 / 10);
}

TEST(EliminationOrder, ALatticesLastSeparatorIsFactorisedAsOneDenseBlock) {
  // 40 × 40 bays: the last separator of the joints' grid is ~40 joints, whose rows fill in to a
  // dense triangle. Kept consecutive and last (no member between them), they are factorised as
  // one dense matrix, in parallel — with one element per member as with several.
  for (const int divisions : {1, 3}) {
    const NodeGraph g = lattice(40, divisions);
    tsm::linalg::BlockLDLT ldlt;
    ldlt.analyze(pattern_in(g, tsm::assembly::elimination_order(g)));
    EXPECT_GE(ldlt.rows_in_dense_paths(), 32) << divisions << " elements per member";
  }
}

}  // namespace
