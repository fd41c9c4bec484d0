#pragma once
// A contact point slides through element ends: where an active contact's point has left its
// element (α < 0 or α > 1), it is handed on to the element the beam goes on with at that end
// (along a member, or across a joint to another member of the contact's set), and on while it is
// still beyond, but no farther than max(one element, 5 % of the model's size) per iterate; where
// the point comes back across a node it already came back across, it rests there on both
// elements (vertex.hpp); where no element goes on, it has left the beam's free end and lets go —
// at a converged iterate (till then the force acts at the end).

#include <Eigen/Core>
#include <vector>

#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"
#include "tsmframe/contact/occupancy.hpp"

namespace tsm::contact {

/// What a hand-over changed.
struct HandOver {
  int handed_over = 0;  ///< elements passed (or a vertex entered)
  int reversed = 0;     ///< hand-overs back the way the point came within the step
  bool released = false;  ///< it left the beam's free end (at a converged iterate only)
};

/// Hands the contact `state`, whose point has left its element, on along the beam.
/// `at_convergence`: a converged iterate (a point past a free end lets go only there).
/// `occupancy`: the points on each element (a point passes an element it may not join as a free end).
HandOver hand_over(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& displacements,
                   const std::vector<double>& rotations, bool at_convergence, ContactState& state,
                   Occupancy& occupancy);

}  // namespace tsm::contact
