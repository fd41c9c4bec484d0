#pragma once
// The contact life cycle (FORMULATION §3): detection, release and sliding across element ends.
//
// After every evaluation of the structure the Newton loop calls update():
//  - an active contact whose force would pull at a converged iterate is released (compression only);
//  - an active contact whose point has left its element (α < 0 or α > 1) is handed to the
//    neighbouring element of its member set at that end (along a member, or across a joint to
//    another member in the set), and on while still beyond, but no farther than
//    max(one element, 5 % of the model's size) per iterate; if there is none, the point
//    has left the beam's free end and the contact is released (at a converged iterate: till
//    then the force acts at the end);
//  - an inactive contact node that has reached or crossed an element's deflected centre line
//    (0 ≤ α ≤ 1, the side flipped since the last converged state) becomes a contact element there.
// Contact is measured from the element's own deflected shape (the line where the contact force
// is exactly zero), so a contact starts with Y = 0 and no jump.

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "tsmframe/contact/contact_element.hpp"
#include "tsmframe/contact/contact_state.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::contact {

/// A contact element to evaluate: node c on element `element`.
struct ActiveContact {
  int node = 0;
  int element = 0;
  ContactElementData data;
};

/// What an evaluation of an active contact element found.
struct ContactEvaluation {
  double alpha = 0.0;
  double Y = 0.0;
};

/// Changes made by one update().
struct ContactChanges {
  int activated = 0;
  int released = 0;
  int handed_over = 0;
  int reversed = 0;  ///< hand-overs back the way a contact point came within the step
  bool any() const { return activated + released + handed_over > 0; }
};

class ContactTracker {
 public:
  explicit ContactTracker(const Model& model);

  int contact_count() const { return static_cast<int>(specs_.size()); }
  /// States at the undeformed model (sides of every contact node against its candidates).
  std::vector<ContactState> initial_states() const;
  /// The contact elements of the active contacts.
  std::vector<ActiveContact> active_contacts(const std::vector<ContactState>& states) const;
  /// Life-cycle changes after an evaluation at `displacements` (chord rotations of that
  /// evaluation); `evaluated` holds one entry per active contact, in active_contacts() order.
  /// Tension releases a contact only with `release_pulling` — the Newton loop asks for it once
  /// the residual has converged: an unconverged iterate's Y is no evidence of pulling (a stiff
  /// contact's Y swings through zero while the beam catches up with the node).
  ContactChanges update(const Eigen::VectorXd& displacements, const std::vector<double>& chord_rotations,
                        const std::vector<ContactEvaluation>& evaluated, std::vector<ContactState>& states,
                        bool release_pulling) const;
  /// Sets α, Y and the compression of every active contact from `evaluated` (active_contacts()
  /// order) without changing the active set: the evaluation that stands after the last update().
  void record(const Eigen::VectorXd& displacements, const std::vector<double>& chord_rotations,
              const std::vector<ContactEvaluation>& evaluated, std::vector<ContactState>& states) const;
  /// Whether a contact released during this step has let its node pass through a beam (it may
  /// not start again within the step): the converged state is then not acceptable.
  bool passed_through(const Eigen::VectorXd& displacements, const std::vector<double>& chord_rotations,
                      const std::vector<ContactState>& states) const;
  /// A contact (index) whose node reached an element another contact is on — which the tracker
  /// cannot give two contact elements — and that element; {−1, −1} if none.
  std::pair<int, int> blocked(const std::vector<ContactState>& states) const;
  /// Lets every contact released during this step whose node has passed through a beam touch
  /// again (the next update() starts it from its side at the step's start); returns how many.
  /// With several contacts pressing one beam, releasing all that pull at once can let another
  /// node through: the active set then needs that contact back.
  int allow_touching_again(const Eigen::VectorXd& displacements, const std::vector<double>& chord_rotations,
                           std::vector<ContactState>& states) const;
  /// Lets go of the contacts `which` (indices, each active on one element) as a contact that
  /// pulls lets go: Newton's look-ahead found that they would pull once the pulling ones have let
  /// go. Returns how many it released.
  int release_as_pulling(const std::vector<int>& which, const Eigen::VectorXd& displacements,
                         const std::vector<double>& chord_rotations, std::vector<ContactState>& states) const;
  /// At a converged state: inactive contacts take their current sides as reference.
  void accept(const Eigen::VectorXd& displacements, const std::vector<double>& chord_rotations,
              std::vector<ContactState>& states) const;

 private:
  bool node_passed_through(size_t k, const Eigen::VectorXd& displacements, const std::vector<double>& chord_rotations,
                           const ContactState& state) const;
  struct Spec {
    int node = 0;
    std::vector<int> candidates;        ///< element indices the node may touch
    std::vector<int> candidate_index;   ///< per element: its place in candidates, −1 if not one
    std::vector<double> shear_flexibility;  ///< per element: Ψ of the contact law
    double gap = 0.0;
    double edge = -1.0;
    double max_stiffness_ratio = 0.0;   ///< the cap: see cap_compliance
    /// The elements holding the node, as drawn: axis (cos, sin of φ0), EA, EI and l0.
    struct Own {
      double cos = 0.0, sin = 0.0, EA = 0.0, EI = 0.0, l0 = 0.0;
    };
    std::vector<Own> own;
    bool sliding_term = true;
    bool cantilever_frame = false;
  };
  /// Where the node is on `element` (node_on_element); its gap is measured only where α lies in
  /// [lowest, highest] (NaN elsewhere: α alone rules the element out).
  NodeOnElement locate(const Spec& spec, int element, const Eigen::VectorXd& displacements,
                       const std::vector<double>& chord_rotations, double lowest = -INFINITY,
                       double highest = INFINITY) const;
  /// The contact node in the frame of an element's straight current chord: α along it, the
  /// signed distance across it (along n). Unlike locate(), meaningful far beyond the element.
  NodeOnElement on_chord(const Spec& spec, int element, const Eigen::VectorXd& displacements) const;
  /// The first candidate whose span the node has crossed, from its side, between the last
  /// converged state and now while ending beyond the span, first along the path (−1: none).
  int swept_crossing(const Spec& spec, const ContactState& state, const Eigen::VectorXd& displacements,
                     const std::vector<char>& occupied) const;
  /// Hands an active contact whose point has left its element on along the beam (update()).
  void hand_over(const Spec& spec, const Eigen::VectorXd& displacements, const std::vector<double>& chord_rotations,
                 bool release_pulling, ContactState& state, std::vector<char>& occupied, ContactChanges& changes) const;
  element::SectionStiffness contact_section(const Spec& spec, int element) const;
  /// How the element's ends are joined to its nodes (ContactElementData::flexibility_i, _j):
  /// ∞ at a hinge, 1/k at an end spring, 0 where rigid.
  std::pair<double, double> end_flexibilities(int element) const;
  /// The stiffness cap's compliance for the contact of `spec` on `element`: 1 / (ratio · k), k
  /// the stiffest element holding the contact node across that element (as drawn: EA/l0 along
  /// the element's axis, 12EI/l0³ across it, mixed by the angle to the touched element's
  /// normal); 0 where no element holds the node (a rigid pusher: no cap).
  double cap_compliance(const Spec& spec, int element) const;
  /// The compliance floor's edge δ of a contact (its own, or the default).
  static double edge_of(const Spec& spec);
  /// `pulled`: released because it would pull (else: it left a free end).
  void release(const Spec& spec, const Eigen::VectorXd& displacements, const std::vector<double>& chord_rotations,
               ContactState& state, bool pulled) const;
  /// Gives every candidate without a side (no_side) the side of the nearest one with a side,
  /// carried from element to element (not from one read past a node through that node: `past`).
  void carry_sides(const Spec& spec, const Eigen::VectorXd& displacements, const std::vector<signed char>& past,
                   std::vector<signed char>& side) const;
  /// Across `node` from `element`, on the contact's `side` of it: the element the beam goes on
  /// with and the same side of it (where two candidates meet, the other one; where more do, the
  /// other edge of the sector between them that the side faces); {−1, 0} at a free end.
  std::pair<int, int> across(const Spec& spec, int element, int side, int node, const Eigen::VectorXd& displacements) const;
  /// The beam node shared by a vertex's two elements.
  int vertex_node(const ContactState& state) const;
  /// Reads one contact's evaluation(s) (two at a vertex) into its state; returns how many.
  size_t read_evaluation(const Eigen::VectorXd& displacements, const std::vector<double>& chord_rotations,
                         const ContactEvaluation* evaluated, ContactState& state) const;
  void reset_sides(const Spec& spec, const Eigen::VectorXd& displacements, const std::vector<double>& chord_rotations,
                   int fallback, ContactState& state) const;

  const Model& model_;
  std::vector<Spec> specs_;
  std::vector<element::InitialChord> initial_;
  std::vector<int> node_start_, node_elements_;  ///< elements at each node (CSR)
  std::vector<int> candidate_elements_;          ///< elements some contact may touch, ascending
  double touch_tolerance_ = 0.0;                 ///< |gap| below this: on the centre line
};

}  // namespace tsm::contact
