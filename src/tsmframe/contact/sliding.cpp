#include "tsmframe/contact/sliding.hpp"

#include "tsmframe/contact/release.hpp"
#include "tsmframe/contact/sides.hpp"
#include "tsmframe/contact/vertex.hpp"

namespace tsm::contact {

HandOver hand_over(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& D,
                   const std::vector<double>& rotations, bool at_convergence, ContactState& state,
                   Occupancy& occupancy) {
  // The point has left its element: hand it on to the neighbour at that end, and on while it
  // is still beyond, but not farther than max(one element, 5 % of the model's size) per
  // iterate (coarse meshes: one element; fine meshes slide many elements per iterate), and over
  // no more hand-overs than the model has elements: where the model's size is set by a node far
  // from the beam, or the point sits in the outer corner of a kink and is beyond both elements,
  // the reach alone would let it hop to and fro for minutes.
  const Model& model = geometry.model();
  const double reach = 0.05 * model.size;
  HandOver changes;
  double travelled = 0.0;
  for (size_t hops = 0; (state.alpha < 0.0 || state.alpha > 1.0) && hops < model.elements.size(); ++hops) {
    const Element& from = model.elements[state.element];
    const int end = state.alpha > 1.0 ? from.end : from.start;
    // The beam goes on across that node: the next element on the side the node presses
    // (at a joint of three or more members, the one bounding the same sector: a point on a
    // beam's top passes a column below it and goes on along the beam).
    auto [best, to_side] = across(geometry, contact, state.element, state.side, end, D);
    if (best >= 0 && !occupancy.may_join(best, contact.frame)) best = -1;
    const double best_alpha = best >= 0 ? geometry.locate(contact, best, D, rotations).alpha : 0.0;
    if (best < 0) {  // no element beyond: the point has left the beam's free end …
      if (at_convergence) {  // … but only a converged iterate says so (till then α is held at the end)
        occupancy.leave(state.element);
        release(geometry, contact, D, rotations, state, false);
        changes.released = true;
      }
      break;
    }
    const int direction = state.alpha > 1.0 ? 1 : -1;
    const Element& to = model.elements[best];
    const double beyond_from = state.alpha > 1.0 ? state.alpha - 1.0 : -state.alpha;
    // The vertex opened towards this element: it stays at the node (unless the point has
    // gone clearly on, more than the edge beyond it).
    const double edge = ContactGeometry::edge_of(contact);
    if (end == state.step.held_node && beyond_from <= edge) break;
    const bool reverses = state.step.handover_direction != 0 && direction != state.step.handover_direction;
    const double into_to = to.start == end ? best_alpha : 1.0 - best_alpha;  // from the node, < 0: behind it
    if (comes_to_rest_on_node(state, direction, end, edge, beyond_from, into_to)) {
      occupancy.join(best, contact.frame);
      enter_vertex(model, end, best, to_side, state);
      ++changes.handed_over;
      break;
    }
    occupancy.leave(state.element);
    occupancy.join(best, contact.frame);
    state.side = to_side;
    if (reverses) {
      ++changes.reversed;
      state.step.hop_node = end;
    }
    // The next element's own direction: past its start (α < 0) when it continues from our end j.
    state.step.handover_direction = (to.start == end) == (direction > 0) ? direction : -direction;
    state.element = best;
    state.alpha = best_alpha;
    ++changes.handed_over;
    travelled += geometry.initial(best).length;
    if (travelled >= reach) break;
  }
  return changes;
}

}  // namespace tsm::contact
