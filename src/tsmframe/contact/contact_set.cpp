#include "tsmframe/contact/contact_set.hpp"

#include <algorithm>
#include <cmath>

#include "tsmframe/contact/broad_phase.hpp"
#include "tsmframe/contact/chord_frames.hpp"
#include "tsmframe/contact/detection.hpp"
#include "tsmframe/contact/landing.hpp"
#include "tsmframe/contact/release.hpp"
#include "tsmframe/contact/sides.hpp"
#include "tsmframe/contact/sliding.hpp"
#include "tsmframe/contact/vertex.hpp"
#include "tsmframe/model/resting_contact.hpp"
#include "tsmframe/util/parallel_for.hpp"

namespace tsm::contact {
namespace {

void add(const HandOver& h, ContactChanges& changes) {
  changes.handed_over += h.handed_over;
  changes.reversed += h.reversed;
  changes.released += h.released ? 1 : 0;
}

}  // namespace

std::vector<ContactState> ContactSet::initial_states() const {
  const Model& model = geometry_.model();
  const StepStart start = unloaded_start(model);
  const Eigen::VectorXd& D = start.displacements;
  std::vector<ContactState> states(contact_count());
  Occupancy occupancy(model.elements.size(), model.node_count());
  ChordFrames frames(geometry_, D);
  const CandidateChords chords(geometry_, D);
  const auto resting = resting_contacts(model);
  for (int k = 0; k < contact_count(); ++k) {
    const ContactCandidates& contact = geometry_.contact(k);
    reset_near_sides(geometry_, contact, start, chords, frames, states[k]);  // no sides before: 0 on a centre line
    // Resting on an element as drawn (model/resting_contact): in contact from the start, so a
    // structure held only by its contacts has a tangent to start from (where the element may take
    // no other point, occupancy.hpp, a second one starts at the first update instead).
    if (const auto& r = resting[k];
        r && occupancy.may_join(r->element, contact.frame) && !pair_in_contact(geometry_, contact, r->element, D, occupancy)) {
      occupancy.join(r->element, contact.frame);
      occupancy.set_touching(contact.node, r->element);
      states[k].active = true;
      states[k].element = r->element;
      states[k].side = r->side;
      states[k].alpha = r->alpha;
    }
  }
  return states;
}

bool ContactSet::bends_normals() const {
  for (int k = 0; k < contact_count(); ++k) {
    const ContactCandidates& c = geometry_.contact(k);
    if (c.frame == ContactFrame::chord && c.normal == ContactNormal::deflected) return true;
  }
  return false;
}

std::vector<ActiveContact> ContactSet::active_contacts(const std::vector<ContactState>& states, bool along_chords) const {
  std::vector<ActiveContact> active;
  active_contacts(states, along_chords, active);
  return active;
}

void ContactSet::active_contacts(const std::vector<ContactState>& states, bool along_chords,
                                 std::vector<ActiveContact>& active) const {
  size_t used = 0;  // active's first `used` are this call's; those beyond keep their storage till then
  std::vector<int> place;  // per element: its place in `active`, −1 none (made only when needed)
  // The points are grouped by element first; what each point's element is made of is formed
  // after, in parallel (a contact element's data costs more than its place).
  struct Pending {
    int slot, point, contact, element, side;
    bool chord;  ///< the point pushes along its chord's normal whatever its contact asks (a vertex's)
    bool second;  ///< a vertex's second element
  };
  std::vector<Pending> pending;
  const auto add_point = [&](int k, bool vertex, int element, int side, bool chord) {
    if (place.empty()) place.assign(geometry_.model().elements.size(), -1);
    if (place[element] < 0) {
      place[element] = static_cast<int>(used);
      if (used == active.size()) active.emplace_back();
      ActiveContact& a = active[used++];
      a.element = element;
      a.points.clear();
    }
    ActiveContact& a = active[place[element]];
    pending.push_back({place[element], a.size(), k, element, side, chord, vertex});
    a.points.push_back({k, vertex, geometry_.contact(k).node});
  };
  for (int k = 0; k < contact_count(); ++k) {
    const ContactState& s = states[k];
    if (!s.active) continue;
    // A vertex pushes along both chords' normals: its force may lie anywhere between them, and
    // its rules (vertex.hpp) are written for those; the bent beams' normals there differ from
    // them by the end rotations against the chords, which vanish as the mesh is refined.
    const bool vertex = s.vertex.has_value();
    add_point(k, false, s.element, s.side, vertex);
    if (vertex) add_point(k, true, s.vertex->element, s.vertex->side, true);
  }
  active.resize(used);
  for (ActiveContact& a : active) a.data.resize(a.points.size());
  util::parallel_for_static(size_t{0}, pending.size(), pending.size() >= 1024, [&](size_t q) {
    const Pending& p = pending[q];
    ContactElementData& data = active[p.slot].data[p.point];
    data = geometry_.element_data(geometry_.contact(p.contact), p.element, p.side);
    if (p.chord) data.normal = ContactNormal::chord;
    if (data.friction.mu > 0.0) anchor(states[p.contact], p.element, p.second, data.friction);
  });
  // An element a point enters pushes along its chord's normal at all its points: the entering
  // point's Y, read from how far the predictor ran its node through the beam, would turn the
  // others' normals too.
  // So does an element of several points one of which has friction: the k-point element's
  // friction is written along the chords' normals (friction.hpp).
  const auto frictional = [](const ActiveContact& a) {
    return a.size() > 1 && std::any_of(a.data.begin(), a.data.end(), [](const ContactElementData& d) { return d.friction.mu > 0.0; });
  };
  for (ActiveContact& a : active)
    if (along_chords || frictional(a) ||
        std::any_of(a.points.begin(), a.points.end(), [&](const ActivePoint& p) { return states[p.contact].entering; }))
      for (ContactElementData& d : a.data) d.normal = ContactNormal::chord;
}

void ContactSet::anchor(const ContactState& state, int element, bool second, FrictionData& friction) const {
  // At a vertex friction acts on the contact's own element, along its chord, and not on the
  // second (the arc length runs on through the beam node). An anchor on another member is not
  // carried across the joint yet (F10): the point anchors again where it is.
  if (second) {
    friction.mu = 0.0;
    return;
  }
  friction.anchored = state.friction.anchored && state.friction.member == geometry_.model().elements[element].member;
  friction.anchor = state.friction.anchor;
}

void ContactSet::record(const std::vector<ContactEvaluation>& evaluated, std::vector<ContactState>& states) const {
  for (const ContactEvaluation& e : evaluated) {
    if (e.vertex) continue;
    ContactState& state = states[e.contact];
    state.alpha = e.alpha;
    state.Y = e.Y;
    state.force = -state.side * state.Y * e.force_per_Y;
    state.push[0] = e.push.x();
    state.push[1] = e.push.y();
    if (geometry_.contact(e.contact).friction > 0.0) record_friction(e, state);
  }
  for (const ContactEvaluation& e : evaluated)  // a vertex's second element, with its first read
    if (e.vertex) read_vertex(geometry_.model(), e.Y, e.push, states[e.contact]);
}

ContactChanges ContactSet::update(const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                  const std::vector<ContactEvaluation>& evaluated, std::vector<ContactState>& states,
                                  bool at_convergence, const StepStart& step_start) const {
  record(evaluated, states);
  ContactChanges changes;
  Occupancy occupancy(geometry_, states);
  ChordFrames frames(geometry_, D);
  std::optional<ChordFrames> start_frames;  // at the step's start, made for the first reference read in full
  const BroadPhase broad_phase(geometry_, D, &step_start);
  // At a converged iterate a node is detected against the shape the points on an element give it.
  const std::optional<ElementLoads> loads = at_convergence ? std::optional<ElementLoads>(states) : std::nullopt;
  for (int k = 0; k < contact_count(); ++k) {
    const ContactCandidates& contact = geometry_.contact(k);
    ContactState& state = states[k];
    const int before = state.active ? state.element : -1;
    if (state.active) {
      update_active(contact, D, rotations, at_convergence, state, occupancy, changes);
    } else {
      const std::vector<int>* near = broad_phase.candidates(contact, state.reference);
      if (!near && state.reference.sides_of_near && step_start.displacements.size() == D.size()) {
        // every candidate: every side, read at the step's start
        if (!start_frames) start_frames.emplace(geometry_, step_start.displacements);
        take_every_side(geometry_, contact, step_start, *start_frames, state.reference);
      }
      if (const std::optional<HandOver> touched =
              detect(geometry_, contact, D, rotations, frames, state, occupancy, loads ? &*loads : nullptr, near, &step_start)) {
        ++changes.activated;
        add(*touched, changes);
      }
    }
    state.entering = state.active && state.element != before;
    occupancy.set_touching(contact.node, state.active ? state.element : -1);
  }
  return changes;
}

void ContactSet::update_active(const ContactCandidates& contact, const Eigen::VectorXd& D,
                               const std::vector<double>& rotations, bool at_convergence, ContactState& state,
                               Occupancy& occupancy, ContactChanges& changes) const {
  if (state.vertex) {
    // A vertex holds the node at the beam node until a converged iterate finds a side pulling.
    if (at_convergence && open_vertex(geometry_, contact, D, rotations, state, occupancy)) ++changes.released;
    return;
  }
  if (at_convergence && state.force < 0.0) {  // compression only
    occupancy.leave(state.element);
    release(geometry_, contact, D, rotations, state, true);
    ++changes.released;
    return;
  }
  if (state.alpha >= 0.0 && state.alpha <= 1.0) return;
  add(hand_over(geometry_, contact, D, rotations, at_convergence, state, occupancy), changes);
}

std::vector<LandingMove> ContactSet::landing_moves(const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                                   const std::vector<ContactState>& states,
                                                   const std::vector<char>& touching_before) const {
  std::vector<LandingMove> moves;
  std::vector<char> moved(geometry_.model().nodes.size(), 0);
  for (int k = 0; k < contact_count(); ++k) {
    if (touching_before[k] || !states[k].active) continue;
    const ContactCandidates& contact = geometry_.contact(k);
    if (moved[contact.node]) continue;
    const LandingMove move = landing_move(geometry_, contact, states[k], D, rotations);
    if (move.node < 0) continue;
    moved[contact.node] = 1;
    moves.push_back(move);
  }
  return moves;
}

double ContactSet::landing_fraction(const Eigen::VectorXd& D, const Eigen::VectorXd& trial,
                                    const std::vector<ContactState>& states) const {
  double fraction = 1.0;
  for (int k = 0; k < contact_count(); ++k)
    fraction = std::min(fraction, contact::landing_fraction(geometry_, geometry_.contact(k), states[k], D, trial));
  return fraction;
}

bool ContactSet::passed_through(const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                const std::vector<ContactState>& states) const {
  const ElementLoads loads(states);
  for (int k = 0; k < contact_count(); ++k)
    if (contact::passed_through(geometry_, geometry_.contact(k), D, rotations, states[k], loads)) return true;
  return false;
}

std::pair<int, int> ContactSet::blocked(const std::vector<ContactState>& states) const {
  for (size_t k = 0; k < states.size(); ++k)
    if (!states[k].active && states[k].step.blocked_element >= 0) return {static_cast<int>(k), states[k].step.blocked_element};
  return {-1, -1};
}

int ContactSet::allow_touching_again(const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                     std::vector<ContactState>& states) const {
  int count = 0;
  const ElementLoads loads(states);
  for (int k = 0; k < contact_count(); ++k)
    if (contact::passed_through(geometry_, geometry_.contact(k), D, rotations, states[k], loads)) {
      states[k].step.released = false;
      ++count;
    }
  return count;
}

int ContactSet::release_as_pulling(const std::vector<int>& which, const Eigen::VectorXd& D,
                                   const std::vector<double>& rotations, std::vector<ContactState>& states) const {
  int released = 0;
  for (const int k : which) {
    if (!states[k].active || states[k].vertex) continue;
    release(geometry_, geometry_.contact(k), D, rotations, states[k], true);
    ++released;
  }
  return released;
}

void ContactSet::restore(const StepStart& start, std::vector<ContactState>& states) const {
  const Eigen::VectorXd& D = start.displacements;
  ChordFrames frames(geometry_, D);
  const CandidateChords chords(geometry_, D);
  for (int k = 0; k < contact_count(); ++k) {
    const ContactCandidates& contact = geometry_.contact(k);
    // A release's reference (every side) stands; a step's start's is taken again here, with the
    // candidates the contact has now (a stage may have turned it off and on since).
    const ContactReference& reference = states[k].reference;
    if (!reference.sides_of_near && reference.side.size() == contact.candidates.size() && !contact.candidates.empty()) continue;
    reset_near_sides(geometry_, contact, start, chords, frames, states[k]);
  }
}

void ContactSet::record_friction(const ContactEvaluation& e, ContactState& state) const {
  FrictionState& f = state.friction;
  const FrictionResult& r = e.friction;
  f.status = r.status;
  f.tangential = r.tangential;
  f.trial_anchor = r.trial_anchor;
  if (!f.anchored && f.status == FrictionStatus::stick) {  // the touching iterate: anchored here for the rest of the step
    f.anchored = true;
    f.anchor = r.arc;
    f.member = geometry_.model().elements[state.element].member;
  }
  if (f.status == FrictionStatus::stick || f.status == FrictionStatus::slip)
    state.force = -state.side * r.normal_Y * e.force_per_Y;  // the normal force, friction's share taken out (F2)
}

void ContactSet::accept(const StepStart& start, std::vector<ContactState>& states) const {
  const Eigen::VectorXd& D = start.displacements;
  ChordFrames frames(geometry_, D);
  const CandidateChords chords(geometry_, D);
  for (int k = 0; k < contact_count(); ++k) {
    states[k].step = StepMemory{};
    if (FrictionState& f = states[k].friction;
        states[k].active && (f.status == FrictionStatus::stick || f.status == FrictionStatus::slip)) {
      f.slip += std::abs(f.trial_anchor - f.anchor);  // the step's slip: the anchor moves where the map left it
      f.anchor = f.trial_anchor;
    }
    states[k].friction.step_status = states[k].friction.status;
    states[k].friction.step_tangential = states[k].friction.tangential;
    if (states[k].active) continue;
    // Apart at a converged state: a node that touches again starts afresh. (Within a step an
    // iterate that lets go and touches again keeps the step's anchor.)
    states[k].friction = FrictionState{};
    reset_near_sides(geometry_, geometry_.contact(k), start, chords, frames, states[k]);
  }
}

}  // namespace tsm::contact
