#pragma once
// Where each contact of the model stands at one point of the path (part of solver::State, so a
// failed step restores it with everything else).

#include <vector>

namespace tsm::contact {

inline constexpr signed char no_side = 2;

struct ContactState {
  bool active = false;
  int element = -1;   ///< element carrying the contact (index), −1 when inactive
  /// Inactive: an element the node has reached that another contact is on (one contact per
  /// element), at the last update; −1 none.
  int blocked_element = -1;
  int side = 0;       ///< side of that element's chord the node is on: +1 along n, −1 against
  double alpha = 0.0; ///< α = l_ic / l at the last evaluation
  double force = 0.0; ///< compression −side·Y (≥ 0 when converged); at a vertex, of the resultant
  double Y = 0.0;     ///< the element force Y (chord frame, Eq. 6–9)
  /// A vertex: the node rests on a beam node where two elements meet at an angle (on either
  /// element alone, the force normal to its chord pushes the point over the node onto the other).
  /// Both elements then carry a contact element with the node held at that beam node, so the
  /// force lies between the two chords' normals (README, Contact). −1: on one element.
  int partner = -1;
  int partner_side = 0;
  double partner_Y = 0.0;
  /// The beam node at which a vertex opened on one side in this step: the contact left on the
  /// other element stays there rather than go back into the corner (until the step converges).
  int held_node = -1;
  /// Per candidate element (ContactTracker order): the side the node was on at the last
  /// converged state (+1, −1), 0 while it lies on the element's centre line, or no_side when it
  /// was beyond the element's reach then (see ContactTracker). Contact starts when it reaches
  /// the other side.
  std::vector<signed char> reference_side;
  /// Per candidate element: where the node was at the last converged state in the frame of
  /// that element's straight chord then — along it (α) and across it (signed distance). An
  /// iterate that takes the node across an element's span without ending within it (a long step
  /// along a beam) is caught by interpolating between these and the iterate's (ContactTracker).
  std::vector<double> reference_along, reference_across;
  /// The node's position at the last converged state (the start of its path in the step).
  double reference_position[2] = {0.0, 0.0};
  /// Released during the current step: it stays released until the step has converged (the
  /// iterates after a release may sweep the beam through the node).
  bool released_in_step = false;
  /// Direction of the last hand-over in this step (+1 past node j, −1 past node i, 0 none), to
  /// tell a point sliding on from one hopping back and forth.
  int handover_direction = 0;
  /// The beam node (index) across which the point last came back the way it had gone, −1: none
  /// in this step — for the message when it keeps hopping.
  int hop_node = -1;
  /// At that release: the side the node was on, the normal n of the element it left, and per
  /// candidate whether the node lay within its span (0 ≤ α ≤ 1). Until the step ends the node
  /// must not reach the other side of those elements while within their span (going round a
  /// free end is allowed).
  int released_side = 0;
  /// Released because it would pull (not off a free end): it let go on its side of the beam and
  /// may not reach the other side of any element of it within the step (reference_side holds
  /// that side, carried along the beam from the element it left).
  bool released_pulled = false;
  /// The element whose free end the point left in this step (released so), −1: none.
  int slid_off_element = -1;
  double released_normal[2] = {0.0, 0.0};
  std::vector<char> released_within;
};

}  // namespace tsm::contact
