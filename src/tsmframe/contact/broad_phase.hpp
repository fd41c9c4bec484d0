#pragma once
// Detection's broad phase: which candidate elements a contact node can reach within a step.
// At a converged state each inactive contact lists the candidates whose chord lies within a
// radius R of its node (ContactReference::near); at an iterate, no other candidate can have come
// within the contact's gap of the node, nor swept across it, while the node and the candidates'
// nodes have moved less since then than R leaves beyond the gap and an element's bulge from its
// chord (the distance from a node to a chord changes by no more than the node and the chord's
// ends move). Detection then runs over the listed candidates only; beyond that bound (the first
// iterate of a step that moves a beam a long way, a reference taken at a release) over all of
// them, as before: the contacts found are the same either way.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"
#include "tsmframe/util/segment_grid.hpp"

namespace tsm::contact {

/// A fingerprint of a displacement vector: a list of near candidates holds only while the
/// displacements it was made at are the step's start.
std::uint64_t displacement_stamp(const Eigen::VectorXd& displacements);

/// The displacements at a step's start, where the near lists were made, with their fingerprint
/// (taken once per step), and the chords' rotations there (the sides not kept are read there).
struct StepStart {
  Eigen::VectorXd displacements;
  std::uint64_t stamp = 0;
  std::vector<double> rotations;
};
StepStart step_start(Eigen::VectorXd displacements, std::vector<double> rotations);
/// The unloaded state as a step's start (where ContactSet::initial_states takes the references).
StepStart unloaded_start(const Model& model);

/// The chords of the candidate elements at one state on a grid (util/segment_grid), made once
/// for a pass over the contacts: which lie near a node without a look at every one.
class CandidateChords {
 public:
  CandidateChords(const ContactGeometry& geometry, const Eigen::VectorXd& displacements);
  /// The candidate elements (model indices, ascending) whose chords' boxes meet the square of
  /// half-width `radius` about `x`: every one within `radius` of it, and some farther.
  void near(const Eigen::Vector2d& x, double radius, std::vector<int>& elements) const;

 private:
  const std::vector<int>& elements_;
  util::SegmentGrid grid_;
};

/// Lists in `reference.near` the candidates whose chord at `displacements` (a converged state,
/// the step's start; `chords` there) lies within the broad phase's radius of the node.
void list_near_candidates(const ContactGeometry& geometry, const ContactCandidates& contact,
                          const Eigen::VectorXd& displacements, std::uint64_t stamp, const CandidateChords& chords,
                          ContactReference& reference);

/// How far the candidates of every contact have moved since the step's start, for one update.
class BroadPhase {
 public:
  /// `start`: the step's start (null: no broad phase, every candidate).
  BroadPhase(const ContactGeometry& geometry, const Eigen::VectorXd& displacements, const StepStart* start);
  /// The candidates (indices into contact.candidates, ascending) detection need look at for the
  /// contact's node now; null: all of them.
  const std::vector<int>* candidates(const ContactCandidates& contact, const ContactReference& reference) const;

 private:
  const ContactGeometry& geometry_;
  const Eigen::VectorXd& displacements_;
  std::uint64_t stamp_ = 0;
  bool valid_ = false;
  double beam_motion_ = 0.0;  ///< the largest move of a candidate element's node since the start
};

}  // namespace tsm::contact
