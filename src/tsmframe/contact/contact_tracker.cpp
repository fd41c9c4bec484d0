#include "tsmframe/contact/contact_tracker.hpp"

#include "tsmframe/model/resting_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace tsm::contact {
namespace {

constexpr double alpha_tolerance = 1e-12;  // a node on a beam node counts for both elements
// A side is recorded only while the node lies within this reach along the element (α from
// −reach to 1 + reach): a node far beyond an element's ends has no meaningful side of it, and
// its side flipping there (a beam swinging around) must not start a contact later.
constexpr double side_reach = 1.0;
// A vertex holds the node at a beam node, where only the compliance floor (edge δ) keeps the
// contact law finite: with the floor switched off (the paper's element as published, δ → 0) a
// vertex would be singular, and there is none.
constexpr double vertex_min_edge = 1e-6;
// … and it is taken only by a point at most this far (a fraction of either element) past the
// node: a point sliding over many short elements hops about while it overshoots.
constexpr double vertex_reach = 0.5;

int sign(double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); }

element::Vector6 element_displacements(const Element& e, const Eigen::VectorXd& D) {
  return tsm::element_displacements(D, e.start, e.end);
}

/// Unit normal n of an element's current chord.
Eigen::Vector2d chord_normal(const element::InitialChord& initial, const element::Vector6& d, double rotation) {
  const element::Chord chord = element::current_chord(initial, d, rotation);
  return {-chord.sin, chord.cos};
}

}  // namespace

ContactTracker::ContactTracker(const Model& model) : model_(model) {
  if (model.contacts.empty()) return;  // nothing to track: no per-element data for big contact-free models
  const int n_elements = static_cast<int>(model.elements.size());
  initial_.reserve(n_elements);
  for (const Element& e : model.elements)
    initial_.push_back(element::initial_chord(model.nodes[e.start].position, model.nodes[e.end].position));
  node_start_.assign(model.node_count() + 1, 0);
  for (const Element& e : model.elements) {
    ++node_start_[e.start + 1];
    ++node_start_[e.end + 1];
  }
  for (int k = 0; k < model.node_count(); ++k) node_start_[k + 1] += node_start_[k];
  node_elements_.resize(node_start_.back());
  std::vector<int> fill(node_start_.begin(), node_start_.end() - 1);
  for (int k = 0; k < n_elements; ++k) {
    node_elements_[fill[model.elements[k].start]++] = k;
    node_elements_[fill[model.elements[k].end]++] = k;
  }
  touch_tolerance_ = 1e-10 * model.size;

  for (const ContactSpec& c : model.contacts) {
    Spec s;
    s.node = c.node;
    s.candidate_index.assign(n_elements, -1);
    std::vector<bool> in_set(model.member_count, false);
    for (int m : c.members) in_set[m] = true;
    const bool timoshenko_override = c.element == "timoshenko", euler_bernoulli_override = c.element == "euler-bernoulli";
    for (int k = 0; k < n_elements; ++k) {
      const Element& e = model.elements[k];
      if (!in_set[e.member]) continue;
      s.candidate_index[k] = static_cast<int>(s.candidates.size());
      s.candidates.push_back(k);
      double psi = e.section.shear_flexibility;
      if (euler_bernoulli_override) psi = 0.0;
      if (timoshenko_override) psi = c.member_shear_flexibility[e.member];
      s.shear_flexibility.push_back(psi);
    }
    s.gap = c.gap;
    s.edge = c.edge;
    s.max_stiffness_ratio = c.max_stiffness_ratio;
    for (int p = node_start_[c.node]; p < node_start_[c.node + 1]; ++p) {
      const int e = node_elements_[p];
      const element::SectionStiffness& section = model.elements[e].section;
      s.own.push_back({std::cos(initial_[e].angle), std::sin(initial_[e].angle), section.EA, section.EI, initial_[e].length});
    }
    s.sliding_term = c.sliding_tangent;
    s.cantilever_frame = c.frame == "cantilever";
    specs_.push_back(std::move(s));
  }
  std::vector<char> candidate(n_elements, 0);
  for (const Spec& spec : specs_)
    for (const int f : spec.candidates) candidate[f] = 1;
  for (int k = 0; k < n_elements; ++k)
    if (candidate[k]) candidate_elements_.push_back(k);
}

double ContactTracker::cap_compliance(const Spec& spec, int element) const {
  const double angle = initial_[element].angle;
  const Eigen::Vector2d normal(-std::sin(angle), std::cos(angle));
  double stiffest = 0.0;
  for (const Spec::Own& o : spec.own) {
    const double along = o.cos * normal.x() + o.sin * normal.y();
    const double c2 = along * along;  // the element's axis against the contact's normal
    stiffest = std::max(stiffest, c2 * o.EA / o.l0 + (1.0 - c2) * 12.0 * o.EI / (o.l0 * o.l0 * o.l0));
  }
  return stiffest > 0.0 ? 1.0 / (spec.max_stiffness_ratio * stiffest) : 0.0;
}

double ContactTracker::edge_of(const Spec& spec) { return spec.edge >= 0.0 ? spec.edge : default_edge(); }

element::SectionStiffness ContactTracker::contact_section(const Spec& spec, int element) const {
  element::SectionStiffness s = model_.elements[element].section;
  s.shear_flexibility = spec.shear_flexibility[spec.candidate_index[element]];
  return s;
}

std::pair<double, double> ContactTracker::end_flexibilities(int element) const {
  const Element& e = model_.elements[element];
  return {e.release_start ? INFINITY : model_.flexibility_start(e), e.release_end ? INFINITY : model_.flexibility_end(e)};
}

NodeOnElement ContactTracker::locate(const Spec& spec, int element, const Eigen::VectorXd& D,
                                     const std::vector<double>& chord_rotations, double lowest, double highest) const {
  const Element& e = model_.elements[element];
  const Eigen::Vector2d position = model_.nodes[spec.node].position + D.segment<2>(dofs_per_node * spec.node);
  const element::Vector6 d = element_displacements(e, D);
  // α first, from the chord alone: a node beyond the span asked for needs no gap (most of a
  // long beam's elements, for each contact node).
  if (const double alpha = alpha_on_element(initial_[element], d, position); alpha < lowest || alpha > highest)
    return {alpha, std::numeric_limits<double>::quiet_NaN()};
  const auto [flexibility_i, flexibility_j] = end_flexibilities(element);
  return node_on_element(initial_[element], contact_section(spec, element), d, chord_rotations[element], position,
                         flexibility_i, flexibility_j);
}

NodeOnElement ContactTracker::on_chord(const Spec& spec, int element, const Eigen::VectorXd& D) const {
  const Element& e = model_.elements[element];
  const auto position = [&](int n) -> Eigen::Vector2d { return model_.nodes[n].position + D.segment<2>(dofs_per_node * n); };
  const ChordPlace place = place_on_chord(position(e.start), position(e.end), position(spec.node));
  return {place.alpha, place.across};
}

int ContactTracker::swept_crossing(const Spec& spec, const ContactState& state, const Eigen::VectorXd& D,
                                   const std::vector<char>& occupied) const {
  // In each element's own frame the node moved from (α0, g0) at the last converged state to
  // (α1, g1) now: where g reaches the contact's gap on the far side, α is interpolated between.
  // Only elements with a side (the side the node is to come from) and whose chord the node was
  // then on that side of; none the node now lies within (the ordinary test covers those). And
  // only where the node itself moved across the element as it lies now (its straight path
  // meets the current chord): an element that turned a long way in the step sweeps its frame
  // past nodes that never met it (a strip rolled onto a die in one step).
  if (state.reference_along.size() != spec.candidates.size()) return -1;
  const auto position = [&](int n) -> Eigen::Vector2d { return model_.nodes[n].position + D.segment<2>(dofs_per_node * n); };
  const Eigen::Vector2d p0(state.reference_position[0], state.reference_position[1]), p1 = position(spec.node);
  const Eigen::Vector2d path = p1 - p0;
  if (!(path.squaredNorm() > 0.0)) return -1;
  const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  const auto path_meets_chord = [&](int f) {
    const Eigen::Vector2d a = position(model_.elements[f].start), b = position(model_.elements[f].end);
    const double denominator = cross(path, b - a);
    if (denominator == 0.0) return false;
    const double s = cross(a - p0, b - a) / denominator, u = cross(a - p0, path) / denominator;
    return s >= 0.0 && s <= 1.0 && u >= 0.0 && u <= 1.0;
  };
  int first = -1;
  double first_t = INFINITY;
  for (size_t ci = 0; ci < spec.candidates.size(); ++ci) {
    const int f = spec.candidates[ci], side = state.reference_side[ci];
    if (occupied[f] || (side != 1 && side != -1)) continue;
    const double before = side * state.reference_across[ci];
    if (!(before > spec.gap)) continue;
    const Element& e = model_.elements[f];
    const Eigen::Vector2d a = position(e.start), b = position(e.end);
    if (const double alpha = alpha_on_chord(a, b, p1); alpha >= -alpha_tolerance && alpha <= 1.0 + alpha_tolerance)
      continue;  // on_chord's α, without its square root
    {  // Still on its side beyond the gap, surely (on_chord's distance, squared, with room for rounding).
      const Eigen::Vector2d chord = b - a, r = p1 - a;
      const double across = chord.x() * r.y() - chord.y() * r.x(), length2 = chord.squaredNorm();
      if (length2 > 0.0 && side * across > 0.0 && across * across > spec.gap * spec.gap * length2 * (1.0 + 1e-9)) continue;
    }
    const NodeOnElement now = on_chord(spec, f, D);
    const double after = side * now.gap;
    if (after > spec.gap) continue;
    const double t = (before - spec.gap) / (before - after);
    const double alpha = state.reference_along[ci] + t * (now.alpha - state.reference_along[ci]);
    if (alpha < 0.0 || alpha > 1.0 || t >= first_t || !path_meets_chord(f)) continue;
    first = f;
    first_t = t;
  }
  return first;
}

std::vector<ContactState> ContactTracker::initial_states() const {
  const Eigen::VectorXd D = Eigen::VectorXd::Zero(model_.dof_count());
  const std::vector<double> rotations(model_.elements.size(), 0.0);
  std::vector<ContactState> states(specs_.size());
  std::vector<char> occupied(model_.elements.size(), 0);
  for (size_t k = 0; k < specs_.size(); ++k) {
    states[k].reference_side.assign(specs_[k].candidates.size(), 0);
    reset_sides(specs_[k], D, rotations, 0, states[k]);
    // Resting on an element as drawn (model/resting_contact): in contact from the start, so a
    // structure held only by its contacts has a tangent to start from (one contact per element,
    // as always: a second one on the same element starts at the first update instead).
    if (const auto r = resting_contact(model_, model_.contacts[k]); r && !occupied[r->element]) {
      occupied[r->element] = 1;
      states[k].active = true;
      states[k].element = r->element;
      states[k].side = r->side;
      states[k].alpha = r->alpha;
    }
  }
  return states;
}

std::pair<int, int> ContactTracker::across(const Spec& spec, int element, int side, int node,
                                           const Eigen::VectorXd& D) const {
  // The side of element f left of its direction away from the node (n is e turned +90°).
  const auto left_side = [&](int f) { return model_.elements[f].start == node ? 1 : -1; };
  int count = 0, other = -1;
  for (int p = node_start_[node]; p < node_start_[node + 1]; ++p)
    if (spec.candidate_index[node_elements_[p]] >= 0) {
      ++count;
      if (node_elements_[p] != element) other = node_elements_[p];
    }
  if (count < 2 || other < 0) return {-1, 0};
  if (count == 2) return {other, side * left_side(element) * -left_side(other)};
  // Three or more: the elements around the node by the direction they leave it in; the side
  // faces the sector counter-clockwise from the element (its left) or clockwise (its right).
  const auto position = [&](int n) -> Eigen::Vector2d { return model_.nodes[n].position + D.segment<2>(dofs_per_node * n); };
  const Eigen::Vector2d x = position(node);
  std::vector<std::pair<double, int>> around;
  for (int p = node_start_[node]; p < node_start_[node + 1]; ++p) {
    const int g = node_elements_[p];
    if (spec.candidate_index[g] < 0) continue;
    const Element& e = model_.elements[g];
    const Eigen::Vector2d d = position(e.start == node ? e.end : e.start) - x;
    around.push_back({std::atan2(d.y(), d.x()), g});
  }
  std::sort(around.begin(), around.end());
  const int k = static_cast<int>(around.size());
  const int i = static_cast<int>(std::find_if(around.begin(), around.end(), [&](const auto& q) { return q.second == element; }) -
                                 around.begin());
  if (side == left_side(element)) {  // the far edge of the sector counter-clockwise: its right side
    const int to = around[(i + 1) % k].second;
    return {to, -left_side(to)};
  }
  const int to = around[(i + k - 1) % k].second;  // the far edge of the sector clockwise: its left side
  return {to, left_side(to)};
}

void ContactTracker::reset_sides(const Spec& spec, const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                 int fallback, ContactState& state) const {
  // fallback: the side on state.element's frame, used where the node lies on the centre line.
  Eigen::Vector2d released_normal = Eigen::Vector2d::Zero();
  if (fallback != 0 && state.element >= 0) {
    const Element& e = model_.elements[state.element];
    released_normal = chord_normal(initial_[state.element], element_displacements(e, D), rotations[state.element]);
  }
  // Per candidate: whether the node lies past the element's end node (+1) or before its start
  // node (−1) where its side was read: a side of the chord's line extended beyond a node is no
  // side of the beam on the far side of that node (at a kink or a joint), so it is not carried
  // through that node below.
  std::vector<signed char> past(spec.candidates.size(), 0);
  std::vector<NodeOnElement> where_all(spec.candidates.size());
  for (size_t ci = 0; ci < spec.candidates.size(); ++ci)
    where_all[ci] = locate(spec, spec.candidates[ci], D, rotations, -side_reach, 1.0 + side_reach);  // gap only there
  // Past an element's end node, its chord's line extended is no guide where the next element's
  // span holds the node: at a kink the line cuts across (just outside a convex arch, the next
  // chords' lines run outside it). There the side is carried from the element that holds it.
  const auto held_beyond = [&](size_t ci, int node) {
    for (int p = node_start_[node]; p < node_start_[node + 1]; ++p) {
      const int cj = spec.candidate_index[node_elements_[p]];
      if (cj < 0 || cj == static_cast<int>(ci)) continue;
      if (where_all[cj].alpha >= 0.0 && where_all[cj].alpha <= 1.0) return true;
    }
    return false;
  };
  for (size_t ci = 0; ci < spec.candidates.size(); ++ci) {
    const int f = spec.candidates[ci];
    const NodeOnElement& where = where_all[ci];
    past[ci] = where.alpha > 1.0 ? 1 : (where.alpha < 0.0 ? -1 : 0);
    if (past[ci] != 0 && held_beyond(ci, past[ci] > 0 ? model_.elements[f].end : model_.elements[f].start)) {
      state.reference_side[ci] = no_side;
    } else if (where.alpha < -side_reach || where.alpha > 1.0 + side_reach) {
      state.reference_side[ci] = no_side;
    } else if (std::abs(where.gap) > touch_tolerance_) {
      state.reference_side[ci] = static_cast<signed char>(sign(where.gap));
    } else if (fallback != 0 || state.reference_side[ci] == no_side) {
      const Eigen::Vector2d n = chord_normal(initial_[f], element_displacements(model_.elements[f], D), rotations[f]);
      state.reference_side[ci] = fallback == 0 ? 0 : static_cast<signed char>(n.dot(released_normal) >= 0.0 ? fallback : -fallback);
    }
  }
  // Beyond that reach: the side carried along the beam from the nearest element with one.
  carry_sides(spec, D, past, state.reference_side);
  const Eigen::Vector2d node = model_.nodes[spec.node].position + D.segment<2>(dofs_per_node * spec.node);
  state.reference_position[0] = node.x();
  state.reference_position[1] = node.y();
  state.reference_along.resize(spec.candidates.size());
  state.reference_across.resize(spec.candidates.size());
  for (size_t ci = 0; ci < spec.candidates.size(); ++ci) {
    const NodeOnElement there = on_chord(spec, spec.candidates[ci], D);
    state.reference_along[ci] = there.alpha;
    state.reference_across[ci] = there.gap;
  }
}


void ContactTracker::carry_sides(const Spec& spec, const Eigen::VectorXd& D, const std::vector<signed char>& past,
                                 std::vector<signed char>& side) const {
  // An element takes the side of the nearest element that has one, carried along the beam
  // from element to element through their nodes. Where two candidate elements
  // meet (a member's interior, a joint that only continues the beam into the next member) a
  // side of one is the same side of the other: kept where one element starts where the other
  // ends, flipped where they run against each other. Where three or more meet (a T or a cross),
  // a side faces one of the sectors between the elements around the node, and goes on to the
  // element on the other edge of that sector only (the top of a beam continues across a column
  // below it, into the next span's top). A node that slides over many short elements, or past a
  // joint, in one step still finds the side it came from where it arrives. Only a side (±1) is
  // carried: a node on the centre line has none yet.
  const size_t m = spec.candidates.size();
  std::vector<int> distance(m, std::numeric_limits<int>::max()), queue;
  std::vector<signed char> carried(m, no_side);
  for (size_t ci = 0; ci < m; ++ci)
    if (side[ci] == 1 || side[ci] == -1) distance[ci] = 0, carried[ci] = side[ci], queue.push_back(static_cast<int>(ci));
  for (size_t head = 0; head < queue.size(); ++head) {  // breadth first: from the nearest element with a side
    const int ci = queue[head], f = spec.candidates[ci];
    const Element& a = model_.elements[f];
    for (const int node : {a.start, a.end}) {
      if (distance[ci] == 0 && past[ci] == (node == a.end ? 1 : -1)) continue;  // read beyond this node
      const auto [to, to_side] = across(spec, f, carried[ci], node, D);
      if (to < 0) continue;
      const int cj = spec.candidate_index[to];
      if (distance[cj] <= distance[ci] + 1) continue;
      distance[cj] = distance[ci] + 1;
      carried[cj] = static_cast<signed char>(to_side);
      queue.push_back(cj);
    }
  }
  for (size_t ci = 0; ci < m; ++ci)
    if (side[ci] == no_side) side[ci] = carried[ci];
}

std::vector<ActiveContact> ContactTracker::active_contacts(const std::vector<ContactState>& states) const {
  std::vector<ActiveContact> active;
  const auto add = [&](const Spec& spec, int element, int side) {
    ActiveContact a;
    a.node = spec.node;
    a.element = element;
    a.data.initial = initial_[a.element];
    a.data.section = contact_section(spec, a.element);
    a.data.k0 = element::basic_stiffness(a.data.section, a.data.initial.length);
    a.data.contact_start = model_.nodes[spec.node].position;
    a.data.offset = side * spec.gap;
    a.data.edge = edge_of(spec);
    a.data.min_compliance = cap_compliance(spec, a.element);
    a.data.sliding_term = spec.sliding_term;
    a.data.cantilever_frame = spec.cantilever_frame;
    std::tie(a.data.flexibility_i, a.data.flexibility_j) = end_flexibilities(a.element);
    active.push_back(a);
  };
  for (size_t k = 0; k < specs_.size(); ++k) {
    if (!states[k].active) continue;
    add(specs_[k], states[k].element, states[k].side);
    if (states[k].partner >= 0) add(specs_[k], states[k].partner, states[k].partner_side);
  }
  return active;
}

int ContactTracker::vertex_node(const ContactState& state) const {
  const Element& a = model_.elements[state.element];
  const Element& b = model_.elements[state.partner];
  return a.end == b.start || a.end == b.end ? a.end : a.start;
}

size_t ContactTracker::read_evaluation(const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                       const ContactEvaluation* evaluated, ContactState& state) const {
  state.alpha = evaluated[0].alpha;
  state.Y = evaluated[0].Y;
  state.force = -state.side * state.Y;
  if (state.partner < 0) return 1;
  // A vertex: reported on the element that ends at the node, at α = 1 (or the one that starts
  // there, at 0), with the compression of the resultant of both contact elements' forces.
  state.partner_Y = evaluated[1].Y;
  state.alpha = model_.elements[state.element].end == vertex_node(state) ? 1.0 : 0.0;
  const auto normal = [&](int f) {
    return chord_normal(initial_[f], element_displacements(model_.elements[f], D), rotations[f]);
  };
  const Eigen::Vector2d push = state.Y * normal(state.element) + state.partner_Y * normal(state.partner);
  const double compression = -state.side * state.Y - state.partner_side * state.partner_Y;
  state.force = compression >= 0.0 ? push.norm() : -push.norm();
  return 2;
}

void ContactTracker::record(const Eigen::VectorXd& D, const std::vector<double>& rotations,
                            const std::vector<ContactEvaluation>& evaluated, std::vector<ContactState>& states) const {
  size_t next = 0;
  for (ContactState& state : states)
    if (state.active && next < evaluated.size()) next += read_evaluation(D, rotations, &evaluated[next], state);
}

void ContactTracker::release(const Spec& spec, const Eigen::VectorXd& D, const std::vector<double>& rotations,
                             ContactState& state, bool pulled) const {
  state.released_pulled = pulled;
  if (!pulled) state.slid_off_element = state.element;
  if (pulled) {
    // It let go on its own side of the beam, wherever the iterate has put things: that side,
    // carried along the beam from the element it left, is the side of every element it may not
    // reach the other side of (node_passed_through).
    std::fill(state.reference_side.begin(), state.reference_side.end(), no_side);
    state.reference_side[spec.candidate_index[state.element]] = static_cast<signed char>(state.side);
    carry_sides(spec, D, std::vector<signed char>(spec.candidates.size(), 0), state.reference_side);
  } else {
    reset_sides(spec, D, rotations, state.side, state);
  }
  const Eigen::Vector2d n = chord_normal(initial_[state.element], element_displacements(model_.elements[state.element], D),
                                         rotations[state.element]);
  state.released_side = state.side;
  state.released_normal[0] = n.x();
  state.released_normal[1] = n.y();
  // The elements whose span holds the node, and their neighbours in the set: near a joint the
  // node may sit just past one element's end yet is inside the beam's continuation.
  state.released_within.assign(spec.candidates.size(), 0);
  for (size_t ci = 0; ci < spec.candidates.size(); ++ci) {
    const int f = spec.candidates[ci];
    const double alpha = locate(spec, f, D, rotations, -alpha_tolerance, 1.0 + alpha_tolerance).alpha;
    if (alpha < -alpha_tolerance || alpha > 1.0 + alpha_tolerance) continue;
    for (const int node : {model_.elements[f].start, model_.elements[f].end})
      for (int p = node_start_[node]; p < node_start_[node + 1]; ++p)
        if (spec.candidate_index[node_elements_[p]] >= 0) state.released_within[spec.candidate_index[node_elements_[p]]] = 1;
  }
  state.active = false;
  state.released_in_step = true;
  state.element = state.partner = -1;
  state.side = 0;
  state.force = state.Y = 0.0;
}

int ContactTracker::release_as_pulling(const std::vector<int>& which, const Eigen::VectorXd& D,
                                       const std::vector<double>& rotations, std::vector<ContactState>& states) const {
  int released = 0;
  for (const int k : which) {
    if (!states[k].active || states[k].partner >= 0) continue;
    release(specs_[k], D, rotations, states[k], true);
    ++released;
  }
  return released;
}

void ContactTracker::hand_over(const Spec& spec, const Eigen::VectorXd& D, const std::vector<double>& rotations,
                               bool release_pulling, ContactState& state, std::vector<char>& occupied,
                               ContactChanges& changes) const {
  // The point has left its element: hand it on to the neighbour at that end, and on while it
  // is still beyond, but not farther than max(one element, 5 % of the model's size) per
  // iterate (coarse meshes: one element; fine meshes slide many elements per iterate).
  const double reach = 0.05 * model_.size;
  double travelled = 0.0;
  while (state.alpha < 0.0 || state.alpha > 1.0) {
    const Element& from = model_.elements[state.element];
    const int end = state.alpha > 1.0 ? from.end : from.start;
    // The beam goes on across that node: the next element on the side the node presses
    // (at a joint of three or more members, the one bounding the same sector: a point on a
    // beam's top passes a column below it and goes on along the beam).
    auto [best, to_side] = across(spec, state.element, state.side, end, D);
    if (best >= 0 && occupied[best]) best = -1;
    const double best_alpha = best >= 0 ? locate(spec, best, D, rotations).alpha : 0.0;
    if (best < 0) {  // no element beyond: the point has left the beam's free end …
      if (release_pulling) {  // … but only a converged iterate says so (till then α is held at the end)
        occupied[state.element] = 0;
        release(spec, D, rotations, state, false);
        ++changes.released;
      }
      break;
    }
    const int direction = state.alpha > 1.0 ? 1 : -1;
    const Element& to = model_.elements[best];
    const double beyond_from = state.alpha > 1.0 ? state.alpha - 1.0 : -state.alpha;
    // The vertex opened towards this element: it stays at the node (unless the point has
    // gone clearly on, more than the edge beyond it).
    const double edge = edge_of(spec);
    if (end == state.held_node && beyond_from <= edge) break;
    const bool reverses = state.handover_direction != 0 && direction != state.handover_direction;
    const double into_to = to.start == end ? best_alpha : 1.0 - best_alpha;  // from the node, < 0: behind it
    if (reverses && end == state.hop_node && end != state.held_node && edge >= vertex_min_edge &&
        beyond_from <= vertex_reach && std::abs(into_to) <= vertex_reach) {
      // Back across the node it has already come back across in this step: each element's
      // force (normal to its own chord; the chords meet at an angle) pushes the point over
      // the node onto the other, so it rests on the node. Both elements take it (a vertex).
      occupied[best] = 1;
      state.partner = best;
      state.partner_side = to_side;
      state.partner_Y = 0.0;
      if (from.end != end && to.end == end) {  // reported on the element that ends at the node
        std::swap(state.element, state.partner);
        std::swap(state.side, state.partner_side);
      }
      state.alpha = model_.elements[state.element].end == end ? 1.0 : 0.0;
      ++changes.handed_over;
      break;
    }
    occupied[state.element] = 0;
    occupied[best] = 1;
    state.side = to_side;
    if (reverses) {
      ++changes.reversed;
      state.hop_node = end;
    }
    // The next element's own direction: past its start (α < 0) when it continues from our end j.
    state.handover_direction = (to.start == end) == (direction > 0) ? direction : -direction;
    state.element = best;
    state.alpha = best_alpha;
    ++changes.handed_over;
    travelled += initial_[best].length;
    if (travelled >= reach) break;
  }
}

ContactChanges ContactTracker::update(const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                      const std::vector<ContactEvaluation>& evaluated,
                                      std::vector<ContactState>& states, bool release_pulling) const {
  ContactChanges changes;
  std::vector<char> occupied(model_.elements.size(), 0);
  for (const ContactState& s : states)
    if (s.active) {
      occupied[s.element] = 1;
      if (s.partner >= 0) occupied[s.partner] = 1;
    }
  // Every element's current chord frame once: detection takes α of each inactive node on every
  // candidate, and α alone rules out all but the few whose span holds it.
  std::vector<ChordFrame> frames;
  const auto frame_of = [&](int f) -> const ChordFrame& {
    if (frames.empty()) {
      frames.resize(model_.elements.size());
      for (const int e : candidate_elements_) frames[e] = chord_frame(initial_[e], element_displacements(model_.elements[e], D));
    }
    return frames[f];
  };
  size_t next = 0;
  for (size_t k = 0; k < specs_.size(); ++k) {
    const Spec& spec = specs_[k];
    ContactState& state = states[k];
    if (state.active && state.partner >= 0) {
      next += read_evaluation(D, rotations, &evaluated[next], state);
      // A vertex holds the node at the beam node until a converged iterate finds a side pulling:
      // that side lets go and the node goes on along the other element, or both and it leaves.
      if (!release_pulling) continue;
      const bool first_pulls = -state.side * state.Y < 0.0, partner_pulls = -state.partner_side * state.partner_Y < 0.0;
      if (!first_pulls && !partner_pulls) continue;
      const int node = vertex_node(state);
      if (first_pulls && partner_pulls) {
        occupied[state.element] = occupied[state.partner] = 0;
        release(spec, D, rotations, state, true);
      } else {
        if (first_pulls) {
          occupied[state.element] = 0;
          state.element = state.partner;
          state.side = state.partner_side;
          state.Y = state.partner_Y;
        } else {
          occupied[state.partner] = 0;
        }
        state.partner = -1;
        state.partner_Y = 0.0;
        state.held_node = node;
        state.alpha = locate(spec, state.element, D, rotations).alpha;
        state.force = -state.side * state.Y;
      }
      ++changes.released;
      continue;
    }
    if (state.active) {
      next += read_evaluation(D, rotations, &evaluated[next], state);
      if (release_pulling && state.force < 0.0) {  // compression only
        occupied[state.element] = 0;
        release(spec, D, rotations, state, true);
        ++changes.released;
        continue;
      }
      if (state.alpha >= 0.0 && state.alpha <= 1.0) continue;
      hand_over(spec, D, rotations, release_pulling, state, occupied, changes);
      continue;
    }
    // Detection: the node has reached or crossed an element's deflected centre line.
    state.blocked_element = -1;
    if (state.released_in_step) continue;
    int best = -1, best_side = 0;
    double best_gap = INFINITY, best_alpha = 0.0;
    const Eigen::Vector2d node = model_.nodes[spec.node].position + D.segment<2>(dofs_per_node * spec.node);
    for (size_t ci = 0; ci < spec.candidates.size(); ++ci) {
      const int f = spec.candidates[ci];
      if (const double alpha = frame_of(f).alpha(node); alpha < -alpha_tolerance || alpha > 1.0 + alpha_tolerance)
        continue;  // the same α as locate's
      const NodeOnElement where = locate(spec, f, D, rotations);
      const int reference = state.reference_side[ci];
      int side = 0;
      if (reference == no_side) {
        continue;
      } else if (reference != 0) {
        if (reference * where.gap <= spec.gap) side = reference;
      } else if (std::abs(where.gap) > touch_tolerance_) {
        side = -sign(where.gap);  // it left the centre line: it pushes the way it moves
      }
      if (side != 0 && occupied[f]) {  // another contact holds this element: one per element
        state.blocked_element = f;
        continue;
      }
      if (side != 0 && std::abs(where.gap) < best_gap) {
        best = f;
        best_side = side;
        best_gap = std::abs(where.gap);
        best_alpha = where.alpha;
      }
    }
    if (best < 0) {
      // Across an element's span and on beyond it within one iterate (a long step along a beam
      // the node was pressed onto): contact starts on that element, and is handed on along the
      // beam from there to where the node is — as far as the beam lets it (a column in the way).
      best = swept_crossing(spec, state, D, occupied);
      if (best >= 0) {
        best_side = state.reference_side[spec.candidate_index[best]];
        best_alpha = locate(spec, best, D, rotations).alpha;
      }
    }
    if (best >= 0) {
      state.blocked_element = -1;
      state.active = true;
      state.element = best;
      state.side = best_side;
      state.alpha = best_alpha;
      state.force = state.Y = 0.0;
      occupied[best] = 1;
      ++changes.activated;
      if (state.alpha < 0.0 || state.alpha > 1.0) hand_over(spec, D, rotations, false, state, occupied, changes);
    }
  }
  return changes;
}

bool ContactTracker::node_passed_through(size_t k, const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                         const ContactState& state) const {
  if (state.active || !state.released_in_step) return false;
  const Eigen::Vector2d released_normal(state.released_normal[0], state.released_normal[1]);
  for (size_t ci = 0; ci < specs_[k].candidates.size(); ++ci) {
    if (!state.released_within[ci]) continue;
    const int f = specs_[k].candidates[ci];
    const NodeOnElement where = locate(specs_[k], f, D, rotations, 0.0, 1.0);
    if (where.alpha < 0.0 || where.alpha > 1.0) continue;
    const Eigen::Vector2d n = chord_normal(initial_[f], element_displacements(model_.elements[f], D), rotations[f]);
    const int expected = n.dot(released_normal) >= 0.0 ? state.released_side : -state.released_side;
    if (expected * where.gap < -touch_tolerance_) return true;
  }
  if (!state.released_pulled) return false;  // off a free end: it may go round it
  // The element of the beam nearest the node across its span: a node through the beam lies just
  // beyond the element it went through. Elements farther across are no guide: the side carried
  // round a closed ring from the element it left is the wrong one on the ring's far side, whose
  // span the node above the ring also lies across (a rope draped over a ring was "through" it).
  int nearest = -1;
  double nearest_gap = 0.0;
  for (size_t ci = 0; ci < specs_[k].candidates.size(); ++ci) {
    const NodeOnElement where = locate(specs_[k], specs_[k].candidates[ci], D, rotations, 0.0, 1.0);
    if (where.alpha < 0.0 || where.alpha > 1.0) continue;
    if (nearest < 0 || std::abs(where.gap) < std::abs(nearest_gap)) nearest = static_cast<int>(ci), nearest_gap = where.gap;
  }
  if (nearest < 0) return false;
  const int expected = state.reference_side[nearest];
  return (expected == 1 || expected == -1) && expected * nearest_gap < -touch_tolerance_;
}

std::pair<int, int> ContactTracker::blocked(const std::vector<ContactState>& states) const {
  for (size_t k = 0; k < states.size(); ++k)
    if (!states[k].active && states[k].blocked_element >= 0) return {static_cast<int>(k), states[k].blocked_element};
  return {-1, -1};
}

bool ContactTracker::passed_through(const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                    const std::vector<ContactState>& states) const {
  for (size_t k = 0; k < specs_.size(); ++k)
    if (node_passed_through(k, D, rotations, states[k])) return true;
  return false;
}

int ContactTracker::allow_touching_again(const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                         std::vector<ContactState>& states) const {
  int count = 0;
  for (size_t k = 0; k < specs_.size(); ++k)
    if (node_passed_through(k, D, rotations, states[k])) {
      states[k].released_in_step = false;
      ++count;
    }
  return count;
}

void ContactTracker::accept(const Eigen::VectorXd& D, const std::vector<double>& rotations,
                            std::vector<ContactState>& states) const {
  for (size_t k = 0; k < specs_.size(); ++k) {
    states[k].released_in_step = false;
    states[k].handover_direction = 0;
    states[k].hop_node = states[k].held_node = -1;
    states[k].slid_off_element = -1;
    if (!states[k].active) reset_sides(specs_[k], D, rotations, 0, states[k]);
  }
}

}  // namespace tsm::contact
