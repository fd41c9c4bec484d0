#include "tsmframe/contact/landing.hpp"

#include <algorithm>

namespace tsm::contact {

double landing_fraction(const ContactGeometry& geometry, const ContactCandidates& contact, const ContactState& state,
                        const Eigen::VectorXd& D, const Eigen::VectorXd& trial) {
  if (state.active || state.step.released) return 1.0;
  const double k = landing_depth_in_elements;
  const ContactReference& reference = state.reference;
  double fraction = 1.0;
  const auto visit = [&](int ci, int side) {
    if (side != 1 && side != -1) return;
    const int f = contact.candidates[ci];
    const NodeOnElement now = geometry.on_chord(contact, f, D), then = geometry.on_chord(contact, f, trial);
    const double before = side * now.gap, after = side * then.gap;
    const double deepest = contact.gap - k * geometry.initial(f).length;
    if (!(before > contact.gap) || !(after < deepest)) return;  // in touch already, or landing no deeper
    const double t = (before - contact.gap) / (before - after);  // where it crosses the gap
    const double alpha = now.alpha + t * (then.alpha - now.alpha);
    if (alpha < 0.0 || alpha > 1.0) return;  // passes the element's span by
    fraction = std::min(fraction, (before - deepest) / (before - after));
  };
  if (reference.listed) {
    for (size_t j = 0; j < reference.near.size(); ++j) visit(reference.near[j], reference.near_side(j));
  } else {
    for (size_t ci = 0; ci < contact.candidates.size(); ++ci) visit(static_cast<int>(ci), reference.side_of(static_cast<int>(ci)));
  }
  return fraction;
}

LandingMove landing_move(const ContactGeometry& geometry, const ContactCandidates& contact, const ContactState& state,
                         const Eigen::VectorXd& D, const std::vector<double>& rotations) {
  if (!state.active || state.vertex) return {};
  const NodeOnElement at = geometry.locate(contact, state.element, D, rotations);
  const double back = state.side * contact.gap - at.gap;  // along n, to the gap
  if (!(state.side * back > 0.0)) return {};            // not through it
  return {contact.node, back * geometry.chord_normal(state.element, D, rotations)};
}

}  // namespace tsm::contact
