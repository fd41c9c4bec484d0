#include "tsmframe/contact/detection.hpp"

#include <cmath>
#include <limits>

namespace tsm::contact {
namespace {

/// Calls `visit(ci, side)` for the broad phase's candidates (`near`), or for every one (null),
/// with the node's reference side of each.
template <class Visit>
void for_each_candidate(const ContactCandidates& contact, const ContactReference& reference, const std::vector<int>* near,
                        Visit&& visit) {
  if (near) {
    for (size_t j = 0; j < near->size(); ++j) {
      const int ci = (*near)[j];
      visit(ci, near == &reference.near ? reference.near_side(j) : reference.side_of(ci));
    }
    return;
  }
  for (size_t ci = 0; ci < contact.candidates.size(); ++ci)
    visit(static_cast<int>(ci), reference.side_of(static_cast<int>(ci)));
}

}  // namespace

bool pair_in_contact(const ContactGeometry& geometry, const ContactCandidates& contact, int f, const Eigen::VectorXd& D,
                     const Occupancy& occupancy) {
  const Model& model = geometry.model();
  const Eigen::Vector2d node = geometry.position(contact.node, D);
  for (const int end : {model.elements[f].start, model.elements[f].end}) {
    const int g = occupancy.touching(end);
    if (g < 0 || (model.elements[g].start != contact.node && model.elements[g].end != contact.node)) continue;
    const double reach = contact.gap + 1e-2 * geometry.initial(f).length;
    if ((geometry.position(end, D) - node).squaredNorm() <= reach * reach) return true;
  }
  return false;
}

int swept_crossing(const ContactGeometry& geometry, const ContactCandidates& spec, const ContactState& state,
                   const Eigen::VectorXd& D, const Occupancy& occupancy, const std::vector<int>* near,
                   const StepStart* start) {
  const Model& model = geometry.model();
  // In each element's own frame the node moved from (α0, g0) at the last converged state to
  // (α1, g1) now: where g reaches the contact's gap on the far side, α is interpolated between.
  // Only elements with a side (the side the node is to come from) and whose chord the node was
  // then on that side of; none the node now lies within (the ordinary test covers those). And
  // only where the node itself moved across the element as it lies now (its straight path
  // meets the current chord): an element that turned a long way in the step sweeps its frame
  // past nodes that never met it (a strip rolled onto a die in one step).
  const bool own_place = state.reference.along.size() == spec.candidates.size();
  if (!own_place && !(start && start->stamp == state.reference.stamp && start->displacements.size() == D.size())) return -1;
  const auto place_then = [&](int ci) {  // the node in the chord's frame at the reference
    return own_place ? NodeOnElement{state.reference.along[ci], state.reference.across[ci]}
                     : geometry.on_chord(spec, spec.candidates[ci], start->displacements);
  };
  const auto position = [&](int n) { return geometry.position(n, D); };
  const Eigen::Vector2d p0(state.reference.position[0], state.reference.position[1]), p1 = position(spec.node);
  const Eigen::Vector2d path = p1 - p0;
  if (!(path.squaredNorm() > 0.0)) return -1;
  const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  const auto path_meets_chord = [&](int f) {
    const Eigen::Vector2d a = position(model.elements[f].start), b = position(model.elements[f].end);
    const double denominator = cross(path, b - a);
    if (denominator == 0.0) return false;
    const double s = cross(a - p0, b - a) / denominator, u = cross(a - p0, path) / denominator;
    return s >= 0.0 && s <= 1.0 && u >= 0.0 && u <= 1.0;
  };
  int first = -1;
  double first_t = INFINITY;
  for_each_candidate(spec, state.reference, near, [&](int ci, int side) {
    const int f = spec.candidates[ci];
    if (!occupancy.may_join(f, spec.frame) || (side != 1 && side != -1)) return;
    // The tests on the iterate alone first: most candidates end at one of them, before the
    // node's place at the reference is read.
    const Element& e = model.elements[f];
    const Eigen::Vector2d a = position(e.start), b = position(e.end);
    if (const double alpha = element::alpha_on_chord(a, b, p1); alpha >= -alpha_tolerance && alpha <= 1.0 + alpha_tolerance)
      return;  // on_chord's α, without its square root
    {  // Still on its side beyond the gap, surely (on_chord's distance, squared, with room for rounding).
      const Eigen::Vector2d chord = b - a, r = p1 - a;
      const double across = chord.x() * r.y() - chord.y() * r.x(), length2 = chord.squaredNorm();
      if (length2 > 0.0 && side * across > 0.0 && across * across > spec.gap * spec.gap * length2 * (1.0 + 1e-9)) return;
    }
    const NodeOnElement then = place_then(ci);
    const double before = side * then.gap;
    if (!(before > spec.gap)) return;
    const NodeOnElement now = geometry.on_chord(spec, f, D);
    const double after = side * now.gap;
    if (after > spec.gap) return;
    const double t = (before - spec.gap) / (before - after);
    const double alpha = then.alpha + t * (now.alpha - then.alpha);
    if (alpha < 0.0 || alpha > 1.0 || t >= first_t || !path_meets_chord(f)) return;
    first = f;
    first_t = t;
  });
  return first;
}

std::optional<HandOver> detect(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& D,
                               const std::vector<double>& rotations, ChordFrames& frames, ContactState& state,
                               Occupancy& occupancy, const ElementLoads* loads, const std::vector<int>* near,
                               const StepStart* start) {
  state.step.blocked_element = -1;
  if (state.step.released) return std::nullopt;
  int best = -1, best_side = 0;
  double best_gap = INFINITY, best_alpha = 0.0;
  const Eigen::Vector2d node = geometry.position(contact.node, D);
  for_each_candidate(contact, state.reference, near, [&](int ci, int reference) {
    const int f = contact.candidates[ci];
    if (const double alpha = frames(f).alpha(node); alpha < -alpha_tolerance || alpha > 1.0 + alpha_tolerance)
      return;  // the same α as locate's
    const NodeOnElement where = geometry.locate(contact, f, D, rotations, -INFINITY, INFINITY, loads);
    int side = 0;
    if (reference == no_side) {
      return;
    } else if (reference != 0) {
      if (reference * where.gap <= contact.gap) side = reference;
    } else if (std::abs(where.gap) > geometry.touch_tolerance()) {
      side = -side_of_gap(where.gap);  // it left the centre line: it pushes the way it moves
    }
    if (side != 0 && pair_in_contact(geometry, contact, f, D, occupancy)) return;
    if (side != 0 && !occupancy.may_join(f, contact.frame)) {  // points of the other frame hold it
      state.step.blocked_element = f;
      return;
    }
    if (side != 0 && std::abs(where.gap) < best_gap) {
      best = f;
      best_side = side;
      best_gap = std::abs(where.gap);
      best_alpha = where.alpha;
    }
  });
  if (best < 0) {
    // Across an element's span and on beyond it within one iterate (a long step along a beam
    // the node was pressed onto): contact starts on that element, and is handed on along the
    // beam from there to where the node is — as far as the beam lets it (a column in the way).
    best = swept_crossing(geometry, contact, state, D, occupancy, near, start);
    if (best < 0) return std::nullopt;
    best_side = state.reference.side_of(contact.candidate_index[best]);
    best_alpha = geometry.locate(contact, best, D, rotations).alpha;
  }
  state.step.blocked_element = -1;
  state.active = true;
  state.element = best;
  state.side = best_side;
  state.alpha = best_alpha;
  state.force = state.Y = 0.0;
  occupancy.join(best, contact.frame);
  if (state.alpha < 0.0 || state.alpha > 1.0) return hand_over(geometry, contact, D, rotations, false, state, occupancy);
  return HandOver{};
}

}  // namespace tsm::contact
