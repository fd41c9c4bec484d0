#pragma once
// A contact lets go: because its force would pull (compression only, at a converged iterate),
// or because its point left a beam's free end. Within the step after a release the node may not
// pass through the beam it let go of: a converged iterate where it has is not acceptable, and the
// contact then takes part again (contact_set). Which contacts let go together where several pull
// is release_forecast's.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"

namespace tsm::contact {

/// Releases the active contact `state` (on one element). `pulled`: it would pull (else: it left
/// a free end). It remembers the side it let go on and the elements whose span held its node.
void release(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& displacements,
             const std::vector<double>& rotations, ContactState& state, bool pulled);

/// Whether the node of a contact released in this step has passed through a beam since: it lies
/// within the span of an element that held it at the release, closer than the contact's gap on
/// its side or beyond; or, released by a pull, so near the element nearest across it. The far side of the shape the
/// points on each element give it (`loads`: a converged iterate's).
bool passed_through(const ContactGeometry& geometry, const ContactCandidates& contact, const Eigen::VectorXd& displacements,
                    const std::vector<double>& rotations, const ContactState& state, const ElementLoads& loads);

}  // namespace tsm::contact
