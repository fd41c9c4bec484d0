#include "tsmframe/model/resting_contact.hpp"

#include <cmath>
#include <numeric>
#include <vector>

#include "tsmframe/element/chord.hpp"
#include "tsmframe/util/segment_grid.hpp"

namespace tsm {
namespace {

/// How far from its node a contact's element may lie and still be rested on (the gap, and room
/// for rounding beyond it), and what counts as on the centre line (as the contact tracker's).
struct Reach {
  double tolerance, box;
};
Reach reach_of(const Model& model, const ContactSpec& contact) {
  const double tolerance = 1e-10 * model.size;
  return {tolerance, 2.0 * (contact.gap + tolerance)};
}

/// The nearest of `elements` (ascending; the first of equals) that `contact` rests on.
std::optional<RestingContact> nearest_rested_on(const Model& model, const ContactSpec& contact,
                                                const std::vector<int>& elements) {
  const auto [tolerance, reach] = reach_of(model, contact);
  std::vector<bool> in_set(model.member_count, false);
  for (const int m : contact.members) in_set[m] = true;
  const Eigen::Vector2d x = model.nodes[contact.node].position;
  std::optional<RestingContact> best;
  double best_distance = INFINITY;
  for (const int k : elements) {
    const Element& e = model.elements[k];
    if (!in_set[e.member] || e.start == contact.node || e.end == contact.node) continue;
    const Eigen::Vector2d a = model.nodes[e.start].position, b = model.nodes[e.end].position;
    // Within the gap of the chord and 0 ≤ α ≤ 1 lies within the chord's box grown by the gap:
    // most elements end at this test, without a division or a square root.
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

}  // namespace

std::optional<RestingContact> resting_contact(const Model& model, const ContactSpec& contact) {
  std::vector<int> every(model.elements.size());
  std::iota(every.begin(), every.end(), 0);
  return nearest_rested_on(model, contact, every);
}

util::SegmentGrid drawn_chords(const Model& model) {
  std::vector<util::Segment> chords;
  chords.reserve(model.elements.size());
  for (const Element& e : model.elements) chords.push_back({model.nodes[e.start].position, model.nodes[e.end].position});
  return util::SegmentGrid(chords);
}

std::vector<std::optional<RestingContact>> resting_contacts(const Model& model) {
  if (model.contacts.empty()) return {};
  return resting_contacts(model, drawn_chords(model));
}

std::vector<std::optional<RestingContact>> resting_contacts(const Model& model, const util::SegmentGrid& grid) {
  std::vector<std::optional<RestingContact>> resting(model.contacts.size());
  std::vector<int> near;
  for (size_t k = 0; k < model.contacts.size(); ++k) {
    const ContactSpec& contact = model.contacts[k];
    grid.near(model.nodes[contact.node].position, reach_of(model, contact).box, near);
    resting[k] = nearest_rested_on(model, contact, near);
  }
  return resting;
}

}  // namespace tsm
