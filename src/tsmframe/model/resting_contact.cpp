#include "tsmframe/model/resting_contact.hpp"

#include <cmath>
#include <vector>

#include "tsmframe/element/chord.hpp"

namespace tsm {

std::optional<RestingContact> resting_contact(const Model& model, const ContactSpec& contact) {
  const double tolerance = 1e-10 * model.size;  // as the contact tracker's "on the centre line"
  std::vector<bool> in_set(model.member_count, false);
  for (const int m : contact.members) in_set[m] = true;
  const Eigen::Vector2d x = model.nodes[contact.node].position;
  const double reach = 2.0 * (contact.gap + tolerance);  // room for rounding beyond the gap
  std::optional<RestingContact> best;
  double best_distance = INFINITY;
  for (int k = 0; k < static_cast<int>(model.elements.size()); ++k) {
    const Element& e = model.elements[k];
    if (!in_set[e.member] || e.start == contact.node || e.end == contact.node) continue;
    const Eigen::Vector2d a = model.nodes[e.start].position, b = model.nodes[e.end].position;
    // Within the gap of the chord and 0 ≤ α ≤ 1 lies within the chord's box grown by the gap:
    // most elements of a long beam end at this test, without a division or a square root.
    const Eigen::Vector2d low = a.cwiseMin(b).array() - reach, high = a.cwiseMax(b).array() + reach;
    if ((x.array() < low.array()).any() || (x.array() > high.array()).any()) continue;
    const auto [alpha, across] = element::place_on_chord(a, b, x);
    const double distance = std::abs(across);
    if (alpha < 0.0 || alpha > 1.0 || distance <= tolerance || distance > contact.gap + tolerance) continue;
    if (distance >= best_distance) continue;
    best_distance = distance;
    const Eigen::Vector2d t = (b - a).normalized();
    best = RestingContact{k, alpha, across > 0.0 ? 1 : -1, a + alpha * (b - a), Eigen::Vector2d(-t.y(), t.x())};
  }
  return best;
}

}  // namespace tsm
