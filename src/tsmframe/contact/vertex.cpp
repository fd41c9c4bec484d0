#include "tsmframe/contact/vertex.hpp"

#include <cmath>
#include <utility>

#include "tsmframe/contact/release.hpp"

namespace tsm::contact {
namespace {

// A vertex holds the node at a beam node, where only the compliance floor (edge δ) keeps the
// contact law finite: with the floor switched off (the paper's element as published, δ → 0) a
// vertex would be singular, and there is none.
constexpr double vertex_min_edge = 1e-6;
// … and it is taken only by a point at most this far (a fraction of either element) past the
// node: a point sliding over many short elements hops about while it overshoots.
constexpr double vertex_reach = 0.5;

}  // namespace

int vertex_node(const Model& model, const ContactState& state) {
  const Element& a = model.elements[state.element];
  const Element& b = model.elements[state.vertex->element];
  return a.end == b.start || a.end == b.end ? a.end : a.start;
}

bool comes_to_rest_on_node(const ContactState& state, int direction, int node, double edge, double beyond_from,
                           double into_to) {
  const bool reverses = state.step.handover_direction != 0 && direction != state.step.handover_direction;
  return reverses && node == state.step.hop_node && node != state.step.held_node && edge >= vertex_min_edge &&
         beyond_from <= vertex_reach && std::abs(into_to) <= vertex_reach;
}

void enter_vertex(const Model& model, int node, int to, int to_side, ContactState& state) {
  const int from = state.element;
  state.vertex = Vertex{to, to_side, 0.0};
  if (model.elements[from].end != node && model.elements[to].end == node) {  // reported on the element that ends at the node
    std::swap(state.element, state.vertex->element);
    std::swap(state.side, state.vertex->side);
  }
  state.alpha = model.elements[state.element].end == node ? 1.0 : 0.0;
}

void read_vertex(const Model& model, double partner_Y, const Eigen::Vector2d& partner_push, ContactState& state) {
  Vertex& v = *state.vertex;
  v.Y = partner_Y;
  state.alpha = model.elements[state.element].end == vertex_node(model, state) ? 1.0 : 0.0;
  state.push[0] += partner_push.x();
  state.push[1] += partner_push.y();
  const double compression = -state.side * state.Y - v.side * v.Y;
  const double push = std::hypot(state.push[0], state.push[1]);
  state.force = compression >= 0.0 ? push : -push;
}

bool open_vertex(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& D,
                 const std::vector<double>& rotations, ContactState& state, Occupancy& occupancy) {
  const Vertex v = *state.vertex;
  const bool first_pulls = -state.side * state.Y < 0.0, partner_pulls = -v.side * v.Y < 0.0;
  if (!first_pulls && !partner_pulls) return false;
  const int node = vertex_node(geometry.model(), state);
  if (first_pulls && partner_pulls) {
    occupancy.leave(state.element);
    occupancy.leave(v.element);
    release(geometry, contact, D, rotations, state, true);
    return true;
  }
  if (first_pulls) {
    occupancy.leave(state.element);
    state.element = v.element;
    state.side = v.side;
    state.Y = v.Y;
  } else {
    occupancy.leave(v.element);
  }
  state.vertex.reset();
  state.step.held_node = node;  // the node goes on along the other element, held at the node for now
  state.alpha = geometry.locate(contact, state.element, D, rotations).alpha;
  state.force = -state.side * state.Y;
  return true;
}

}  // namespace tsm::contact
