#pragma once
// The contacts of a model through their life cycle (FORMULATION §3). After every evaluation of
// the structure, update() runs, contact by contact:
//  - an active contact whose force would pull at a converged iterate lets go (release.hpp), and
//    a vertex where one side pulls opens (vertex.hpp);
//  - an active contact whose point has left its element is handed on along the beam, or lets go
//    past a free end at a converged iterate (sliding.hpp);
//  - an inactive contact whose node has reached an element's deflected centre line starts there
//    (detection.hpp), its sides at the last converged state telling (sides.hpp).
// Evaluations come back keyed by contact (ContactEvaluation::contact). What may touch what, and
// where a node stands against an element, is contact_geometry's.

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "tsmframe/contact/active_contact.hpp"
#include "tsmframe/contact/broad_phase.hpp"
#include "tsmframe/contact/contact_element.hpp"
#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"
#include "tsmframe/contact/landing.hpp"
#include "tsmframe/contact/occupancy.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::contact {

/// What an evaluation of an active contact element found, for one of its points.
struct ContactEvaluation {
  int contact = -1;     ///< ActivePoint::contact
  bool vertex = false;  ///< ActivePoint::vertex
  double alpha = 0.0;
  double Y = 0.0;
  double force_per_Y = 1.0;  ///< MultiPointResponse::force_per_Y: the compression is −side · Y · this
  Eigen::Vector2d push = Eigen::Vector2d::Zero();  ///< the element's nodal force on the contact node: Y n, or Y ν
  FrictionResult friction;  ///< friction.hpp (status `none` at μ = 0)
};

/// Changes made by one update().
struct ContactChanges {
  int activated = 0;
  int released = 0;
  int handed_over = 0;
  int reversed = 0;  ///< hand-overs back the way a contact point came within the step
  bool any() const { return activated + released + handed_over > 0; }
};

class ContactSet {
 public:
  explicit ContactSet(const Model& model) : geometry_(model) {}

  int contact_count() const { return geometry_.contact_count(); }
  /// Whether some contact pushes along the bent beam's normal (`"normal": "deflected"`, the
  /// chord frame's default): only then does evaluating along the chords' normals change anything.
  bool bends_normals() const;
  /// States at the undeformed model: sides of every contact node against its candidates, and
  /// in touch where a node rests on an element as drawn (model/resting_contact).
  std::vector<ContactState> initial_states() const;
  /// The contact elements of the active contacts: one per element with points on it (a vertex
  /// is a point on each of its two elements), in the order of their first points' contacts; an
  /// entering point (ContactState::entering) along the chord's normal; with `along_chords`,
  /// every point.
  std::vector<ActiveContact> active_contacts(const std::vector<ContactState>& states, bool along_chords = false) const;
  /// The same into `active`, whose elements' storage is reused (formed again at every pass).
  void active_contacts(const std::vector<ContactState>& states, bool along_chords, std::vector<ActiveContact>& active) const;
  /// Reads the evaluations of the active contacts into their states (α, Y, compression, push)
  /// without changing the active set: the evaluation that stands.
  void record(const std::vector<ContactEvaluation>& evaluated, std::vector<ContactState>& states) const;
  /// Records the evaluations, then runs the life cycle at `displacements` (chord rotations of
  /// that evaluation). A pull releases a contact only `at_convergence` — Newton asks for it once
  /// the residual has converged: an unconverged iterate's Y is no evidence of pulling (a stiff
  /// contact's Y swings through zero while the beam catches up with the node).
  /// `step_start`: the step's start, where accept() (initial_states, restore) took each inactive
  /// node's reference: its near candidates (broad_phase.hpp) and its sides of those; an iterate
  /// the broad phase cannot bound reads the other sides there.
  ContactChanges update(const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                        const std::vector<ContactEvaluation>& evaluated, std::vector<ContactState>& states,
                        bool at_convergence, const StepStart& step_start) const;
  /// The fraction of Newton's step from `displacements` to `trial` that lands no inactive
  /// contact's node deeper than landing.hpp allows (1: all of it).
  double landing_fraction(const Eigen::VectorXd& displacements, const Eigen::VectorXd& trial,
                          const std::vector<ContactState>& states) const;
  /// landing_move (landing.hpp) of each contact in touch in `states` that was not in
  /// `touching_before`, each node once.
  std::vector<LandingMove> landing_moves(const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                                         const std::vector<ContactState>& states,
                                         const std::vector<char>& touching_before) const;
  /// Whether a contact released during this step has let its node pass through a beam: the
  /// converged state is then not acceptable.
  bool passed_through(const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                      const std::vector<ContactState>& states) const;
  /// A contact (index) whose node reached an element it may not join — points of the other frame
  /// are on it (occupancy.hpp) — and that element; {−1, −1} if none.
  std::pair<int, int> blocked(const std::vector<ContactState>& states) const;
  /// Lets every contact released during this step whose node has passed through a beam touch
  /// again (the next update() starts it from its side at the step's start); returns how many.
  /// With several contacts pressing one beam, releasing all that pull at once can let another
  /// node through: the active set then needs that contact back.
  int allow_touching_again(const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                           std::vector<ContactState>& states) const;
  /// Lets go of the contacts `which` (indices, each active on one element) as a contact that
  /// pulls lets go: Newton's look-ahead found that they would pull once the pulling ones have let
  /// go. Returns how many it released.
  int release_as_pulling(const std::vector<int>& which, const Eigen::VectorXd& displacements,
                         const std::vector<double>& rotations, std::vector<ContactState>& states) const;
  /// At a converged state: the step's memory is cleared, and inactive contacts take their
  /// current sides as reference (`start`: this state, the next step's start).
  void accept(const StepStart& start, std::vector<ContactState>& states) const;
  /// At a run's or a stage's start (states read back without their references, solver/
  /// restart.hpp; contacts a stage turns on with other candidates): each contact takes its
  /// reference at this converged state as accept() gives an inactive one — all but a release's.
  void restore(const StepStart& start, std::vector<ContactState>& states) const;

 private:
  /// The life cycle of one active contact at an update.
  void update_active(const ContactCandidates& contact, const Eigen::VectorXd& displacements,
                     const std::vector<double>& rotations, bool at_convergence, ContactState& state,
                     Occupancy& occupancy, ContactChanges& changes) const;

  /// A frictional point's anchor from its state (FrictionData::anchored, anchor), on `element`
  /// (`second`: a vertex's second element, which takes none).
  void anchor(const ContactState& state, int element, bool second, FrictionData& friction) const;
  /// A frictional contact's evaluation into its state: the return map's result, the anchor set
  /// at the iterate that touched, the compression of the normal force alone.
  void record_friction(const ContactEvaluation& evaluation, ContactState& state) const;

  ContactGeometry geometry_;
};

}  // namespace tsm::contact
