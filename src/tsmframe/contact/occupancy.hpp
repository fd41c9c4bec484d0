#pragma once
// Which elements carry contact points at an update, and whether another point may join one: an
// element carries any number of chord-frame points (multi_point_element.hpp, issue 27; a vertex,
// vertex.hpp, is a point on each of its two elements), but a cantilever-frame contact
// (cantilever_frame_element.hpp, one point by its formulation) has its element to itself. It
// also knows which element each contact node is on, for the rule that keeps two beams' nodes
// resting on each other from pressing twice (detection.hpp).

#include <vector>

#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"

namespace tsm::contact {

/// Whether a contact's element carries it alone (keeps_element_to_itself, model.hpp).
inline bool alone(const ContactCandidates& contact) { return keeps_element_to_itself(contact.frame); }

class Occupancy {
 public:
  /// No points yet (`nodes`: how many nodes touching() knows of; 0: none).
  explicit Occupancy(size_t elements, size_t nodes = 0) : points_(elements, 0), exclusive_(elements, 0), touching_(nodes, -1) {}
  /// The elements of the active contacts in `states`.
  Occupancy(const ContactGeometry& geometry, const std::vector<ContactState>& states)
      : Occupancy(geometry.model().elements.size(), geometry.model().node_count()) {
    for (int k = 0; k < static_cast<int>(states.size()); ++k) {
      const ContactState& s = states[k];
      if (!s.active) continue;
      touching_[geometry.contact(k).node] = s.element;
      join(s.element, alone(geometry.contact(k)));
      if (s.vertex) join(s.vertex->element, alone(geometry.contact(k)));
    }
  }

  /// Whether a point (`exclusive`: one that needs the element to itself) may join `element`.
  bool may_join(int element, bool exclusive) const {
    return !exclusive_[element] && (!exclusive || points_[element] == 0);
  }
  /// How many points are on `element`.
  int points(int element) const { return points_[element]; }
  void join(int element, bool exclusive) {
    ++points_[element];
    if (exclusive) exclusive_[element] = 1;
  }
  /// The element the contact of `node` is on, −1: none (or not known).
  int touching(int node) const { return node < static_cast<int>(touching_.size()) ? touching_[node] : -1; }
  /// Records where the contact of `node` is after its update (−1: nowhere).
  void set_touching(int node, int element) {
    if (node < static_cast<int>(touching_.size())) touching_[node] = element;
  }
  /// A point leaves `element` (an exclusive one leaves it free).
  void leave(int element) {
    --points_[element];
    exclusive_[element] = 0;
  }

 private:
  std::vector<int> points_;
  std::vector<char> exclusive_;
  std::vector<int> touching_;  ///< per node: touching()
};

}  // namespace tsm::contact
