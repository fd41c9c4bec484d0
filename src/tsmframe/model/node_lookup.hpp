#pragma once
// A node named by its coordinates: `[x, y]` in a model or study file matches the nodes within
// 1e-9 of the model's size (docs/format.md). One lookup for the reader and the study's records.

#include <Eigen/Core>
#include <string>

#include "tsmframe/model/model.hpp"

namespace tsm {

/// The index of the one node at `point`, or −1 with `problem` saying why there is not exactly
/// one: "no node at [x, y] (the nearest, node 7, is at [x, y], d away)" or "2 nodes at [x, y]
/// (use a node id)".
int node_at(const Model& model, const Eigen::Vector2d& point, std::string& problem);

}  // namespace tsm
