#pragma once
// Which elements carry contact points at an update, and whether another point may join one: an
// element carries any number of points (issue 27; a vertex, vertex.hpp, is a point on each of its
// two elements), all in one frame — the chord's (multi_point_element.hpp) or the cantilever's
// (multi_point_cantilever_frame.hpp), whose element is written in another frame. It
// also knows which element each contact node is on, for the rule that keeps two beams' nodes
// resting on each other from pressing twice (detection.hpp).

#include <vector>

#include "tsmframe/contact/contact_geometry.hpp"
#include "tsmframe/contact/contact_state.hpp"

namespace tsm::contact {

class Occupancy {
 public:
  /// No points yet (`nodes`: how many nodes touching() knows of; 0: none).
  explicit Occupancy(size_t elements, size_t nodes = 0)
      : points_(elements, 0), frame_(elements, ContactFrame::chord), touching_(nodes, -1) {}
  /// The elements of the active contacts in `states`.
  Occupancy(const ContactGeometry& geometry, const std::vector<ContactState>& states)
      : Occupancy(geometry.model().elements.size(), geometry.model().node_count()) {
    for (int k = 0; k < static_cast<int>(states.size()); ++k) {
      const ContactState& s = states[k];
      if (!s.active) continue;
      touching_[geometry.contact(k).node] = s.element;
      join(s.element, geometry.contact(k).frame);
      if (s.vertex) join(s.vertex->element, geometry.contact(k).frame);
    }
  }

  /// Whether a point of a contact in `frame` may join `element` (shares_element, model.hpp).
  bool may_join(int element, ContactFrame frame) const {
    return points_[element] == 0 || shares_element(frame_[element], frame);
  }
  /// How many points are on `element`.
  int points(int element) const { return points_[element]; }
  void join(int element, ContactFrame frame) {
    ++points_[element];
    frame_[element] = frame;
  }
  /// The element the contact of `node` is on, −1: none (or not known).
  int touching(int node) const { return node < static_cast<int>(touching_.size()) ? touching_[node] : -1; }
  /// Records where the contact of `node` is after its update (−1: nowhere).
  void set_touching(int node, int element) {
    if (node < static_cast<int>(touching_.size())) touching_[node] = element;
  }
  /// A point leaves `element`.
  void leave(int element) { --points_[element]; }

 private:
  std::vector<int> points_;
  std::vector<ContactFrame> frame_;  ///< per element with points: their frame
  std::vector<int> touching_;  ///< per node: touching()
};

}  // namespace tsm::contact
