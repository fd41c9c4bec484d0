#pragma once
// The point loads active contacts put on their elements at a converged iterate: what a node
// arriving on such an element meets besides the element's free shape (ContactGeometry::locate,
// loaded_deflection). Only at a converged iterate: within Newton's iterates a point's Y can be far
// from the beam's (10⁸ N on a strip's predictor iterate over a stiff drum), and there the free
// shape is the safer guide.

#include <unordered_map>
#include <vector>

#include "tsmframe/contact/contact_state.hpp"

namespace tsm::contact {

/// A contact point's load on an element: its place α and its force Y on the beam along the
/// chord's normal (the law's).
struct PointLoad {
  double alpha = 0.0, Y = 0.0;
};

class ElementLoads {
 public:
  /// The loads of the active contacts in `states` (a vertex's point sits at an element end,
  /// where it bends nothing).
  explicit ElementLoads(const std::vector<ContactState>& states) {
    for (const ContactState& s : states)
      if (s.active && !s.vertex) loads_[s.element].push_back({s.alpha, s.Y});
  }
  /// The loads on `element` (none: empty).
  const std::vector<PointLoad>& on(int element) const {
    static const std::vector<PointLoad> none;
    const auto found = loads_.find(element);
    return found == loads_.end() ? none : found->second;
  }

 private:
  std::unordered_map<int, std::vector<PointLoad>> loads_;
};

}  // namespace tsm::contact
