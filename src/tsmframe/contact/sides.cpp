#include "tsmframe/contact/sides.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsm::contact {
namespace {

// A side is recorded only while the node lies within this reach along the element (α from
// −reach to 1 + reach): a node far beyond an element's ends has no meaningful side of it, and
// its side flipping there (a beam swinging around) must not start a contact later.
constexpr double side_reach = 1.0;

}  // namespace

std::pair<int, int> across(const ContactGeometry& geometry, const ContactCandidates& spec, int element, int side,
                           int node, const Eigen::VectorXd& D) {
  const Model& model_ = geometry.model();
  // A free end, or two candidates meeting: the link the candidate table holds (contact_geometry).
  const CandidateLink& link = spec.links[2 * spec.candidate_index[element] + (model_.elements[element].start == node ? 0 : 1)];
  if (link.to == CandidateLink::free_end) return {-1, 0};
  if (link.to != CandidateLink::joint) return {spec.candidates[link.to], side * link.sign};
  // Three or more: the elements around the node by the direction they leave it in; the side
  // faces the sector counter-clockwise from the element (its left) or clockwise (its right).
  // The side of element f left of its direction away from the node (n is e turned +90°).
  const auto left_side = [&](int f) { return model_.elements[f].start == node ? 1 : -1; };
  const Eigen::Vector2d x = geometry.position(node, D);
  std::vector<std::pair<double, int>> around;
  for (const int g : geometry.node_elements(node)) {
    if (!spec.is_candidate(g)) continue;
    const Element& e = model_.elements[g];
    const Eigen::Vector2d d = geometry.position(e.start == node ? e.end : e.start, D) - x;
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

namespace {

/// Candidate ci's place in `members` (ascending), −1: not there; every candidate's own (null).
int member_index(const std::vector<int>* members, int ci) {
  if (!members) return ci;
  const auto at = std::lower_bound(members->begin(), members->end(), ci);
  return at != members->end() && *at == ci ? static_cast<int>(at - members->begin()) : -1;
}

/// carry_sides over `members` only (candidate indices, ascending; null: every candidate), with
/// `past` and `side` one per member.
void carry_among(const ContactGeometry& geometry, const ContactCandidates& spec, const Eigen::VectorXd& D,
                 const std::vector<int>* members, const std::vector<signed char>& past, std::vector<signed char>& side) {
  const Model& model_ = geometry.model();
  const size_t m = side.size();
  const auto candidate = [&](int j) { return members ? (*members)[j] : j; };
  // Scratch kept per thread: a pass over thousands of contacts does not allocate and free three
  // arrays for each.
  thread_local std::vector<int> distance, queue;
  thread_local std::vector<signed char> carried;
  distance.assign(m, std::numeric_limits<int>::max());
  carried.assign(m, no_side);
  queue.clear();
  for (size_t j = 0; j < m; ++j)
    if (side[j] == 1 || side[j] == -1) distance[j] = 0, carried[j] = side[j], queue.push_back(static_cast<int>(j));
  for (size_t head = 0; head < queue.size(); ++head) {  // breadth first: from the nearest element with a side
    const int j = queue[head], ci = candidate(j);
    for (int end = 0; end < 2; ++end) {
      const CandidateLink& link = spec.links[2 * ci + end];
      if (link.to == CandidateLink::free_end) continue;
      if (distance[j] == 0 && past[j] == (end == 1 ? 1 : -1)) continue;  // read beyond this node
      int cj = link.to, to_side = carried[j] * link.sign;  // two candidates meet: the table's link
      if (link.to == CandidateLink::joint) {               // three or more: by the geometry
        const Element& a = model_.elements[spec.candidates[ci]];
        const auto [to, side_there] = across(geometry, spec, spec.candidates[ci], carried[j], end == 0 ? a.start : a.end, D);
        if (to < 0) continue;
        cj = spec.candidate_index[to];
        to_side = side_there;
      }
      const int k = member_index(members, cj);
      if (k < 0 || distance[k] <= distance[j] + 1) continue;
      distance[k] = distance[j] + 1;
      carried[k] = static_cast<signed char>(to_side);
      queue.push_back(k);
    }
  }
  for (size_t j = 0; j < m; ++j)
    if (side[j] == no_side) side[j] = carried[j];
}

/// Reads the node's side of candidate elements at one state (D, rotations): the node's place on
/// each, and the side that place gives before sides are carried.
struct SideReader {
  const ContactGeometry& geometry;
  const ContactCandidates& spec;
  const Eigen::VectorXd& D;
  const std::vector<double>& rotations;
  ChordFrames* frames;  ///< the chord frames at D (null: α from locate)
  Eigen::Vector2d node;
  int fallback = 0;  ///< ±1: the side the node pressed from on a released element; 0: none
  Eigen::Vector2d released_normal = Eigen::Vector2d::Zero();

  /// α along candidate ci's chord, and the gap from its deflected centre line where α is within
  /// reach (beyond it: NaN).
  NodeOnElement place(int ci) const {
    const int f = spec.candidates[ci];
    if (frames) {  // locate's α from the shared frame: most candidates end here
      if (const double alpha = (*frames)(f).alpha(node); alpha < -side_reach || alpha > 1.0 + side_reach)
        return {alpha, std::numeric_limits<double>::quiet_NaN()};
    }
    return geometry.locate(spec, f, D, rotations, -side_reach, 1.0 + side_reach);  // gap only there
  }

  /// Past an element's end node, its chord's line extended is no guide where the next element's
  /// span holds the node: at a kink the line cuts across (just outside a convex arch, the next
  /// chords' lines run outside it). `alpha_of(cj)`: the node's α on candidate cj.
  template <class Alpha>
  bool held_beyond(int ci, int beam_node, Alpha&& alpha_of) const {
    for (const int g : geometry.node_elements(beam_node)) {
      const int cj = spec.candidate_index[g];
      if (cj < 0 || cj == ci) continue;
      if (const double alpha = alpha_of(cj); alpha >= 0.0 && alpha <= 1.0) return true;
    }
    return false;
  }

  /// The side candidate ci gives with the node at `where`; `held`: held_beyond the node it lies
  /// past; `before`: the side held until now (kept on a centre line; no_side: none).
  signed char side(int ci, const NodeOnElement& where, bool held, signed char before) const {
    if (where.alpha < -side_reach || where.alpha > 1.0 + side_reach) return no_side;  // most candidates: far along
    if (held) return no_side;
    if (std::abs(where.gap) > geometry.touch_tolerance()) return static_cast<signed char>(side_of_gap(where.gap));
    if (fallback == 0 && before != no_side) return before;  // on the centre line: the side it had
    if (fallback == 0) return 0;
    const Eigen::Vector2d n = geometry.chord_normal(spec.candidates[ci], D, rotations);
    return static_cast<signed char>(n.dot(released_normal) >= 0.0 ? fallback : -fallback);
  }

  /// Whether the node lies past element ci's end node (+1), before its start node (−1), or
  /// within (0) — a side read past a node is not carried through it.
  static signed char past(const NodeOnElement& where) { return where.alpha > 1.0 ? 1 : (where.alpha < 0.0 ? -1 : 0); }

  /// The beam node candidate ci's `past` lies beyond.
  int node_past(int ci, signed char past) const {
    const Element& e = geometry.model().elements[spec.candidates[ci]];
    return past > 0 ? e.end : e.start;
  }
};

/// The sides held until now, one per candidate (`near`: the near list they were taken with,
/// where they are the near ones'); a candidate without one: no_side.
void sides_before(const ContactReference& reference, const std::vector<int>& near, size_t m,
                  std::vector<signed char>& before) {
  before.assign(m, no_side);
  if (!reference.sides_of_near) {
    if (reference.side.size() == m) reference.side.read(before);
    return;
  }
  for (size_t j = 0; j < near.size() && j < reference.side.size(); ++j) before[near[j]] = reference.side[j];
}

/// Reads the node's side of the candidates `members` (ascending; null: every candidate) into
/// `side`, one per member, and carries them among the members. On entry `side` holds the sides
/// held until now (kept where the node lies on a centre line); the members in `keep` (ascending;
/// null: none) keep theirs as they are.
void read_and_carry(const SideReader& read, const std::vector<int>* members, const std::vector<int>* keep,
                    std::vector<signed char>& side) {
  const size_t m = side.size();
  const auto candidate = [&](size_t j) { return members ? (*members)[j] : static_cast<int>(j); };
  thread_local std::vector<NodeOnElement> where;
  thread_local std::vector<signed char> past;
  where.resize(m);
  past.resize(m);
  for (size_t j = 0; j < m; ++j) where[j] = read.place(candidate(j));
  const auto alpha_of = [&](int cj) {  // a neighbour beyond the members: its α read here
    const int k = member_index(members, cj);
    return k >= 0 ? where[k].alpha : read.place(cj).alpha;
  };
  for (size_t j = 0, kept = 0; j < m; ++j) {
    const int ci = candidate(j);
    past[j] = SideReader::past(where[j]);
    if (keep && kept < keep->size() && (*keep)[kept] == ci) {
      ++kept;
      continue;
    }
    side[j] = read.side(ci, where[j], past[j] != 0 && read.held_beyond(ci, read.node_past(ci, past[j]), alpha_of), side[j]);
  }
  // Beyond the reach of each: the side carried along the beam from the nearest element with one.
  carry_among(read.geometry, read.spec, read.D, members, past, side);
}

/// The node's position in the reference; a release's place (keep_place) freed.
void keep_position(const Eigen::Vector2d& node, ContactReference& reference) {
  reference.position[0] = node.x();
  reference.position[1] = node.y();
  std::vector<double>().swap(reference.along);
  std::vector<double>().swap(reference.across);
}

}  // namespace

void carry_sides(const ContactGeometry& geometry, const ContactCandidates& spec, const Eigen::VectorXd& D,
                 const std::vector<signed char>& past, std::vector<signed char>& side) {
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
  carry_among(geometry, spec, D, nullptr, past, side);
}

void reset_sides(const ContactGeometry& geometry, const ContactCandidates& spec, const Eigen::VectorXd& D,
                 const std::vector<double>& rotations, int fallback, ContactState& state, ChordFrames* frames) {
  SideReader read{geometry, spec, D, rotations, frames, geometry.position(spec.node, D), fallback};
  // fallback: the side on state.element's frame, used where the node lies on the centre line.
  if (fallback != 0 && state.element >= 0) read.released_normal = geometry.chord_normal(state.element, D, rotations);
  thread_local std::vector<signed char> side;
  sides_before(state.reference, state.reference.near, spec.candidates.size(), side);
  read_and_carry(read, nullptr, nullptr, side);
  state.reference.side.set(side);
  state.reference.sides_of_near = false;
  keep_position(read.node, state.reference);
}

void reset_near_sides(const ContactGeometry& geometry, const ContactCandidates& spec, const StepStart& start,
                      const CandidateChords& chords, ChordFrames& frames, ContactState& state) {
  ContactReference& reference = state.reference;
  const std::vector<int> near_before = std::move(reference.near);
  list_near_candidates(geometry, spec, start.displacements, start.stamp, chords, reference);
  const std::vector<int>& near = reference.near;
  // The sides held until now, of the candidates near now (a node on a centre line keeps its side).
  thread_local std::vector<signed char> side;
  side.assign(near.size(), no_side);
  if (reference.sides_of_near) {
    for (size_t j = 0, i = 0; j < near.size(); ++j) {  // both lists ascending
      while (i < near_before.size() && near_before[i] < near[j]) ++i;
      if (i < near_before.size() && near_before[i] == near[j] && i < reference.side.size()) side[j] = reference.side[i];
    }
  } else if (reference.side.size() == spec.candidates.size()) {
    for (size_t j = 0; j < near.size(); ++j) side[j] = reference.side[near[j]];
  }
  const SideReader read{geometry, spec, start.displacements, start.rotations, &frames,
                        geometry.position(spec.node, start.displacements)};
  read_and_carry(read, &near, nullptr, side);
  reference.side.set(side);
  reference.sides_of_near = true;
  keep_position(read.node, reference);
}

void take_every_side(const ContactGeometry& geometry, const ContactCandidates& spec, const StepStart& start,
                     ChordFrames& frames, ContactReference& reference) {
  if (!reference.sides_of_near || reference.stamp != start.stamp) return;
  const SideReader read{geometry, spec, start.displacements, start.rotations, &frames,
                        geometry.position(spec.node, start.displacements)};
  thread_local std::vector<signed char> side;
  sides_before(reference, reference.near, spec.candidates.size(), side);  // the near ones' as they are, no_side elsewhere
  read_and_carry(read, nullptr, &reference.near, side);
  reference.side.set(side);
  reference.sides_of_near = false;
}

void keep_place(const ContactGeometry& geometry, const ContactCandidates& spec, const Eigen::VectorXd& D,
                ContactReference& reference) {
  reference.along.resize(spec.candidates.size());
  reference.across.resize(spec.candidates.size());
  for (size_t ci = 0; ci < spec.candidates.size(); ++ci) {
    const NodeOnElement there = geometry.on_chord(spec, spec.candidates[ci], D);
    reference.along[ci] = there.alpha;
    reference.across[ci] = there.gap;
  }
}

}  // namespace tsm::contact
