#pragma once
// Hinges made by member releases (Element::release_start/end): the nodes whose rotation no
// element end turns with.

#include <vector>

#include "tsmframe/model/model.hpp"

namespace tsm {

/// Per node: 1 where an element end turns with it (held and not released there). A node turned by
/// none — a hinge, or a node no element holds (a rigid pusher) — has a rotation that means nothing.
std::vector<char> turned_nodes(const Model& model);

/// Per node: 1 where elements hold it but every element end there is released (a hinge). Its
/// rotation is the reader's to fix: it is no support (results' reactions) and holds nothing of
/// the structure (the mechanism check).
std::vector<char> hinge_nodes(const Model& model);

}  // namespace tsm
