#include "tsmframe/contact/release.hpp"

#include <algorithm>
#include <cmath>

#include "tsmframe/contact/sides.hpp"

namespace tsm::contact {
namespace {

/// The element of the beam nearest the node across its span (candidate index; −1: none), and
/// the node's gap from it.
std::pair<int, double> nearest_across(const ContactGeometry& geometry, const ContactCandidates& contact,
                                      const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                      const ElementLoads& loads) {
  int nearest = -1;
  double nearest_gap = 0.0;
  for (size_t ci = 0; ci < contact.candidates.size(); ++ci) {
    const NodeOnElement where = geometry.locate(contact, contact.candidates[ci], D, rotations, 0.0, 1.0, &loads);
    if (where.alpha < 0.0 || where.alpha > 1.0) continue;
    if (nearest < 0 || std::abs(where.gap) < std::abs(nearest_gap)) nearest = static_cast<int>(ci), nearest_gap = where.gap;
  }
  return {nearest, nearest_gap};
}

}  // namespace

void release(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& D,
             const std::vector<double>& rotations, ContactState& state, bool pulled) {
  const Model& model = geometry.model();
  state.reference.listed = false;  // a reference taken now, not at the step's start: every candidate
  state.step.released_pulled = pulled;
  if (!pulled) state.step.slid_off_element = state.element;
  if (pulled) {
    // It let go on its own side of the beam, wherever the iterate has put things: that side,
    // carried along the beam from the element it left, is the side of every element it may not
    // reach the other side of (passed_through).
    std::vector<signed char> side(contact.candidates.size(), no_side);
    side[contact.candidate_index[state.element]] = static_cast<signed char>(state.side);
    carry_sides(geometry, contact, D, std::vector<signed char>(contact.candidates.size(), 0), side);
    state.reference.side.set(side);
    state.reference.sides_of_near = false;
  } else {
    reset_sides(geometry, contact, D, rotations, state.side, state);
    keep_place(geometry, contact, D, state.reference);
  }
  const Eigen::Vector2d n = geometry.chord_normal(state.element, D, rotations);
  state.step.released_side = state.side;
  state.step.released_normal[0] = n.x();
  state.step.released_normal[1] = n.y();
  // The elements whose span holds the node, and their neighbours in the set: near a joint the
  // node may sit just past one element's end yet is inside the beam's continuation.
  std::vector<int>& within = state.step.released_within;
  within.clear();
  for (size_t ci = 0; ci < contact.candidates.size(); ++ci) {
    const int f = contact.candidates[ci];
    const double alpha = geometry.locate(contact, f, D, rotations, -alpha_tolerance, 1.0 + alpha_tolerance).alpha;
    if (alpha < -alpha_tolerance || alpha > 1.0 + alpha_tolerance) continue;
    for (const int node : {model.elements[f].start, model.elements[f].end})
      for (const int g : geometry.node_elements(node))
        if (contact.is_candidate(g)) within.push_back(contact.candidate_index[g]);
  }
  std::sort(within.begin(), within.end());
  within.erase(std::unique(within.begin(), within.end()), within.end());
  state.active = false;
  state.step.released = true;
  state.element = -1;
  state.vertex.reset();
  state.side = 0;
  state.force = state.Y = 0.0;
}

bool passed_through(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& D,
                    const std::vector<double>& rotations, const ContactState& state, const ElementLoads& loads) {
  if (state.active || !state.step.released) return false;
  const Eigen::Vector2d released_normal(state.step.released_normal[0], state.step.released_normal[1]);
  for (const int ci : state.step.released_within) {
    const int f = contact.candidates[ci];
    const NodeOnElement where = geometry.locate(contact, f, D, rotations, 0.0, 1.0, &loads);
    if (where.alpha < 0.0 || where.alpha > 1.0) continue;
    const Eigen::Vector2d n = geometry.chord_normal(f, D, rotations);
    const int expected = n.dot(released_normal) >= 0.0 ? state.step.released_side : -state.step.released_side;
    if (expected * where.gap < contact.gap - geometry.touch_tolerance()) return true;  // inside its gap, as detect() has it
  }
  if (!state.step.released_pulled) return false;  // off a free end: it may go round it
  // The element of the beam nearest the node across its span: a node through the beam lies just
  // beyond the element it went through. Elements farther across are no guide: the side carried
  // round a closed ring from the element it left is the wrong one on the ring's far side, whose
  // span the node above the ring also lies across (a rope draped over a ring was "through" it).
  const auto [nearest, nearest_gap] = nearest_across(geometry, contact, D, rotations, loads);
  if (nearest < 0) return false;
  const int expected = state.reference.side_of(nearest);
  return (expected == 1 || expected == -1) && expected * nearest_gap < contact.gap - geometry.touch_tolerance();
}

}  // namespace tsm::contact
