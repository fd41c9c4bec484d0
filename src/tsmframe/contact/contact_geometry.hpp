#pragma once
// What each contact may touch and how its law is set up, fixed for the run: its node, its
// candidate elements (the members it may touch), the contact law's section and end conditions on
// each, the stiffness cap, and where a node stands against an element at a state (α along it and
// its gap from the element's deflected centre line). The life cycle (sides, detection, sliding,
// vertex, release, contact_set) reads it; nothing here changes with the path.

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "tsmframe/contact/contact_element.hpp"
#include "tsmframe/contact/element_loads.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::contact {

/// How far beyond an element's ends (in α) a node still counts as on it: a node on a beam node
/// counts for both elements.
constexpr double alpha_tolerance = 1e-12;

/// The side (+1, −1) a signed gap puts a node on; 0 on the centre line.
inline int side_of_gap(double gap) { return gap > 0.0 ? 1 : (gap < 0.0 ? -1 : 0); }

/// Where the beam goes on from a candidate element through one of its nodes, among the
/// candidates (sides.hpp, across): where exactly two meet, the other one (`to`, its place among
/// the candidates) and whether a side of the one is the same side of the other (`sign` +1) or
/// the opposite (−1); `free_end` where no other candidate meets there; `joint` where three or
/// more do (which one a side goes on to then depends on the geometry).
struct CandidateLink {
  static constexpr int free_end = -1, joint = -2;
  int to = free_end;
  int sign = 0;
};

/// The elements some contacts may touch (model/candidate_groups: one table per group).
struct CandidateTable {
  std::vector<int> elements;                ///< element indices, ascending
  std::vector<int> index;                   ///< per element of the model: its place in elements, −1 if not one
  std::vector<double> shear_flexibility;    ///< per candidate: Ψ of the contact law
  std::vector<CandidateLink> links;         ///< per candidate: through its start node, through its end node
  double longest = 0.0;                     ///< the longest candidate's length as drawn
};

/// A contact's node, its candidate elements and its law's settings (from ContactSpec). The
/// candidate tables are its group's, held by the ContactGeometry.
struct ContactCandidates {
  int node = 0;
  std::span<const int> candidates;         ///< element indices the node may touch, ascending
  std::span<const int> candidate_index;    ///< per element: its place in candidates, −1 if not one
  std::span<const double> shear_flexibility;  ///< per candidate: Ψ of the contact law
  std::span<const CandidateLink> links;    ///< per candidate: through its start node, through its end node
  double longest_candidate = 0.0;          ///< the longest candidate's length as drawn
  double gap = 0.0;
  double edge = -1.0;                 ///< the compliance floor's edge δ; < 0: the default
  double max_stiffness_ratio = 0.0;   ///< the cap: see ContactGeometry::cap_compliance
  /// The elements holding the node, as drawn: axis (cos, sin of φ0), EA, EI and l0.
  struct Own {
    double cos = 0.0, sin = 0.0, EA = 0.0, EI = 0.0, l0 = 0.0;
  };
  std::vector<Own> own;
  bool sliding_term = true;
  double friction = 0.0;  ///< Coulomb's μ (0: none)
  ContactFrame frame = ContactFrame::chord;
  ContactNormal normal = ContactNormal::chord;
  bool is_candidate(int element) const { return candidate_index[element] >= 0; }
};

class ContactGeometry {
 public:
  explicit ContactGeometry(const Model& model);

  const Model& model() const { return model_; }
  int contact_count() const { return static_cast<int>(contacts_.size()); }
  const ContactCandidates& contact(int k) const { return contacts_[k]; }
  const element::InitialChord& initial(int element) const { return initial_[element]; }
  /// The elements at a node.
  std::span<const int> node_elements(int node) const {
    return {node_elements_.data() + node_start_[node], node_elements_.data() + node_start_[node + 1]};
  }
  /// Elements some contact may touch, ascending.
  const std::vector<int>& candidate_elements() const { return candidate_elements_; }
  /// |gap| below this: the node lies on the centre line (it has no side yet).
  double touch_tolerance() const { return touch_tolerance_; }

  /// A node's current position.
  Eigen::Vector2d position(int node, const Eigen::VectorXd& displacements) const {
    return model_.nodes[node].position + displacements.segment<2>(dofs_per_node * node);
  }
  /// The unit normal n of an element's current chord.
  Eigen::Vector2d chord_normal(int element, const Eigen::VectorXd& displacements, const std::vector<double>& rotations) const;
  /// Where the contact node is on `element` (node_on_element); its gap is measured only where α
  /// lies in [lowest, highest] (NaN elsewhere: α alone rules the element out). With `loads`, from
  /// the element's shape under the points already pressing it (loaded_deflection), else from its
  /// free shape.
  NodeOnElement locate(const ContactCandidates& contact, int element, const Eigen::VectorXd& displacements,
                       const std::vector<double>& rotations, double lowest = -INFINITY, double highest = INFINITY,
                       const ElementLoads* loads = nullptr) const;
  /// The deflection at α that points already pressing `element` (`loads`) add to the shape
  /// locate() measures the gap from (the element's free shape): Σ_q C(α, α_q) Y_q, C the
  /// points' compliance of the k-point law, floors and end connections included (docs/
  /// contact-k-points.md §1) — where the law puts a point of zero force. 0 without loads.
  double loaded_deflection(const ContactCandidates& contact, int element, double alpha,
                           const std::vector<PointLoad>& loads) const;
  /// The contact node in the frame of an element's straight current chord: α along it, the
  /// signed distance across it (along n). Unlike locate(), meaningful far beyond the element.
  NodeOnElement on_chord(const ContactCandidates& contact, int element, const Eigen::VectorXd& displacements) const;
  /// What the contact element of `contact` on `element`, the node on `side` of it, is made of.
  ContactElementData element_data(const ContactCandidates& contact, int element, int side) const;
  /// The arc length along its member, as drawn, of a point at α on `element` (F5).
  double arc_length(int element, double alpha) const { return arc_start_[element] + initial_[element].length * alpha; }
  /// The compliance floor's edge δ of a contact (its own, or the default).
  static double edge_of(const ContactCandidates& contact);

 private:
  element::SectionStiffness contact_section(const ContactCandidates& contact, int element) const;
  /// How the element's ends are joined to its nodes (ContactElementData::flexibility_i, _j): ∞ at
  /// a hinge, 1/k at an end spring, 0 where rigid.
  std::pair<double, double> end_flexibilities(int element) const;
  /// The stiffness cap's compliance for `contact` on `element`: 1 / (ratio · k), k the stiffest
  /// element holding the contact node across that element (as drawn: EA/l0 along the element's
  /// axis, 12EI/l0³ across it, mixed by the angle to the touched element's normal); 0 where no
  /// element holds the node (a rigid pusher: no cap).
  double cap_compliance(const ContactCandidates& contact, int element, bool along_chord = false) const;
  CandidateTable table_of(const ContactSpec& spec) const;
  CandidateLink link(const CandidateTable& table, int element, int node) const;
  ContactCandidates candidates_of(const ContactSpec& spec, const CandidateTable& table) const;

  const Model& model_;
  std::vector<ContactCandidates> contacts_;
  /// One per candidate group; shared, so the contacts' spans stay valid in a copy.
  std::vector<std::shared_ptr<const CandidateTable>> tables_;
  std::vector<element::InitialChord> initial_;
  std::vector<int> node_start_, node_elements_;  ///< elements at each node (CSR)
  std::vector<int> candidate_elements_;
  /// Per element, the length of its member as drawn before it (F5; only where a contact has friction).
  std::vector<double> arc_start_;
  double touch_tolerance_ = 0.0;
};

/// The element displacements (u, v, θ)_i, (u, v, θ)_j of element `e`.
inline element::Vector6 element_displacements(const Element& e, const Eigen::VectorXd& displacements) {
  return tsm::element_displacements(displacements, e.start, e.end);
}

}  // namespace tsm::contact
