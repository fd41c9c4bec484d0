#pragma once
// The two-element contact: a node resting on a beam node where two elements meet at an angle.
// On either element alone the force, normal to that element's chord, pushes the point over the
// node onto the other, and the point hops back and forth; so where it comes back across the node
// it has already come back across in the step, both elements take it — each carries a contact
// element with the node held at that beam node, and the force lies between the two chords'
// normals (README, Contact). At a converged iterate where one side pulls, that side lets go and
// the node goes on along the other element, held at the node until it has clearly gone on; where
// both pull, the contact lets go. Everything the vertex needs is here; ContactState::vertex
// holds its second element.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"
#include "tsmframe/contact/occupancy.hpp"

namespace tsm::contact {

/// The beam node shared by a vertex's two elements.
int vertex_node(const Model& model, const ContactState& state);

/// Whether a point handed over from `from` across beam node `node` onto `to` comes to rest on
/// the node: it comes back the way it went, across the node it already came back across in this
/// step, at most vertex_reach past it on either element (`beyond_from`, `into_to`: fractions of
/// the elements), where the contact's edge keeps the law finite.
bool comes_to_rest_on_node(const ContactState& state, int direction, int node, double edge, double beyond_from,
                           double into_to);
/// The contact on element `state.element` becomes a vertex at beam node `node` with element `to`
/// (the node on its side `to_side`); reported on the element that ends at the node.
void enter_vertex(const Model& model, int node, int to, int to_side, ContactState& state);

/// The vertex's second contact element's force, read with the first's (already in `state`): the
/// contact is reported on the element ending at the node, at its end, with the compression of
/// the resultant of both forces.
void read_vertex(const Model& model, double partner_Y, const Eigen::Vector2d& partner_push, ContactState& state);

/// At a converged iterate: a vertex where a side pulls opens — that side lets go (both: the
/// contact is released). Returns whether it opened; the elements it leaves are left in `occupancy`.
bool open_vertex(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& displacements,
                 const std::vector<double>& rotations, ContactState& state, Occupancy& occupancy);

}  // namespace tsm::contact
