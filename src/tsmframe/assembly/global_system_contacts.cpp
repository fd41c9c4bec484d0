#include "tsmframe/assembly/global_system.hpp"
// GlobalSystem's contact elements: the pattern their node pairs need, their responses formed in
// parallel and added in the contacts' order (forces, node blocks, sliding terms).

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "tsmframe/assembly/contact_assembly.hpp"
#include "tsmframe/contact/active_contact.hpp"
#include "tsmframe/util/parallel_for.hpp"

namespace tsm::assembly {
namespace {

// Point p's values in either response: one point's scalars and vectors, or k points' columns.
double point_alpha(const contact::ContactResponse& r, int) { return r.alpha; }
double point_alpha(const contact::MultiPointResponse& r, int p) { return r.alpha[p]; }
double point_force_per_Y(const contact::ContactResponse& r, int) { return r.force_per_Y; }
double point_force_per_Y(const contact::MultiPointResponse& r, int p) { return r.force_per_Y[p]; }
const contact::Vector9& sliding_u(const contact::ContactResponse& r, int) { return r.sliding_u; }
const contact::Vector9& sliding_v(const contact::ContactResponse& r, int) { return r.sliding_v; }
auto sliding_u(const contact::MultiPointResponse& r, int p) { return r.sliding_u.col(p); }
auto sliding_v(const contact::MultiPointResponse& r, int p) { return r.sliding_v.col(p); }
double point_alpha(const KeptPointResponse& r, int) { return r.alpha; }
double point_force_per_Y(const KeptPointResponse& r, int) { return r.force_per_Y; }
const contact::Vector9& sliding_u(const KeptPointResponse& r, int) { return r.sliding_u; }
const contact::Vector9& sliding_v(const KeptPointResponse& r, int) { return r.sliding_v; }
// Friction: the return map's result (none in a kept response: no frictional one is kept).
contact::FrictionResult point_friction(const contact::ContactResponse& r, int) { return r.friction; }
contact::FrictionResult point_friction(const contact::MultiPointResponse& r, int p) {
  return r.friction.empty() ? contact::FrictionResult{} : r.friction[static_cast<size_t>(p)];
}
contact::FrictionResult point_friction(const KeptPointResponse&, int) { return {}; }
// The symmetric tangent's node block (p, q ≥ p), the `pair`-th in that order.
template <class Response>
auto node_block(const Response& r, int p, int q, int) { return r.symmetric_tangent.template block<3, 3>(3 * p, 3 * q); }
const Eigen::Matrix3d& node_block(const KeptPointResponse& r, int, int, int pair) { return r.blocks[pair]; }
// The full tangent's entry (k, b): what a prescribed displacement couples (no response is kept
// in a model with one).
template <class Response>
double tangent_entry(const Response& r, int k, int b) { return r.tangent(k, b); }
double tangent_entry(const KeptPointResponse&, int, int) {
  throw std::logic_error("GlobalSystem: a kept contact response where displacements are prescribed");
}

}  // namespace

void GlobalSystem::ensure_contact_pattern(const std::vector<contact::ActiveContact>& contacts) {
  // The pairs the contacts join, each contact node with its element's nodes and the other points
  // on the element (coupled through the beam), lower node first: one pair whichever of its two
  // nodes is the contact's (beams touching each other both ways visit it either way round).
  const auto for_each_pair = [&contacts, this](const auto& visit) {
    const auto ordered = [&visit](int a, int b) { visit(std::min(a, b), std::max(a, b)); };
    for (const contact::ActiveContact& a : contacts) {
      const Element& e = model_.elements[a.element];
      for (int p = 0; p < a.size(); ++p) {
        ordered(a.points[p].node, e.start);
        ordered(a.points[p].node, e.end);
        for (int q = 0; q < p; ++q) ordered(a.points[p].node, a.points[q].node);
      }
    }
  };
  bool forgot = false, missing = false;
  if (std::exchange(forget_contact_pairs_, false) && !contact_pairs_.empty()) {
    std::vector<std::pair<int, int>> used;
    for_each_pair([&used](int a, int b) { used.emplace_back(a, b); });
    std::sort(used.begin(), used.end());
    const size_t before = contact_pairs_.size();
    std::erase_if(contact_pairs_, [&used](const std::pair<int, int>& pair) {
      return !std::binary_search(used.begin(), used.end(), pair);
    });
    forgot = contact_pairs_.size() != before;
    if (forgot) build_pattern();  // what ensure() reads next is the pattern without them
  }
  const auto ensure = [&](int a, int b) {
    const int bc = dofs_.block(a), bn = dofs_.block(b);
    if (bc < 0 || bn < 0 || bc == bn) return;
    // An entry that is fill of the factor is no entry of A: the factorisation starts it at
    // zero, so a contact element's block written there would be lost. The pair is added.
    const int p = entry(std::max(bc, bn), std::min(bc, bn));
    if (p >= 0 && !tangent_.is_fill(p)) return;
    contact_pairs_.emplace_back(a, b);
    missing = true;
  };
  for_each_pair(ensure);
  if (missing) build_pattern();
  if (forgot || missing) mark_first_writers();
}

void GlobalSystem::contact_blocks(const contact::ActiveContact& a, std::vector<int>& blocks) const {
  const Element& e = model_.elements[a.element];
  const auto node = [&](int p) { return p == 0 ? e.start : p == 1 ? e.end : a.points[p - 2].node; };
  blocks.clear();
  for (int p = 0; p < 2 + a.size(); ++p)
    for (int q = p; q < 2 + a.size(); ++q) {
      const int bp = dofs_.block(node(p)), bq = dofs_.block(node(q));
      if ((p != q && node(p) == node(q)) || bp < 0 || bq < 0) {
        blocks.push_back(-1);
        continue;
      }
      const int entry_index = bp >= bq ? entry(bp, bq) : entry(bq, bp);
      if (entry_index < 0) throw std::logic_error("GlobalSystem: a block written where the pattern has no entry");
      blocks.push_back(2 * entry_index + (bp >= bq ? 0 : 1));
    }
}

void GlobalSystem::prefetch_contact_blocks(const std::vector<int>& blocks) const {
  for (const int slot : blocks)
    if (slot >= 0) {  // a 72-byte block spans two cache lines
      const char* block = reinterpret_cast<const char*>(tangent_.value.data() + slot / 2);
      __builtin_prefetch(block, 1);
      __builtin_prefetch(block + 64, 1);
    }
}

template <class Response>
void GlobalSystem::add_contact(const contact::ActiveContact& a, const Response& r, const std::vector<int>& blocks,
                               bool with_tangent, Evaluation& out) {
  const Element& e = model_.elements[a.element];
  std::vector<int>& g = contact_dofs_;
  contact_dofs(e, a, g);
  const int size = static_cast<int>(g.size());
  out.chord_rotations[a.element] = r.chord.rotation;
  for (int p = 0; p < a.size(); ++p)
    out.contacts.push_back({a.points[p].contact, a.points[p].vertex, point_alpha(r, p), r.forces[3 + p],
                            point_force_per_Y(r, p), r.nodal_forces.template segment<2>(6 + 3 * p), point_friction(r, p)});
  for (int k = 0; k < size; ++k) out.internal_force[g[k]] += r.nodal_forces[k];
  if (!with_tangent) return;
  // The symmetric part joins the node blocks (i, j, then each point's node; each node pair once,
  // the lower triangle) at the entries contact_blocks found; each point's sliding term stays a
  // rank-one term for the linear solver.
  int pair = 0;
  for (int p = 0; p < size / dofs_per_node; ++p)
    for (int q = p; q < size / dofs_per_node; ++q) {
      const int slot = blocks[pair];
      const auto value = node_block(r, p, q, pair++);
      if (slot < 0) continue;
      if (slot % 2 == 0) tangent_.value[slot / 2] += value;
      else tangent_.value[slot / 2] += value.transpose();
    }
  std::vector<int>& equation = contact_equations_;
  equation.resize(g.size());
  for (int k = 0; k < size; ++k) equation[k] = dofs_.equation(g[k]);
  const auto add_rank_one = [&](const auto& u, const auto& v, std::vector<linalg::RankOne>& terms, size_t& count) {
    if (u.squaredNorm() == 0.0 || v.squaredNorm() == 0.0) return;
    if (count == terms.size()) terms.emplace_back();
    linalg::RankOne& term = terms[count++];  // its storage reused
    term.equation.assign(equation.begin(), equation.end());
    term.u = u;
    term.v = v;
    frames_.to_nodal(g, term.u);
    frames_.to_nodal(g, term.v);
  };
  // A frictional point's sliding term joins its friction term: its normal force's rate along the
  // beam is its friction force's too, not optional.
  for (int p = 0; p < a.size(); ++p) {
    const bool frictional = point_friction(r, p).status != contact::FrictionStatus::none &&
                            point_friction(r, p).status != contact::FrictionStatus::open;
    add_rank_one(sliding_u(r, p), sliding_v(r, p), frictional ? friction_rank_one_ : contact_rank_one_,
                 frictional ? friction_rank_ones_ : contact_rank_ones_);
  }
  if constexpr (std::is_same_v<Response, contact::ContactResponse>)
    add_rank_one(r.friction_u, r.friction_v, friction_rank_one_, friction_rank_ones_);
  if constexpr (std::is_same_v<Response, contact::MultiPointResponse>)
    for (Eigen::Index p = 0; p < r.friction_u.cols(); ++p)
      add_rank_one(r.friction_u.col(p), r.friction_v.col(p), friction_rank_one_, friction_rank_ones_);
  if (!has_prescribed_) return;
  for (int b = 0; b < size; ++b) {
    const double dp = model_.reference_prescribed[g[b]];
    if (dp == 0.0 || equation[b] >= 0) continue;
    for (int k = 0; k < size; ++k) add_coupling(g[k], tangent_entry(r, k, b) * dp, out.prescribed_coupling);
  }
}

void GlobalSystem::finish_evaluation(const Eigen::VectorXd& displacements, const std::vector<double>& previous_rotations,
                                     bool with_tangent, Evaluation& out, const std::vector<contact::ActiveContact>& contacts,
                                     bool same_displacements) {
  out.largest_end_rotation = 0.0;  // a maximum: the same whatever the order
  for (const double largest : chunk_largest_end_rotation_) out.largest_end_rotation = std::max(out.largest_end_rotation, largest);
  // The contact elements' responses, each a function of its own dofs, are formed in parallel a
  // chunk at a time and added in the contacts' order: the sums are the same on any number of
  // threads, and a chunk's responses are all that is held at once.
  // A one-point contact's response is kept (KeptPointResponse, per contact): a contact change at
  // the same displacements forms only the contacts that changed. Not where displacements are
  // prescribed (their coupling reads the full tangent).
  const std::uint64_t id = evaluations_ + 1;
  const bool keep_responses = with_tangent && !has_prescribed_;
  if (keep_responses)
    for (const contact::ActiveContact& a : contacts)
      if (a.size() == 1 && static_cast<size_t>(a.points.front().contact) >= kept_responses_.size())
        kept_responses_.resize(static_cast<size_t>(a.points.front().contact) + 1);
  const auto kept = [&](const contact::ActiveContact& a) -> KeptPointResponse* {
    const contact::ActivePoint& p = a.points.front();
    // Not a frictional one: its response reads its anchor, which an update may set.
    return keep_responses && a.size() == 1 && !p.vertex && a.data.front().friction.mu == 0.0 ? &kept_responses_[p.contact]
                                                                                                  : nullptr;
  };
  constexpr size_t chunk = 256;
  for (size_t begin = 0; begin < contacts.size(); begin += chunk) {
    const size_t count = std::min(chunk, contacts.size() - begin);
    if (contact_responses_.size() < count)
      contact_responses_.resize(count), point_responses_.resize(count), contact_blocks_.resize(count);
    util::parallel_for_dynamic(size_t{0}, count, count >= 16, [&](size_t i) {
      const contact::ActiveContact& a = contacts[begin + i];
      KeptPointResponse* k = kept(a);
      if (k && same_displacements && k->stands_for(a, id)) k->evaluation = id;
      else if (a.size() == 1) {
        contact_element_response(model_, a, displacements, previous_rotations, with_tangent, point_responses_[i]);
        if (k) keep(a, point_responses_[i], id, *k);
      } else contact_element_response(model_, a, displacements, previous_rotations, with_tangent, contact_responses_[i]);
      if (with_tangent) contact_blocks(contacts[begin + i], contact_blocks_[i]);
    });
    // The blocks are scattered through the tangent (numbered for the factorisation): each
    // contact's are asked for a few contacts ahead, as the elements' are (prefetch_element).
    constexpr size_t prefetch_distance = 4;
    for (size_t i = 0; i < count; ++i) {
      if (with_tangent && i + prefetch_distance < count) prefetch_contact_blocks(contact_blocks_[i + prefetch_distance]);
      const contact::ActiveContact& a = contacts[begin + i];
      if (const KeptPointResponse* k = kept(a)) add_contact(a, *k, contact_blocks_[i], with_tangent, out);
      else if (a.size() == 1) add_contact(a, point_responses_[i], contact_blocks_[i], with_tangent, out);
      else add_contact(a, contact_responses_[i], contact_blocks_[i], with_tangent, out);
      replaced_[contacts[begin + i].element] = 0;
    }
  }
  if (with_tangent) contact_rank_one_.resize(contact_rank_ones_), friction_rank_one_.resize(friction_rank_ones_);
  if (!frames_.empty()) turn_to_nodal_frames(out, with_tangent);
  if (with_tangent) mask_constrained_dofs();
  out.id = ++evaluations_;
  tangent_of_ = with_tangent ? out.id : 0;
  last_contact_nodes_.clear();
  for (const contact::ActiveContact& a : contacts) {
    const Element& e = model_.elements[a.element];
    last_contact_nodes_.push_back(e.start);
    last_contact_nodes_.push_back(e.end);
    for (const contact::ActivePoint& p : a.points) last_contact_nodes_.push_back(p.node);
  }
}

}  // namespace tsm::assembly
