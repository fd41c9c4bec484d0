#pragma once
// Where each contact of the model stands at one point of the path (part of solver::State, so a
// failed step restores it with everything else): whether and where it touches, the second
// element of a contact resting on a beam node (a vertex), where its node was at the last
// converged state (what detection compares with), and what it remembers within the current step.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include "tsmframe/contact/friction.hpp"
#include "tsmframe/contact/side_table.hpp"

namespace tsm::contact {

/// The second element of a contact whose node rests on a beam node where two elements meet at an
/// angle (vertex.hpp): on either element alone, the force normal to its chord pushes the point
/// over the node onto the other, so both carry a contact element with the node held at that beam
/// node, and the force lies between the two chords' normals (README, Contact).
struct Vertex {
  int element = -1;  ///< the other element at the beam node
  int side = 0;      ///< the side of its chord the node is on
  double Y = 0.0;    ///< its contact element's force Y
};

/// Where the node was at the last converged state, per candidate element (ContactGeometry
/// order): detection starts a contact where the node has crossed to the other side since.
struct ContactReference {
  /// The side of the element's deflected centre line the node was on (+1 along n, −1 against),
  /// 0 on it, or no_side beyond the element's reach (sides.hpp): one per candidate, or, where
  /// `sides_of_near`, one per entry of `near` — a reference taken at a step's start holds only
  /// those (memory and time linear in the contacts), and the others are read when an iterate
  /// the broad phase cannot bound asks for them (sides.hpp, take_every_side).
  SideTable side;
  bool sides_of_near = false;
  /// The side of candidate near[j].
  signed char near_side(size_t j) const { return sides_of_near ? side[j] : side[static_cast<size_t>(near[j])]; }
  /// The side of candidate `ci` (one the reference holds no side of: no_side).
  signed char side_of(int ci) const {
    if (!sides_of_near) return static_cast<size_t>(ci) < side.size() ? side[static_cast<size_t>(ci)] : no_side;
    const auto at = std::lower_bound(near.begin(), near.end(), ci);
    return at != near.end() && *at == ci ? side[static_cast<size_t>(at - near.begin())] : no_side;
  }
  /// The node in the frame of the element's straight chord then: α along it, the signed
  /// distance across it. An iterate that takes the node across an element's span without ending
  /// within it (a long step along a beam) is caught by interpolating between these and the
  /// iterate's (detection.hpp). Kept only for a reference taken at a release (keep_place); one
  /// taken at the step's start has them from the step start's displacements (StepStart), so a
  /// state holds one byte per candidate, not seventeen.
  std::vector<double> along, across;
  double position[2] = {0.0, 0.0};  ///< the node's position (the start of its path in the step)
  /// The broad phase (broad_phase.hpp): at a step's start (`stamp` its displacements'), the
  /// candidates within reach of the node (indices into the candidates, ascending), and how far
  /// the node and the beams may move with that list still holding. Not `listed`: detection looks
  /// at every candidate (a reference taken at a release).
  std::vector<int> near;
  double allowance = 0.0;
  std::uint64_t stamp = 0;
  bool listed = false;
};

/// What a contact remembers within the current step only: cleared when a step is accepted.
struct StepMemory {
  /// Released during the step: it stays released until the step has converged (the iterates
  /// after a release may sweep the beam through the node), unless its node passes through a beam.
  bool released = false;
  /// Released because it would pull (not off a free end): it let go on its side of the beam and
  /// may not reach the other side of any element of it within the step (the reference sides
  /// hold that side, carried along the beam from the element it left).
  bool released_pulled = false;
  /// At that release: the side the node was on, the normal n of the element it left, and the
  /// candidates (ascending) whose span held the node (0 ≤ α ≤ 1), with their neighbours. Until
  /// the step ends the node must not reach the other side of those elements while within their
  /// span (going round a free end is allowed).
  int released_side = 0;
  double released_normal[2] = {0.0, 0.0};
  std::vector<int> released_within;
  /// The element whose free end the point left (released so), −1: none.
  int slid_off_element = -1;
  /// Direction of the last hand-over (+1 past node j, −1 past node i, 0 none), to tell a point
  /// sliding on from one hopping back and forth.
  int handover_direction = 0;
  /// The beam node (index) across which the point last came back the way it had gone, −1: none
  /// — for the message when it keeps hopping.
  int hop_node = -1;
  /// The beam node at which a vertex opened on one side: the contact left on the other element
  /// stays there rather than go back into the corner.
  int held_node = -1;
  /// Inactive: an element the node has reached that it may not join (a cantilever-frame contact
  /// is on it, or it is one, occupancy.hpp), at the last update; −1 none.
  int blocked_element = -1;
};

/// A frictional contact's history (docs/friction.md §6): its anchor on the member, fixed within a
/// step and moved by accept() to where the converged iterate left it, and what the last
/// evaluation found.
struct FrictionState {
  bool anchored = false;
  int member = -1;           ///< the member the anchor is on
  double anchor = 0.0;       ///< s_a: the anchor's arc length along the member as drawn (F5)
  double slip = 0.0;         ///< the slip accumulated since the contact touched: Σ |Δs_a|
  FrictionStatus status = FrictionStatus::none;  ///< at the last evaluation
  /// At the iterate that converged the step (accept()): what a converged state reports — an
  /// evaluation after it, from the moved anchor, finds a slipping point sticking on the cone's
  /// edge, its force read from a difference of arc lengths at round-off.
  FrictionStatus step_status = FrictionStatus::none;
  double step_tangential = 0.0;
  double tangential = 0.0;   ///< the friction force along the beam's tangent, signed along e (Z q)
  double trial_anchor = 0.0; ///< where the last evaluation's return map left the anchor
};

struct ContactState {
  bool active = false;
  int element = -1;   ///< element carrying the contact (index), −1 when inactive
  int side = 0;       ///< side of that element's chord the node is on: +1 along n, −1 against
  double alpha = 0.0; ///< α = l_ic / l at the last evaluation
  double force = 0.0; ///< compression −side·Y (≥ 0 when converged); at a vertex, of the resultant
  double Y = 0.0;     ///< the element force Y (chord frame, Eq. 6–9)
  /// The push the node gives the beam(s) (x, y): Y along the chord's normal or the bent beam's;
  /// at a vertex, both elements' together.
  double push[2] = {0.0, 0.0};
  std::optional<Vertex> vertex;  ///< resting on a beam node between two elements (vertex.hpp)
  /// Started, or handed to another element, at the last update: until the next update its force
  /// acts along the chord's normal whatever its `normal` (its Y, read from how far the iterate
  /// took the node through the beam, is not yet the beam's, and would turn a deflected normal by
  /// ½ c_α Y / l, N16, arbitrarily far). Also set for every contact in touch at a step's
  /// predictor iterate (solver::TsmProblem::evaluate), and it turns every point of its element
  /// to the chord's normal (ContactSet::active_contacts; an iterate the landing cut short turns
  /// every point, without marking them).
  bool entering = false;
  FrictionState friction;  ///< μ > 0 only
  ContactReference reference;
  StepMemory step;
};

}  // namespace tsm::contact
