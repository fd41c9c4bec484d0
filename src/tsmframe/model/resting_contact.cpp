#include "tsmframe/model/resting_contact.hpp"

#include <cmath>
#include <vector>

namespace tsm {

std::optional<RestingContact> resting_contact(const Model& model, const ContactSpec& contact) {
  const double tolerance = 1e-10 * model.size;  // as the contact tracker's "on the centre line"
  std::vector<bool> in_set(model.member_count, false);
  for (const int m : contact.members) in_set[m] = true;
  const Eigen::Vector2d x = model.nodes[contact.node].position;
  std::optional<RestingContact> best;
  double best_distance = INFINITY;
  for (int k = 0; k < static_cast<int>(model.elements.size()); ++k) {
    const Element& e = model.elements[k];
    if (!in_set[e.member] || e.start == contact.node || e.end == contact.node) continue;
    const Eigen::Vector2d a = model.nodes[e.start].position, chord = model.nodes[e.end].position - a;
    const double length = chord.norm();
    if (!(length > 0.0)) continue;
    const Eigen::Vector2d t = chord / length, n(-t.y(), t.x());
    const double alpha = (x - a).dot(t) / length, across = (x - a).dot(n);
    const double distance = std::abs(across);
    if (alpha < 0.0 || alpha > 1.0 || distance <= tolerance || distance > contact.gap + tolerance) continue;
    if (distance >= best_distance) continue;
    best_distance = distance;
    best = RestingContact{k, alpha, across > 0.0 ? 1 : -1, a + alpha * chord, n};
  }
  return best;
}

}  // namespace tsm
