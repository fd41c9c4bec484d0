#pragma once
// Which elements carry contact points at an update, and whether another point may join one: an
// element carries any number of chord-frame points (multi_point_element.hpp, issue 27; a vertex,
// vertex.hpp, is a point on each of its two elements), but a cantilever-frame contact
// (cantilever_frame_element.hpp, one point by its formulation) has its element to itself.

#include <vector>

#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"

namespace tsm::contact {

/// Whether a contact's element carries it alone: the cantilever frame has one point per element.
inline bool alone(const ContactCandidates& contact) { return contact.frame == ContactFrame::cantilever; }

class Occupancy {
 public:
  explicit Occupancy(size_t elements) : points_(elements, 0), exclusive_(elements, 0) {}
  /// The elements of the active contacts in `states`.
  Occupancy(const ContactGeometry& geometry, const std::vector<ContactState>& states)
      : Occupancy(geometry.model().elements.size()) {
    for (int k = 0; k < static_cast<int>(states.size()); ++k) {
      const ContactState& s = states[k];
      if (!s.active) continue;
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
  /// A point leaves `element` (an exclusive one leaves it free).
  void leave(int element) {
    --points_[element];
    exclusive_[element] = 0;
  }

 private:
  std::vector<int> points_;
  std::vector<char> exclusive_;
};

}  // namespace tsm::contact
