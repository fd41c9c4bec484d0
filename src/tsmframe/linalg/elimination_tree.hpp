#pragma once
// The elimination tree of a symmetric pattern (Liu's algorithm with path compression, as
// cs_etree), shared by the solver (the tangent's fill) and the ordering (the joints' top path).

#include <vector>

namespace tsm::linalg {

/// parent[k] of each row k of an n × n symmetric pattern given by its rows' entries left of the
/// diagonal: row k's columns i < k are lower[start[k] .. start[k + 1]) (any order); −1 at a root.
std::vector<int> elimination_tree(const std::vector<int>& start, const std::vector<int>& lower, int n);

}  // namespace tsm::linalg
