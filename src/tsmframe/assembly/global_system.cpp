#include "tsmframe/assembly/global_system.hpp"

#include "tsmframe/contact/active_contact.hpp"
#include "tsmframe/util/first_touch.hpp"
#include "tsmframe/util/parallel_for.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace tsm::assembly {
namespace {

std::array<int, 6> element_dofs(int start, int end) {
  const int i = dofs_per_node * start, j = dofs_per_node * end;
  return {i, i + 1, i + 2, j, j + 1, j + 2};
}

}  // namespace

GlobalSystem::GlobalSystem(const Model& model, const DofMap& dofs)
    : frames_(model), follower_loads_(model, dofs, frames_), springs_(model, dofs), model_(model), dofs_(dofs) {
  const int n_elements = static_cast<int>(model.elements.size());
  const int n_blocks = dofs.block_count();
  // Elements in the tangent's memory order (by the smaller block of their two nodes), cut into
  // chunks of a fixed size. A chunk sweeps a compact stretch of the tangent once, its elements
  // in order; chunks that share no node get the same colour (greedy) and a colour's chunks run
  // in parallel. Colours beyond 63 all share the last group, run serially. Every sum keeps its
  // order whatever the number of threads.
  const int chunk_size = std::clamp(n_elements / 16, 64, 512);  // 16 chunks or more: two groups of 8 for small models
  element_order_.resize(n_elements);
  std::iota(element_order_.begin(), element_order_.end(), 0);
  {
    std::vector<int> key(n_elements);
    for (int k = 0; k < n_elements; ++k) {
      const int a = dofs.block(model.elements[k].start), b = dofs.block(model.elements[k].end);
      key[k] = std::min(a < 0 ? n_blocks : a, b < 0 ? n_blocks : b);
    }
    std::stable_sort(element_order_.begin(), element_order_.end(), [&](int x, int y) { return key[x] < key[y]; });
  }
  // The records in the loop's order, so that the loop streams through them (in the model's
  // order a lattice's loop jumped between them, a cache miss per element).
  util::resize_touched(records_, n_elements);
  for (int q = 0; q < n_elements; ++q) {
    const Element& e = model.elements[element_order_[q]];
    const element::InitialChord chord = element::initial_chord(model.nodes[e.start].position, model.nodes[e.end].position);
    ElementRecord& r = records_[q];
    r.start = e.start;
    r.end = e.end;
    r.delta0[0] = chord.end.x() - chord.start.x();
    r.delta0[1] = chord.end.y() - chord.start.y();
    r.length = chord.length;
    r.angle = chord.angle;
    r.k0 = element::basic_stiffness_terms(e.section, chord.length);
    r.release_i = e.release_start;
    r.release_j = e.release_end;
    const double flexibility_i = model.flexibility_start(e), flexibility_j = model.flexibility_end(e);
    r.connected = e.release_start || e.release_end || flexibility_i > 0.0 || flexibility_j > 0.0;
    if (r.connected) {
      connections_.resize(n_elements);
      connections_[q] = {element::connected_stiffness(r.k0, e.release_start ? INFINITY : flexibility_i,
                                                      e.release_end ? INFINITY : flexibility_j),
                         flexibility_i, flexibility_j};
    }
  }

  build_pattern();
  block_mask_.assign(n_blocks, 0);
  for (int b = 0; b < n_blocks; ++b)
    for (int d = 0; d < dofs_per_node; ++d)
      if (model.constrained[dofs_per_node * dofs.block_node(b) + d]) block_mask_[b] |= 1u << d;

  const int n_chunks = (n_elements + chunk_size - 1) / chunk_size;
  chunk_start_.resize(n_chunks + 1);
  for (int c = 0; c <= n_chunks; ++c) chunk_start_[c] = std::min(n_elements, c * chunk_size);
  constexpr int serial_colour = 63;
  std::vector<std::uint64_t> seen(model.node_count(), 0);
  std::vector<int> colour(n_chunks);
  int colours = 0;
  for (int ch = 0; ch < n_chunks; ++ch) {
    std::uint64_t used = 0;
    for (int q = chunk_start_[ch]; q < chunk_start_[ch + 1]; ++q) {
      const Element& e = model.elements[element_order_[q]];
      used |= seen[e.start] | seen[e.end];
    }
    int c = 0;
    while (c < serial_colour && (used >> c & 1u)) ++c;
    colour[ch] = c;
    for (int q = chunk_start_[ch]; q < chunk_start_[ch + 1]; ++q) {
      const Element& e = model.elements[element_order_[q]];
      seen[e.start] |= std::uint64_t{1} << c;
      seen[e.end] |= std::uint64_t{1} << c;
    }
    colours = std::max(colours, c + 1);
  }
  colour_start_.assign(colours + 1, 0);
  for (int ch = 0; ch < n_chunks; ++ch) ++colour_start_[colour[ch] + 1];
  for (int c = 0; c < colours; ++c) colour_start_[c + 1] += colour_start_[c];
  colour_chunks_.resize(n_chunks);
  chunk_largest_end_rotation_.assign(n_chunks, 0.0);
  std::vector<int> fill(colour_start_.begin(), colour_start_.end() - 1);
  for (int ch = 0; ch < n_chunks; ++ch) colour_chunks_[fill[colour[ch]]++] = ch;

  replaced_.assign(n_elements, 0);
  mark_first_writers();
  has_prescribed_ = model.reference_prescribed.size() > 0 && model.reference_prescribed.any();
}

void GlobalSystem::build_pattern() {
  // Block pattern, lower triangle: column c holds the blocks ≥ c of the nodes joined to c's node
  // by an element, or by a contact element that has been active (contact_pairs_).
  const NodeGraph graph = node_graph(model_);
  const int n_blocks = dofs_.block_count();
  std::vector<std::pair<int, int>> extra;  // (column, row) of the contact pairs: few, sorted
  for (const auto& [a, b] : contact_pairs_) {
    const int ba = dofs_.block(a), bb = dofs_.block(b);
    if (ba < 0 || bb < 0 || ba == bb) continue;
    extra.emplace_back(std::min(ba, bb), std::max(ba, bb));
  }
  std::sort(extra.begin(), extra.end());
  auto next_extra = extra.begin();
  tangent_.size = n_blocks;
  tangent_.column.assign(n_blocks + 1, 0);
  tangent_.row.clear();
  for (int c = 0; c < n_blocks; ++c) {
    const int node = dofs_.block_node(c);
    const size_t first = tangent_.row.size();
    for (int p = graph.start[node]; p < graph.start[node + 1]; ++p) {
      const int r = dofs_.block(graph.neighbours[p]);
      if (r >= c) tangent_.row.push_back(r);
    }
    for (; next_extra != extra.end() && next_extra->first == c; ++next_extra) tangent_.row.push_back(next_extra->second);
    std::sort(tangent_.row.begin() + first, tangent_.row.end());
    tangent_.row.erase(std::unique(tangent_.row.begin() + first, tangent_.row.end()), tangent_.row.end());
    tangent_.column[c + 1] = static_cast<int>(tangent_.row.size());
  }
  linalg::add_fill(tangent_);  // the factor overwrites the tangent in place
  for (ElementRecord& s : records_) {
    const int bi = dofs_.block(s.start), bj = dofs_.block(s.end);
    s.ii = s.jj = s.ij = -1;
    s.transposed = false;
    if (bi >= 0) s.ii = entry(bi, bi);
    if (bj >= 0) s.jj = entry(bj, bj);
    if (bi >= 0 && bj >= 0 && bi != bj) {
      s.transposed = bi < bj;  // the lower triangle stores K(max, min): K_ji when j's block is the larger
      s.ij = s.transposed ? entry(bj, bi) : entry(bi, bj);
    }
  }
  ++pattern_version_;
}

void GlobalSystem::mark_first_writers() {
  // The loop's order: colour groups in turn, a group's chunks by index, a chunk's elements in
  // order. Chunks of one group share no node, so this is also the order in which each block and
  // each node is written, whatever the number of threads.
  std::vector<char> entry_written(tangent_.value.size(), 0), node_written(model_.node_count(), 0);
  for (size_t c = 0; c + 1 < colour_start_.size(); ++c)
    for (int idx = colour_start_[c]; idx < colour_start_[c + 1]; ++idx) {
      const int chunk = colour_chunks_[idx];
      for (int q = chunk_start_[chunk]; q < chunk_start_[chunk + 1]; ++q) {
        ElementRecord& r = records_[q];
        auto first = [](int index, std::vector<char>& written) {
          if (index < 0 || written[index]) return false;
          written[index] = 1;
          return true;
        };
        r.first_ii = first(r.ii, entry_written);
        r.first_jj = first(r.jj, entry_written);
        r.first_ij = first(r.ij, entry_written);
        r.first_i = first(r.start, node_written);
        r.first_j = first(r.end, node_written);
      }
    }
  unwritten_entries_.clear();
  for (size_t p = 0; p < entry_written.size(); ++p)
    if (!entry_written[p] && !tangent_.is_fill(p)) unwritten_entries_.push_back(static_cast<int>(p));  // fill: the factorisation zeroes it
  unwritten_nodes_.clear();
  for (size_t k = 0; k < node_written.size(); ++k)
    if (!node_written[k]) unwritten_nodes_.push_back(static_cast<int>(k));
}

int GlobalSystem::entry(int r, int c) const {
  const auto first = tangent_.row.begin() + tangent_.column[c], last = tangent_.row.begin() + tangent_.column[c + 1];
  const auto it = std::lower_bound(first, last, r);
  return it != last && *it == r ? static_cast<int>(it - tangent_.row.begin()) : -1;
}

void GlobalSystem::add_block(int a, int b, const Eigen::Matrix3d& value) {
  // K(a, b) for nodes a, b (both with blocks); the lower triangle stores K(max, min).
  const int ba = dofs_.block(a), bb = dofs_.block(b);
  if (ba < 0 || bb < 0) return;
  const int p = ba >= bb ? entry(ba, bb) : entry(bb, ba);
  if (p < 0) throw std::logic_error("GlobalSystem: a block written where the pattern has no entry");
  if (ba >= bb) tangent_.value[p] += value;
  else tangent_.value[p] += value.transpose();
}

double GlobalSystem::ElementRecord::connected_end_rotation(const element::BeamResponse& r, const Connection& c) const {
  const double at_i = r.deformations[1] - c.flexibility_i * r.forces[1];  // the node's turn less the spring's
  const double at_j = r.deformations[2] - c.flexibility_j * r.forces[2];
  return std::max(release_i ? 0.0 : std::abs(at_i), release_j ? 0.0 : std::abs(at_j));
}

void GlobalSystem::prefetch_element(int q, const Eigen::VectorXd& displacements, bool with_tangent, const Evaluation& out) const {
  // In a frame whose nodes are numbered for the factorisation (a lattice), consecutive elements'
  // blocks are far apart in the tangent: each store into one would miss the cache and stall the
  // loop, so they are asked for a few elements ahead (a chain's blocks follow each other and
  // gain nothing; bench/README.md measures both).
  const ElementRecord& ahead = records_[q];
  __builtin_prefetch(displacements.data() + dofs_per_node * ahead.start, 0);
  __builtin_prefetch(displacements.data() + dofs_per_node * ahead.end, 0);
  __builtin_prefetch(out.internal_force.data() + dofs_per_node * ahead.start, 1);
  __builtin_prefetch(out.internal_force.data() + dofs_per_node * ahead.end, 1);
  if (!with_tangent) return;
  for (const int entry : {ahead.ii, ahead.jj, ahead.ij})
    if (entry >= 0) {  // a 72-byte block spans two cache lines
      const char* block = reinterpret_cast<const char*>(tangent_.value.data() + entry);
      __builtin_prefetch(block, 1);
      __builtin_prefetch(block + 64, 1);
    }
}

template <bool only_contact_nodes>
double GlobalSystem::evaluate_element(int q, const Eigen::VectorXd& displacements,
                                      const std::vector<double>& previous_rotations, bool with_tangent,
                                      Evaluation& out) {
  const ElementRecord& slot = records_[q];
  const int k = element_order_[q];
  const auto g = element_dofs(slot.start, slot.end);
  double* force = out.internal_force.data();
  linalg::Block* value = tangent_.value.data();
  // What touches node i (its forces, K_ii, K_ij) and node j; in a full evaluation everything.
  const bool at_i = !only_contact_nodes || contact_node_[slot.start];
  const bool at_j = !only_contact_nodes || contact_node_[slot.end];
  if (replaced_[k]) {  // a contact element stands in for it: it only clears what it would have set first
    for (int a = 0; a < 3; ++a) {
      if (slot.first_i && at_i) force[g[a]] = 0.0;
      if (slot.first_j && at_j) force[g[3 + a]] = 0.0;
    }
    if (!with_tangent) return 0.0;
    if (slot.first_ii && at_i) value[slot.ii].setZero();
    if (slot.first_jj && at_j) value[slot.jj].setZero();
    if (slot.first_ij) value[slot.ij].setZero();  // at i or j: it is evaluated for one of them
    return 0.0;
  }
  const element::Vector6 d = element_displacements(displacements, slot.start, slot.end);
  const element::BeamResponse r = slot.respond(d, previous_rotations[k], with_tangent, connection(q));
  out.chord_rotations[k] = r.chord.rotation;
  for (int a = 0; a < 3; ++a) {
    if (at_i) force[g[a]] = slot.first_i ? r.nodal_forces[a] : force[g[a]] + r.nodal_forces[a];
    if (at_j) force[g[3 + a]] = slot.first_j ? r.nodal_forces[3 + a] : force[g[3 + a]] + r.nodal_forces[3 + a];
  }
  const double end_rotation = slot.end_rotation(r, connection(q));
  if (!with_tangent) return end_rotation;
  auto put = [&](int entry, bool first, const auto& block) {
    if (first) value[entry] = block;
    else value[entry] += block;
  };
  if (slot.ii >= 0 && at_i) put(slot.ii, slot.first_ii, r.tangent.topLeftCorner<3, 3>());
  if (slot.jj >= 0 && at_j) put(slot.jj, slot.first_jj, r.tangent.bottomRightCorner<3, 3>());
  if (slot.ij >= 0) {
    if (slot.transposed) put(slot.ij, slot.first_ij, r.tangent.bottomLeftCorner<3, 3>());
    else put(slot.ij, slot.first_ij, r.tangent.topRightCorner<3, 3>());
  }
  if (!has_prescribed_) return end_rotation;
  for (int b = 0; b < 6; ++b) {
    const double dp = model_.reference_prescribed[g[b]];
    if (dp == 0.0 || dofs_.equation(g[b]) >= 0) continue;
    for (int a = 0; a < 6; ++a)
      if (a < 3 ? at_i : at_j) add_coupling(g[a], r.tangent(a, b) * dp, out.prescribed_coupling);
  }
  return end_rotation;
}

double GlobalSystem::end_rotation(int q, const Eigen::VectorXd& displacements,
                                  const std::vector<double>& previous_rotations) const {
  const ElementRecord& slot = records_[q];
  const int k = element_order_[q];
  if (replaced_[k]) return 0.0;
  const element::Vector6 d = element_displacements(displacements, slot.start, slot.end);
  return slot.end_rotation(slot.respond(d, previous_rotations[k], false, connection(q)), connection(q));
}

void GlobalSystem::evaluate(const Eigen::VectorXd& displacements, const std::vector<double>& previous_rotations,
                            bool with_tangent, Evaluation& out, const std::vector<contact::ActiveContact>& contacts,
                            bool same_displacements) {
  if (with_tangent) ensure_contact_pattern(contacts);
  for (const contact::ActiveContact& a : contacts) replaced_[a.element] = 1;
  out.contacts.clear();
  if (with_tangent) contact_rank_ones_ = friction_rank_ones_ = 0;  // filled again by the contacts (finish_evaluation)
  const int n_elements = static_cast<int>(model_.elements.size());
  // The elements' first writers assign (mark_first_writers): only what no element writes is cleared.
  util::resize_touched(out.internal_force, model_.dof_count());
  for (const int node : unwritten_nodes_) out.internal_force.segment<dofs_per_node>(dofs_per_node * node).setZero();
  util::resize_touched(out.chord_rotations, n_elements);
  if (has_prescribed_) out.prescribed_coupling.setZero(dofs_.free_count());
  else out.prescribed_coupling.resize(0);  // nothing prescribed moves: no coupling to carry
  if (with_tangent) {
    const Eigen::Index unwritten = static_cast<Eigen::Index>(unwritten_entries_.size());
    const int* entry = unwritten_entries_.data();
    linalg::Block* value = tangent_.value.data();
    util::parallel_for_static(Eigen::Index{0}, unwritten, unwritten > 65536, [&](Eigen::Index q) { value[entry[q]].setZero(); });
  }

  for (size_t c = 0; c + 1 < colour_start_.size(); ++c) {
    const int begin = colour_start_[c], end = colour_start_[c + 1];
    const bool serial = c == 63 || end - begin < 4 || n_elements < util::smallest_shared_model;
    util::parallel_for_dynamic(begin, end, !serial, [&](int idx) {
      const int chunk = colour_chunks_[idx];
      double largest = 0.0;
      const int chunk_end = chunk_start_[chunk + 1];
      for (int q = chunk_start_[chunk]; q < chunk_end; ++q) {
        if (q + prefetch_distance < chunk_end) prefetch_element(q + prefetch_distance, displacements, with_tangent, out);
        largest = std::max(largest, evaluate_element<false>(q, displacements, previous_rotations, with_tangent, out));
      }
      chunk_largest_end_rotation_[chunk] = largest;
    });
  }
  if (!springs_.empty()) {  // after the elements' first writes, before the contacts, as in evaluate_contact_change
    springs_.add_forces(displacements, nullptr, out.internal_force);
    if (with_tangent)
      springs_.add_blocks(nullptr, out.prescribed_coupling, [&](int i, int j, const Eigen::Matrix3d& k) { add_block(i, j, k); });
  }
  if (!follower_loads_.empty()) {  // before the contacts and the masks, as in evaluate_contact_change
    follower_loads_.reference_load(displacements, out.reference_load);
    if (follower_loads_.has_dead()) follower_loads_.dead_load(displacements, out.dead_load);
    if (with_tangent) {
      follower_loads_.couplings(load_factor_, nullptr, [&](int i, int j, const Eigen::Matrix3d& k) { add_block(i, j, k); });
      follower_loads_.skew_terms(load_factor_, displacements, follower_rank_one_);
    }
  }
  finish_evaluation(displacements, previous_rotations, with_tangent, out, contacts, same_displacements);
}

void GlobalSystem::evaluate_contact_change(const Eigen::VectorXd& displacements,
                                           const std::vector<double>& previous_rotations, Evaluation& out,
                                           const std::vector<contact::ActiveContact>& contacts) {
  const int version = pattern_version_;
  ensure_contact_pattern(contacts);
  // A skew roller's frames turn the sums as a whole, after the loop: they are formed again whole.
  if (tangent_of_ == 0 || out.id != tangent_of_ || pattern_version_ != version || !frames_.empty()) {
    // At the same displacements (only the pattern or the frames ask for it), the contacts' kept
    // responses still stand.
    evaluate(displacements, previous_rotations, true, out, contacts, tangent_of_ != 0 && out.id == tangent_of_);
    return;
  }
  if (node_element_start_.empty()) list_node_elements();
  // The nodes whose sums change: every node of an old or a new contact element (a contact that
  // stays is added again too: its sums are formed again from their start).
  std::vector<int> nodes;
  const auto mark = [&](int node) {
    if (contact_node_[node]) return;
    contact_node_[node] = 1;
    nodes.push_back(node);
  };
  for (const int node : last_contact_nodes_) mark(node);
  for (const contact::ActiveContact& a : contacts) {
    const Element& e = model_.elements[a.element];
    mark(e.start);
    mark(e.end);
    for (const contact::ActivePoint& p : a.points) mark(p.node);
  }
  for (const contact::ActiveContact& a : contacts) replaced_[a.element] = 1;
  // What no element writes starts from zero (the contacts add to it), as in evaluate().
  for (const int node : unwritten_nodes_)
    if (contact_node_[node]) out.internal_force.segment<dofs_per_node>(dofs_per_node * node).setZero();
  for (const int p : unwritten_entries_) tangent_.value[p].setZero();
  if (has_prescribed_)
    for (const int node : nodes)
      for (int d = 0; d < dofs_per_node; ++d)
        if (const int row = dofs_.equation(dofs_per_node * node + d); row >= 0) out.prescribed_coupling[row] = 0.0;
  // Every element at those nodes, in the loop's order (chunks by rank, then place).
  std::vector<std::pair<int, int>> places;  // (chunk's rank, q)
  const int chunk_size = chunk_start_.size() > 1 ? chunk_start_[1] : 1;
  for (const int node : nodes)
    for (int p = node_element_start_[node]; p < node_element_start_[node + 1]; ++p)
      places.push_back({chunk_rank_[node_elements_[p] / chunk_size], node_elements_[p]});
  std::sort(places.begin(), places.end());
  places.erase(std::unique(places.begin(), places.end()), places.end());
  for (const auto& [rank, q] : places) evaluate_element<true>(q, displacements, previous_rotations, true, out);
  // Their chunks' largest end rotations again (a replaced element counts 0).
  for (size_t p = 0; p < places.size(); ++p) {
    const int chunk = places[p].second / chunk_size;
    if (p > 0 && places[p - 1].second / chunk_size == chunk) continue;
    double largest = 0.0;
    for (int q = chunk_start_[chunk]; q < chunk_start_[chunk + 1]; ++q)
      largest = std::max(largest, end_rotation(q, displacements, previous_rotations));
    chunk_largest_end_rotation_[chunk] = largest;
  }
  // The re-evaluated elements formed their (i, j) blocks anew: their follower loads' coupling
  // joins them again, in the same order as in evaluate() (after the elements, before contacts).
  follower_loads_.couplings(load_factor_, &contact_node_, [&](int i, int j, const Eigen::Matrix3d& k) { add_block(i, j, k); });
  if (!springs_.empty()) {  // and the springs at those nodes
    springs_.add_forces(displacements, &contact_node_, out.internal_force);
    springs_.add_blocks(&contact_node_, out.prescribed_coupling, [&](int i, int j, const Eigen::Matrix3d& k) { add_block(i, j, k); });
  }
  for (const int node : nodes) contact_node_[node] = 0;
  out.contacts.clear();
  contact_rank_ones_ = friction_rank_ones_ = 0;
  finish_evaluation(displacements, previous_rotations, true, out, contacts, true);
}

void GlobalSystem::list_node_elements() {
  const int n_nodes = model_.node_count();
  chunk_rank_.assign(chunk_start_.size() - 1, 0);
  node_element_start_.assign(n_nodes + 1, 0);
  int rank = 0;
  for (size_t c = 0; c + 1 < colour_start_.size(); ++c)
    for (int idx = colour_start_[c]; idx < colour_start_[c + 1]; ++idx) chunk_rank_[colour_chunks_[idx]] = rank++;
  for (const ElementRecord& r : records_) {
    ++node_element_start_[r.start + 1];
    ++node_element_start_[r.end + 1];
  }
  for (int k = 0; k < n_nodes; ++k) node_element_start_[k + 1] += node_element_start_[k];
  node_elements_.resize(node_element_start_[n_nodes]);
  std::vector<int> next(node_element_start_.begin(), node_element_start_.end() - 1);
  for (int q = 0; q < static_cast<int>(records_.size()); ++q) {  // places ascending: sorted by q per node
    node_elements_[next[records_[q].start]++] = q;
    node_elements_[next[records_[q].end]++] = q;
  }
  contact_node_.assign(n_nodes, 0);
}

Eigen::VectorXd GlobalSystem::element_forces(const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                                             const std::vector<contact::ActiveContact>& contacts) const {
  const int n_elements = static_cast<int>(records_.size());
  Eigen::VectorXd forces;
  util::resize_touched(forces, 3 * n_elements);
  util::parallel_for_static(0, n_elements, n_elements > 65536, [&](int q) {
    const ElementRecord& slot = records_[q];
    const int k = element_order_[q];
    const element::Vector6 d = element_displacements(displacements, slot.start, slot.end);
    forces.segment<3>(3 * k) = slot.respond(d, rotations[k], false, connection(q)).forces;
  });
  for (const contact::ActiveContact& a : contacts) {
    const Eigen::VectorXd d = gather(displacements, contact_dofs(model_.elements[a.element], a));
    forces.segment<3>(3 * a.element) = contact::active_contact_response(a, d, rotations[a.element], false).forces.head<3>();
  }
  return forces;
}

std::vector<ContactDirection> GlobalSystem::contact_directions(const Eigen::VectorXd& displacements,
                                                              const std::vector<double>& rotations,
                                                              const std::vector<contact::ActiveContact>& contacts) const {
  return assembly::contact_directions(model_, dofs_, frames_, displacements, rotations, contacts);
}

RoundingFloor GlobalSystem::rounding_floor(const Eigen::VectorXd& displacements, const std::vector<double>& rotations,
                                           const std::vector<contact::ActiveContact>& contacts) const {
  // Squares summed: element errors taken as independent. Asked for only when Newton stagnates.
  std::vector<char> replaced(model_.elements.size(), 0);
  for (const contact::ActiveContact& a : contacts) replaced[a.element] = 1;
  // Per chunk of the loop's order, on both threads; then summed chunk by chunk in that order,
  // so the floor is the same whatever the thread count.
  const int n_chunks = static_cast<int>(chunk_start_.size()) - 1;
  std::vector<std::array<double, 2>> chunk_sum(n_chunks, {0.0, 0.0});
  util::parallel_for_static(0, n_chunks, n_chunks > 1 && static_cast<int>(records_.size()) >= util::smallest_shared_model, [&](int chunk) {
    double force = 0.0, moment = 0.0;
    for (int q = chunk_start_[chunk]; q < chunk_start_[chunk + 1]; ++q) {
      const ElementRecord& slot = records_[q];
      const int k = element_order_[q];
      if (replaced[k]) continue;
      const element::Vector6 d = element_displacements(displacements, slot.start, slot.end);
      const element::BeamResponse r = slot.respond(d, rotations[k], false, connection(q));
      const element::RoundOffFloor f = element::round_off_floor(slot.chord(), slot.stiffness(connection(q)), d, r);
      force += 4.0 * f.force * f.force;  // two nodes, two translations each
      moment += 2.0 * f.moment * f.moment;
    }
    chunk_sum[chunk] = {force, moment};
  });
  std::array<double, 2> squared = {0.0, 0.0};
  for (const auto& [f, m] : chunk_sum) {
    squared[0] += f;
    squared[1] += m;
  }
  std::vector<ContactRounding> shares;
  for (const contact::ActiveContact& a : contacts)
    shares.push_back(contact_rounding(a, gather(displacements, contact_dofs(model_.elements[a.element], a)),
                                      rotations[a.element]));
  return assembly::rounding_floor(squared, contacts, shares);
}

}  // namespace tsm::assembly
