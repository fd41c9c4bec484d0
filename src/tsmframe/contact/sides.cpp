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

void carry_sides(const ContactGeometry& geometry, const ContactCandidates& spec, const Eigen::VectorXd& D,
                 const std::vector<signed char>& past, std::vector<signed char>& side) {
  const Model& model_ = geometry.model();
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
  // Scratch kept per thread: a pass over thousands of contacts does not allocate and free three
  // candidate-sized arrays for each.
  thread_local std::vector<int> distance, queue;
  thread_local std::vector<signed char> carried;
  distance.assign(m, std::numeric_limits<int>::max());
  carried.assign(m, no_side);
  queue.clear();
  for (size_t ci = 0; ci < m; ++ci)
    if (side[ci] == 1 || side[ci] == -1) distance[ci] = 0, carried[ci] = side[ci], queue.push_back(static_cast<int>(ci));
  for (size_t head = 0; head < queue.size(); ++head) {  // breadth first: from the nearest element with a side
    const int ci = queue[head];
    for (int end = 0; end < 2; ++end) {
      const CandidateLink& link = spec.links[2 * ci + end];
      if (link.to == CandidateLink::free_end) continue;
      if (distance[ci] == 0 && past[ci] == (end == 1 ? 1 : -1)) continue;  // read beyond this node
      int cj = link.to, to_side = carried[ci] * link.sign;  // two candidates meet: the table's link
      if (link.to == CandidateLink::joint) {                // three or more: by the geometry
        const Element& a = model_.elements[spec.candidates[ci]];
        const auto [to, side_there] = across(geometry, spec, spec.candidates[ci], carried[ci], end == 0 ? a.start : a.end, D);
        if (to < 0) continue;
        cj = spec.candidate_index[to];
        to_side = side_there;
      }
      if (distance[cj] <= distance[ci] + 1) continue;
      distance[cj] = distance[ci] + 1;
      carried[cj] = static_cast<signed char>(to_side);
      queue.push_back(cj);
    }
  }
  for (size_t ci = 0; ci < m; ++ci)
    if (side[ci] == no_side) side[ci] = carried[ci];
}

void reset_sides(const ContactGeometry& geometry, const ContactCandidates& spec, const Eigen::VectorXd& D,
                 const std::vector<double>& rotations, int fallback, ContactState& state, ChordFrames* frames) {
  const Model& model_ = geometry.model();
  // fallback: the side on state.element's frame, used where the node lies on the centre line.
  Eigen::Vector2d released_normal = Eigen::Vector2d::Zero();
  if (fallback != 0 && state.element >= 0) released_normal = geometry.chord_normal(state.element, D, rotations);
  // Per candidate: whether the node lies past the element's end node (+1) or before its start
  // node (−1) where its side was read: a side of the chord's line extended beyond a node is no
  // side of the beam on the far side of that node (at a kink or a joint), so it is not carried
  // through that node below.
  std::vector<signed char> past(spec.candidates.size(), 0);
  std::vector<NodeOnElement> where_all(spec.candidates.size());
  const Eigen::Vector2d node = geometry.position(spec.node, D);
  for (size_t ci = 0; ci < spec.candidates.size(); ++ci) {
    const int f = spec.candidates[ci];
    if (frames) {  // locate's α from the shared frame: most candidates end here
      if (const double alpha = (*frames)(f).alpha(node); alpha < -side_reach || alpha > 1.0 + side_reach) {
        where_all[ci] = {alpha, std::numeric_limits<double>::quiet_NaN()};
        continue;
      }
    }
    where_all[ci] = geometry.locate(spec, f, D, rotations, -side_reach, 1.0 + side_reach);  // gap only there
  }
  // Past an element's end node, its chord's line extended is no guide where the next element's
  // span holds the node: at a kink the line cuts across (just outside a convex arch, the next
  // chords' lines run outside it). There the side is carried from the element that holds it.
  const auto held_beyond = [&](size_t ci, int node) {
    for (const int g : geometry.node_elements(node)) {
      const int cj = spec.candidate_index[g];
      if (cj < 0 || cj == static_cast<int>(ci)) continue;
      if (where_all[cj].alpha >= 0.0 && where_all[cj].alpha <= 1.0) return true;
    }
    return false;
  };
  // The sides as they were (a node on a centre line keeps its side; none yet: 0), in a scratch
  // array per thread; the table takes them at the end (and keeps its own where they are equal).
  thread_local std::vector<signed char> side;
  state.reference.side.read(side);
  if (side.size() != spec.candidates.size()) side.assign(spec.candidates.size(), 0);
  for (size_t ci = 0; ci < spec.candidates.size(); ++ci) {
    const int f = spec.candidates[ci];
    const NodeOnElement& where = where_all[ci];
    past[ci] = where.alpha > 1.0 ? 1 : (where.alpha < 0.0 ? -1 : 0);
    if (where.alpha < -side_reach || where.alpha > 1.0 + side_reach) {  // most candidates: far along
      side[ci] = no_side;
    } else if (past[ci] != 0 && held_beyond(ci, past[ci] > 0 ? model_.elements[f].end : model_.elements[f].start)) {
      side[ci] = no_side;
    } else if (std::abs(where.gap) > geometry.touch_tolerance()) {
      side[ci] = static_cast<signed char>(side_of_gap(where.gap));
    } else if (fallback != 0 || side[ci] == no_side) {
      const Eigen::Vector2d n = geometry.chord_normal(f, D, rotations);
      side[ci] = fallback == 0 ? 0 : static_cast<signed char>(n.dot(released_normal) >= 0.0 ? fallback : -fallback);
    }
  }
  // Beyond that reach: the side carried along the beam from the nearest element with one.
  carry_sides(geometry, spec, D, past, side);
  state.reference.side.set(side);
  state.reference.position[0] = node.x();
  state.reference.position[1] = node.y();
  std::vector<double>().swap(state.reference.along);  // freed: a release's place is kept by keep_place
  std::vector<double>().swap(state.reference.across);
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
