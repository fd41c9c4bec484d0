#pragma once
// Which side of each candidate element a contact node is on — what detection compares a new
// iterate with. A side is read from an element's deflected centre line where the node lies
// within the element's reach, and carried along the beam from element to element beyond it
// (through their nodes: kept where one element continues the other, flipped where they run
// against each other, and at a joint of three or more, on to the element across the sector the
// side faces), so a node that slides over many short elements, or past a joint, within one step
// still finds the side it came from where it arrives.

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "tsmframe/contact/broad_phase.hpp"
#include "tsmframe/contact/chord_frames.hpp"
#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"

namespace tsm::contact {

/// Across beam node `node` from `element`, on the contact's `side` of it: the element the beam
/// goes on with and the same side of it (where two candidates meet, the other one; where more
/// do, the other edge of the sector between them that the side faces); {−1, 0} at a free end.
std::pair<int, int> across(const ContactGeometry& geometry, const ContactCandidates& contact, int element, int side,
                           int node, const Eigen::VectorXd& displacements);

/// Gives every candidate without a side (no_side) the side of the nearest one with a side,
/// carried from element to element (not from one read past a node through that node: `past`,
/// per candidate +1 past its end node, −1 before its start node, 0 within).
void carry_sides(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& displacements,
                 const std::vector<signed char>& past, std::vector<signed char>& side);

/// The node's reference at `displacements` (a release): its side of every candidate and its
/// position; the place it kept at a release let go. Where it lies on a centre line, `fallback`
/// (±1: the side it pressed from on state.element, 0: none) gives the side. `frames`: the
/// candidates' chord frames at `displacements`, shared by the contacts of one pass (null: each
/// formed here).
void reset_sides(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& displacements,
                 const std::vector<double>& rotations, int fallback, ContactState& state, ChordFrames* frames = nullptr);

/// The node's reference at a step's start (`start`; `chords` and `frames` there): the candidates
/// near it (broad_phase.hpp, list_near_candidates), its side of each of those only
/// (ContactReference::sides_of_near: carried among them) and its position — what detection
/// looks at while the broad phase holds.
void reset_near_sides(const ContactGeometry& geometry, const ContactCandidates& contact, const StepStart& start,
                      const CandidateChords& chords, ChordFrames& frames, ContactState& state);

/// Every candidate's side, where the reference holds the near ones' only (reset_near_sides), for
/// an iterate the broad phase cannot bound: those stay, the others are read at the step's start
/// (`start`, `frames` there) and carried from them. A reference that holds every side already,
/// or was not taken at `start`, is left as it is (a side it does not hold: no_side).
void take_every_side(const ContactGeometry& geometry, const ContactCandidates& contact, const StepStart& start,
                     ChordFrames& frames, ContactReference& reference);

/// Keeps in the reference the node's place in each candidate chord's frame at `displacements`
/// (a release, away from the step's start): α along the chord, the signed distance across it.
void keep_place(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& displacements,
                ContactReference& reference);

}  // namespace tsm::contact
