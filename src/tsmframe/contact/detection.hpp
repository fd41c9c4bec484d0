#pragma once
// A contact starts where its node has reached or crossed a candidate element's deflected centre
// line since the last converged state: within the element's span on the other side of it (or
// off the centre line, for a node that was on it), measured from the element's own deflected
// shape (the line where the contact force is exactly zero), so a contact starts with Y = 0 and
// no jump. A node that went across an element's span and on beyond it within one iterate (a
// long step along a beam it was pressed onto) is caught along its path (swept_crossing).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "tsmframe/contact/broad_phase.hpp"
#include "tsmframe/contact/chord_frames.hpp"
#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"
#include "tsmframe/contact/occupancy.hpp"
#include "tsmframe/contact/sliding.hpp"

namespace tsm::contact {

/// The first candidate whose span the node has crossed, from its side, between the last
/// converged state and now while ending beyond the span, first along the path (−1: none).
/// `near`: the broad phase's candidates (broad_phase.hpp), null: every one. The node's place
/// then is the reference's own (a release's), else read at `start` where the reference was taken
/// there; neither: no crossing is looked for.
int swept_crossing(const ContactGeometry& geometry, const ContactCandidates& contact, const ContactState& state,
                   const Eigen::VectorXd& displacements, const Occupancy& occupancy, const std::vector<int>* near = nullptr,
                   const StepStart* start = nullptr);

/// Whether the contact's node would start on element `f` against a node of f that already
/// presses on an element at the contact's node (two beams' nodes resting on each other, as a
/// "between" entry makes them): that pair is in contact already, and a second contact would
/// count its force twice. The nodes are then within the gap (and a little) of each other.
bool pair_in_contact(const ContactGeometry& geometry, const ContactCandidates& contact, int element,
                     const Eigen::VectorXd& displacements, const Occupancy& occupancy);

/// Starts the inactive contact `state` where its node has reached an element, and hands it on
/// along the beam to where the node is (sliding.hpp). None: it touches nothing (or only elements
/// it may not join, occupancy.hpp: state.step.blocked_element says which). With `loads` (at a
/// converged iterate), the gap is measured from the shape the points already on an element give
/// it: a node they lift clear is clear. `near`: the broad phase's candidates, null: every one;
/// `start`: the step's start (swept_crossing).
std::optional<HandOver> detect(const ContactGeometry& geometry, const ContactCandidates& contact,
                               const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                               ChordFrames& frames, ContactState& state, Occupancy& occupancy,
                               const ElementLoads* loads = nullptr, const std::vector<int>* near = nullptr,
                               const StepStart* start = nullptr);

}  // namespace tsm::contact
