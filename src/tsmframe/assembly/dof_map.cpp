#include "tsmframe/assembly/dof_map.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "tsmframe/assembly/elimination_order.hpp"
#include "tsmframe/element/chord.hpp"
#include "tsmframe/model/resting_contact.hpp"
#include "tsmframe/util/first_touch.hpp"
#include "tsmframe/util/segment_grid.hpp"

namespace tsm::assembly {
namespace {

/// The candidate element of `spec` nearest its node as drawn (distance to the chord, less the
/// contact's gap), if that is at most `reach`; −1 otherwise; the last of equals. `chords`: a grid
/// over the elements' chords as drawn. The square searched doubles until it holds every element
/// nearer than the nearest found (or all within the reach), so the answer is a scan's.
int nearest_candidate(const Model& model, const ContactSpec& spec, double reach, const util::SegmentGrid& chords,
                      std::vector<int>& near) {
  const Eigen::Vector2d x = model.nodes[spec.node].position;
  for (double r = chords.cell();; r *= 2.0) {
    chords.near(x, r, near);
    int nearest = -1;
    double best = reach;
    for (const int k : near) {
      const Element& e = model.elements[k];
      if (e.start == spec.node || e.end == spec.node ||
          std::find(spec.members.begin(), spec.members.end(), e.member) == spec.members.end())
        continue;
      const double distance =
          element::distance_to_segment(model.nodes[e.start].position, model.nodes[e.end].position, x) - spec.gap;
      if (distance <= best) best = distance, nearest = static_cast<int>(k);
    }
    // The square's edges rounded, and distance − gap rounded at the gap's scale (where two
    // distances round to one value, the later element wins: it must be in the square).
    const double margin = 1e-9 * (r + x.cwiseAbs().maxCoeff() + std::abs(spec.gap));
    if (!chords.usable() || best + spec.gap + margin < r || !(reach + spec.gap + margin >= r)) return nearest;
  }
}

}  // namespace

DofMap::DofMap(const Model& model) {
  const int n = model.node_count();
  // Contacts join their node to the element they touch: ordered as if joined by an element where
  // that is known or likely before the run — the element a contact rests on, or else the nearest
  // of its candidates within half the model's size beyond its gap. A mat lying on a beam, 1,000
  // nodes on 3,000 elements, ordered as two separate chains, fills in completely once its
  // contacts join them (a dense block). The reach is wide: a beam drawn a twentieth of the
  // model's size above another closes its contacts within its first step.
  std::vector<std::pair<int, int>> joined;
  const util::SegmentGrid chords = model.contacts.empty() ? util::SegmentGrid({}) : drawn_chords(model);
  const std::vector<std::optional<RestingContact>> resting = resting_contacts(model, chords);
  std::vector<int> near;
  for (size_t c = 0; c < model.contacts.size(); ++c) {
    const ContactSpec& spec = model.contacts[c];
    bool moves = false;  // a node held in every dof (a rigid pusher) is no unknown: nothing to order
    for (int d = 0; d < dofs_per_node; ++d) moves = moves || !model.constrained[dofs_per_node * spec.node + d];
    if (!moves) continue;
    int element = -1;
    if (const std::optional<RestingContact>& rest = resting[c]) element = rest->element;
    else element = nearest_candidate(model, spec, 0.5 * model.size, chords, near);
    if (element < 0) continue;
    joined.emplace_back(spec.node, model.elements[element].start);
    joined.emplace_back(spec.node, model.elements[element].end);
  }
  const std::vector<int> order = elimination_order(node_graph(model, joined));

  util::assign_touched(equation_, model.dof_count(), -1);
  util::assign_touched(node_block_, n, -1);
  util::reserve_touched(free_dofs_, model.dof_count());  // exact sizes below: no growth by doubling
  util::reserve_touched(block_node_, n);

  for (int k = 0; k < n; ++k) {
    const int node = order[k];
    bool free = false;
    for (int d = 0; d < dofs_per_node; ++d) free = free || !model.constrained[dofs_per_node * node + d];
    if (!free) continue;
    node_block_[node] = static_cast<int>(block_node_.size());
    block_node_.push_back(node);
    for (int d = 0; d < dofs_per_node; ++d) {
      const int dof = dofs_per_node * node + d;
      if (model.constrained[dof]) continue;
      equation_[dof] = static_cast<int>(free_dofs_.size());
      free_dofs_.push_back(dof);
    }
  }
  free_dofs_.shrink_to_fit();
  block_node_.shrink_to_fit();
}

}  // namespace tsm::assembly
