#pragma once
// The order in which the nodes are eliminated (the tangent's block order), chosen once per model
// from the node graph, the way frames are built: members are chains of elements between joints.
//
// A node with one or two neighbours lies on a path between joints (nodes with three or more
// neighbours, or none) or dead ends (one neighbour). Each path is eliminated first, from both
// ends toward its middle: no fill beyond one edge per node to the path's end joint, and an
// elimination tree of two independent branches per path — so even a single long member is
// factorised and solved by two threads. Between two dead ends (a free cantilever, a cable) and
// from a dead end toward a joint no fill arises at all. The joints are ordered by approximate
// minimum degree on the graph the paths leave behind (joints joined by a member or by an
// element), and each path goes right before the first of its end joints in that order (the same
// fill as all paths first, but a joint's row is formed while its members' columns are in
// cache). A ring with no joint is opened at one of its nodes.
//
// Compared with minimum degree on the whole node graph: the same fill on frames, elimination
// trees that branch on long members, and a minimum-degree problem the size of the joints only.

#include <vector>

#include "tsmframe/assembly/node_graph.hpp"

namespace tsm::assembly {

/// Node indices in elimination order (a permutation of 0 … n−1).
std::vector<int> elimination_order(const NodeGraph& graph);

}  // namespace tsm::assembly
