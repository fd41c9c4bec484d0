#include "tsmframe/solver/tsm_problem.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <numbers>
#include <utility>

#include "tsmframe/model/mechanism.hpp"
#include "tsmframe/model/resting_contact.hpp"
#include "tsmframe/solver/convergence.hpp"
#include "tsmframe/solver/free_mode.hpp"
#include "tsmframe/contact/release_forecast.hpp"
#include "tsmframe/util/first_touch.hpp"

namespace tsm::solver {
namespace {

constexpr double largest_end_rotation = std::numbers::pi / 2;  // |θ| an element end may turn against its chord
constexpr int max_passes = 4;  // contact changes settled per iterate before Newton goes on

}  // namespace

TsmProblem::TsmProblem(assembly::GlobalSystem& system, const contact::ContactSet* contacts)
    : system_(system), contacts_(contacts && contacts->contact_count() > 0 ? contacts : nullptr) {
  bends_normals_ = contacts_ && contacts_->bends_normals();
  const assembly::DofMap& dofs = system.dofs();
  const Model& model = system.model();
  equations_.free_dofs = dofs.free_dofs();
  equations_.is_moment.resize(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq) equations_.is_moment[eq] = dofs.dof(eq) % dofs_per_node == rz ? 1 : 0;
  for (int dof = 0; dof < model.dof_count(); ++dof) {
    if (model.constrained[dof]) equations_.constrained_dofs.push_back(dof);
    if (dof % dofs_per_node != rz) equations_.prescribed_squared += model.prescribed(dof) * model.prescribed(dof);
  }
  equations_.size = model.size;
  equations_.prescribed_size = model.reference_prescribed.lpNorm<Eigen::Infinity>();
  double shortest = model.elements.empty() ? 0.0 : std::numeric_limits<double>::infinity();
  for (const Element& e : model.elements)
    shortest = std::min(shortest, model.drawn_length(e));
  equations_.resolvable_move = resolvable_move(shortest);
  // Hinges can leave a mechanism inside a part (pinned bars in a row) that the supports' check,
  // which looks at parts as rigid bodies, does not see.
  hinged_ = std::any_of(model.elements.begin(), model.elements.end(),
                        [](const Element& e) { return e.release_start || e.release_end; });
  if (contacts_ && !is_mechanism(model) && is_mechanism(model, false)) {
    const auto resting = resting_contacts(model);
    for (int k = 0; k < static_cast<int>(model.contacts.size()); ++k)
      if (resting[k]) holding_contacts_.push_back(k);
  }
  solver_.analyze(system.dofs(), system.tangent());
  analysed_pattern_ = system.pattern_version();
}

bool TsmProblem::evaluate(State& state, Proximity proximity, bool contacts_only) {
  const Model& model = system_.model();
  system_.set_load_factor(state.load_factor);
  for (int dof : equations_.constrained_dofs) state.displacements[dof] = model.prescribed_at(dof, state.load_factor);
  const Eigen::VectorXd& u = physical(state);
  // The predictor runs contact nodes through their beams by as much as the step extrapolates:
  // Y at its iterate measures that, not the contact force, and along the bent beam's normal it
  // would turn the normals as much. That iterate pushes along the chords' normals, as a point
  // entering an element does (ContactState::entering).
  if (std::exchange(predictor_pending_, false))
    for (contact::ContactState& c : state.contacts) c.entering = c.entering || c.active;
  // So does an iterate the landing cut short (step_fraction), through every pass that settles
  // its contacts: those that started on the way there are still as deep as the cut left them,
  // their Y not yet the beam's. Until the next evaluation (the tangent refilled for the LU is
  // this one's); no contact's state is marked, so nothing of it outlives the iterate.
  // And so does an iterate far from the solution with many points in touch (far_along_chords).
  // An iterate whose normals turned back from the chords' to the bent beams' is judged as one
  // whose contacts changed: the correction that reached it was the other model's (no round-off).
  const bool was_along_chords = along_chords_;
  const bool landed = landing_cut_;
  along_chords_ = std::exchange(landing_cut_, false) || far_along_chords(state, proximity);
  bool changed = bends_normals_ && was_along_chords && !along_chords_;
  bool moved = false;  // contact nodes put on the surface they landed on: every element again
  for (int pass = 0;; ++pass) {
    std::vector<contact::ActiveContact>& active = active_;
    if (contacts_) contacts_->active_contacts(state.contacts, along_chords_, active);
    // The rotations are continued in place (one vector, not two): lent to the evaluation.
    std::swap(state.chord_rotations, eval_.chord_rotations);
    if (pass == 0 ? contacts_only : !moved) system_.evaluate_contact_change(u, eval_.chord_rotations, eval_, active);
    else system_.evaluate(u, eval_.chord_rotations, true, eval_, active);
    std::swap(state.chord_rotations, eval_.chord_rotations);
    if (!contacts_) return false;
    if (pass == max_passes) break;
    if (landed && pass == 0) {
      touching_before_.resize(state.contacts.size());
      for (size_t k = 0; k < state.contacts.size(); ++k) touching_before_[k] = state.contacts[k].active;
    }
    const contact::ContactChanges changes =
        contacts_->update(u, state.chord_rotations, eval_.contacts, state.contacts, false, state.contact_references);
    moved = landed && pass == 0 && changes.activated > 0 && put_on_surface(state);
    if (!changes.any()) break;
    changed = true;
    switches_ += changes.activated + changes.released;
    reversals_ += changes.reversed;
  }
  // α and force of the evaluation that stands (update() has set them unless the passes ran out).
  contacts_->record(eval_.contacts, state.contacts);
  return changed;
}

bool TsmProblem::put_on_surface(State& state) {
  const std::vector<contact::LandingMove> moves =
      contacts_->landing_moves(physical(state), state.chord_rotations, state.contacts, touching_before_);
  const NodalFrames& frames = system_.frames();
  const std::vector<int>& held = equations_.constrained_dofs;
  for (const contact::LandingMove& move : moves) {
    const std::array<int, dofs_per_node> dofs{dofs_per_node * move.node, dofs_per_node * move.node + 1,
                                              dofs_per_node * move.node + 2};
    Eigen::Vector3d by(move.by.x(), move.by.y(), 0.0);
    if (frames.turned(move.node)) frames.to_nodal(dofs, by);  // a skew roller's node: in its frame
    for (int d = 0; d < 2; ++d)
      if (!std::binary_search(held.begin(), held.end(), dofs[d])) state.displacements[dofs[d]] += by[d];
  }
  if (!moves.empty()) physical(state);  // where frames turn, u (physical_) follows
  return !moves.empty();
}

bool TsmProblem::far_along_chords(const State& state, Proximity proximity) {
  if (proximity != Proximity::far || !bends_normals_) return false;
  if (far_along_chords_) return true;  // the step's far iterates stay so: no switching about the count
  // Far off, the points' Y measure how deep the iterates ran them into their beams, up to the
  // stiffness cap (~10¹⁰ N on a press whose beams carry 10² N per point), not the beams' forces;
  // along the bent beams' normals, which tilt with α, each then pushes sideways by Y·w', and
  // no tangent term sees it (the sliding terms are left out there). With thousands of points
  // on one beam, soft lengthwise, those pushes added up and ran the points back and forth over
  // beam nodes until the step failed (the 500-m press: 6 of its 22 steps cut back). A few
  // points converge sooner along the bent normals throughout: turning back to them once near
  // costs an iterate (the examples, at most ~100 points in touch: 9 % more iterations; the
  // arc-length cantilever 45 → 69 steps). bench/README "Far off, along the chords".
  constexpr std::ptrdiff_t many_points = 200;
  far_along_chords_ = std::count_if(state.contacts.begin(), state.contacts.end(),
                                    [](const contact::ContactState& c) { return c.active; }) >= many_points;
  return far_along_chords_;
}

std::vector<contact::ActiveContact> TsmProblem::active_contacts(const State& state) const {
  return contacts_ ? contacts_->active_contacts(state.contacts, along_chords_) : std::vector<contact::ActiveContact>();
}

assembly::RoundingFloor TsmProblem::rounding_floor(const State& state, bool with_contacts) const {
  return system_.rounding_floor(physical(state), state.chord_rotations,
                                with_contacts ? active_contacts(state) : std::vector<contact::ActiveContact>());
}

void TsmProblem::analyse_pattern() {
  if (system_.pattern_version() == analysed_pattern_) return;  // a contact has joined new nodes
  solver_.analyze(system_.dofs(), system_.tangent());
  analysed_pattern_ = system_.pattern_version();
}

Factorisation TsmProblem::factorize(const State& state, bool with_optional_terms, Eigen::VectorXd* rhs, bool stability) {
  solver_.guard_inertia(stability);
  analyse_pattern();
  // The SparseLU fallback (contacts only) needs the tangent the in-place LDLᵀ overwrote: it is
  // evaluated again at the same state, which stays as it is (a scratch evaluation).
  const auto refill = [&](BlockMatrix&) {
    const std::vector<contact::ActiveContact> active = active_contacts(state);
    assembly::Evaluation scratch;
    system_.evaluate(physical(state), state.chord_rotations, true, scratch, active);
  };
  // K_ff = tangent + the sliding terms in use (all, or none); with `rhs`, solved for it in place.
  // A follower load's skew terms and friction's always join.
  const std::vector<RankOne>& follower_terms = system_.follower_rank_one();
  const std::vector<RankOne>& friction_terms = system_.friction_rank_one();
  std::vector<RankOne> always;  // only in a model with both
  if (!follower_terms.empty() && !friction_terms.empty()) {
    always = follower_terms;
    always.insert(always.end(), friction_terms.begin(), friction_terms.end());
  }
  const std::vector<RankOne>& skew = friction_terms.empty() ? follower_terms : follower_terms.empty() ? friction_terms : always;
  const std::vector<RankOne>& contact = system_.contact_rank_one();
  const bool skewed = !skew.empty();
  std::vector<RankOne> both;  // only in a model with both
  if (skewed && !contact.empty()) {
    both = skew;
    both.insert(both.end(), contact.begin(), contact.end());
  }
  const std::vector<RankOne>& sliding = !skewed ? contact : contact.empty() ? skew : both;
  BlockMatrix& K = system_.tangent_for_factorisation();
  const auto attempt = [&](const std::vector<RankOne>& terms, Eigen::VectorXd* x) {
    const bool ok = x ? solver_.factorize_and_solve(K, terms, *x, refill) : solver_.factorize(K, terms, refill);
    // With a follower load's skew terms or friction's the tangent is not symmetric: its symmetric
    // part's inertia tells nothing of stability (a non-conservative load, a path-dependent one).
    return factorisation(ok, !skewed);
  };
  if (contact.empty()) return attempt(sliding, rhs);
  if (with_optional_terms && stability && contact.size() > LinearSolver::most_rank_one) {
    // A step's start, where the symmetric part's inertia is read (the limit-point diagnosis,
    // load_stepping), and the block LU of the whole does not give it: the symmetric part is
    // factorised first for it — one factorisation and one evaluation more a step.
    const Factorisation symmetric = attempt(skew, nullptr);
    refill(K);
    analyse_pattern();
    Factorisation whole = attempt(sliding, rhs);
    if (whole.ok) whole.negative_pivots = symmetric.negative_pivots, whole.rounded = symmetric.rounded;
    return whole;
  }
  if (with_optional_terms) return attempt(sliding, rhs);
  // Without the sliding terms the symmetric part alone may be singular where the whole is not:
  // then once more with them.
  if (rhs) kept_rhs_ = *rhs;  // the solve runs along the factorisation
  if (const Factorisation f = attempt(skew, rhs); f.ok) return f;
  refill(K);  // the failed factorisation has overwritten part of it
  analyse_pattern();  // the evaluation may have joined or forgotten contact pairs
  if (rhs) *rhs = kept_rhs_;
  return attempt(sliding, rhs);
}

double TsmProblem::step_fraction(const State& state, const Eigen::VectorXd& correction) {
  if (!contacts_) return 1.0;
  // The whole correction over all dofs, global, then the iterate it reaches (one buffer, kept).
  const Eigen::VectorXd& u = physical(state);
  trial_.setZero(u.size());
  for (int eq = 0; eq < equations_.free_count(); ++eq) trial_[equations_.free_dofs[eq]] = correction[eq];
  system_.frames().to_global(trial_);
  trial_ += u;
  const double fraction = contacts_->landing_fraction(u, trial_, state.contacts);
  landing_cut_ = fraction < 1.0;
  return fraction;
}

void TsmProblem::begin_step(const State& state) {
  switches_ = reversals_ = 0;
  max_switches_ = 4 + 4 * static_cast<int>(state.contacts.size());
  // A contact point that keeps hopping back and forth between elements within one step is
  // wandering over iterates far from the path (it may land on another branch, a beam looped
  // around the node): fail the step so that cutback follows the path in smaller steps. Sliding
  // on in one direction, one element per iterate, is not limited here.
  max_reversals_ = 4 * static_cast<int>(state.contacts.size());
  predictor_pending_ = true;
  landing_cut_ = false;
  far_along_chords_ = false;
  system_.forget_contact_pairs();  // the pairs the last step's iterates joined and its end no longer uses
  from_unloaded_ = physical(state).isZero() && (dead_load().size() == 0 || dead_load().isZero());
}

std::optional<StepFailure> TsmProblem::after_iterate(const State& state) const {
  if (!switching_too_often() && reversals_ <= max_reversals_) return std::nullopt;
  StepFailure failure;
  if (switching_too_often()) {
    failure.reason = StepFailure::Reason::contacts_switching;
    return failure;
  }
  failure.reason = StepFailure::Reason::contacts_hopping;
  // A point that rests on a beam node where two elements meet at an angle (a symmetric push on
  // a node) is pushed along one chord's normal, then the other's (README, Contact).
  const auto hops = std::find_if(state.contacts.begin(), state.contacts.end(),
                                 [](const contact::ContactState& c) { return c.step.hop_node >= 0; });
  if (hops != state.contacts.end()) {
    failure.hopping_contact = static_cast<int>(hops - state.contacts.begin());
    failure.hop_node = hops->step.hop_node;
  }
  return failure;
}

Settlement TsmProblem::at_convergence(State& state) {
  Settlement settlement;
  if (along_chords_) {  // balanced along the chords' normals (a landing iterate): not the model's
    evaluate(state);
    settlement.evaluated_again = true;
    settlement.kind = Settlement::Kind::iterate_on;
    return settlement;
  }
  if (release_pulling_contacts(state)) {  // converged with a contact pulling: iterate on without it
    settlement.evaluated_again = true;
    settlement.kind = Settlement::Kind::iterate_on;
    if (switching_too_often()) {
      settlement.kind = Settlement::Kind::failed;
      settlement.failure.reason = StepFailure::Reason::contacts_switching;
    }
    return settlement;
  }
  if (contacts_ && contacts_->passed_through(physical(state), state.chord_rotations, state.contacts)) {
    // A contact released in this step let its node through a beam: it takes part again (the
    // active set needs it), and Newton iterates on; the switch count bounds the cycling.
    switches_ += contacts_->allow_touching_again(physical(state), state.chord_rotations, state.contacts);
    if (switching_too_often()) {
      settlement.kind = Settlement::Kind::failed;
      settlement.failure.reason = StepFailure::Reason::contact_passed_through;
      return settlement;
    }
    evaluate(state, Proximity::near, true);
    settlement.evaluated_again = true;
    settlement.kind = Settlement::Kind::iterate_on;
    return settlement;
  }
  if (eval_.largest_end_rotation > largest_end_rotation) {
    // Eq. 3–5 describe an element by its chord: an end turned past a right angle against it
    // is no state of the beam, but a branch the mesh cannot carry (Newton with a large step
    // can land there, e.g. a beam looped around a contact node). The step fails and is cut back.
    settlement.kind = Settlement::Kind::failed;
    settlement.failure.reason = StepFailure::Reason::end_turned_too_far;
    settlement.failure.end_rotation = eval_.largest_end_rotation;
    return settlement;
  }
  if (const auto [k, element] = contacts_ ? contacts_->blocked(state.contacts) : std::pair{-1, -1}; k >= 0) {
    // Its node lies through an element points of the other frame are on: the state is not
    // acceptable, and no iterate can change that.
    settlement.kind = Settlement::Kind::failed;
    settlement.failure.reason = StepFailure::Reason::contact_blocked;
    settlement.failure.blocked_contact = k;
    settlement.failure.element = element;
    settlement.failure.holding_contact = contact_on(state, element);
  }
  return settlement;
}

std::vector<std::pair<int, int>> TsmProblem::accept(State& state) {
  std::vector<std::pair<int, int>> slid_off;
  for (size_t k = 0; k < state.contacts.size(); ++k)
    if (!state.contacts[k].active && state.contacts[k].step.slid_off_element >= 0)
      slid_off.emplace_back(static_cast<int>(k), state.contacts[k].step.slid_off_element);
  if (contacts_) {
    state.contact_references = contact::step_start(physical(state), state.chord_rotations);
    contacts_->accept(state.contact_references, state.contacts);
    // A slipping contact's anchor has moved: the next step starts from the tangent with it (it
    // sticks there), as a run restarted from this state does, not from the converged iterate's.
    if (std::any_of(state.contacts.begin(), state.contacts.end(), [](const contact::ContactState& c) {
          return c.active && c.friction.step_status == contact::FrictionStatus::slip;
        }))
      evaluate(state);
  }
  return slid_off;
}

void TsmProblem::take_contact_references(State& state) const {
  if (!contacts_) return;
  state.contact_references = contact::step_start(physical(state), state.chord_rotations);
  contacts_->restore(state.contact_references, state.contacts);
}

bool TsmProblem::name_unloaded_mechanism(const State& state, StepFailure& failure, double within_shifts) {
  State scratch = state;  // at the unloaded state (a blown-up iterate moved off it), evaluated again
  scratch.displacements.setZero();
  scratch.load_factor = 0.0;
  std::fill(scratch.chord_rotations.begin(), scratch.chord_rotations.end(), 0.0);
  evaluate(scratch);
  analyse_pattern();
  const Eigen::VectorXd mode = null_vector(system_.tangent_for_factorisation(), solver_, equations_.free_count(), within_shifts);
  if (mode.size() == 0) return false;
  const Model& model = system_.model();
  Eigen::VectorXd all = Eigen::VectorXd::Zero(model.dof_count());
  for (int eq = 0; eq < equations_.free_count(); ++eq) all[equations_.free_dofs[eq]] = mode[eq];
  system_.frames().to_global(all);
  name_free_motion(model, all, failure);
  return true;
}

void TsmProblem::explain(const State& state, StepFailure& failure) {
  landing_cut_ = false;  // a step that failed between its cut and the iterate: the retry starts afresh
  along_chords_ = false;  // nor does the failed iterate's model outlive it (element_forces of the restored state)
  failure.hinged = hinged_;
  failure.contacts = contacts_ != nullptr;
  const Model& model = system_.model();
  // Singular, or blown up, at the unloaded state (no displacement, no load held from an earlier
  // stage): the elements' own stiffness may leave a motion free — a mechanism; named by its null
  // vector. A tangent that did factorise (its pivots rounded off zero: a four-hinged portal's
  // sway) only where its smallest eigenvalue is at round-off level.
  const bool singular = failure.reason == StepFailure::Reason::singular_tangent;
  if ((singular || failure.reason == StepFailure::Reason::blew_up) && failure.iteration == 1 && from_unloaded_) {
    if (name_unloaded_mechanism(state, failure, singular ? singular_within_shifts : regular_within_shifts) || singular) return;
  }
  // A free end: the node ends one element only. A point within contact_at_free_end of one is as
  // good as off it when the step fails: along the bent beam's normal Newton's iterates there
  // pass to and fro across the end, the last one on either side of it.
  constexpr double contact_at_free_end = 1e-3;
  const auto at_free_end = [&](const contact::ContactState& c) {
    const Element& e = model.elements[c.element];
    const int node = c.alpha < contact_at_free_end ? e.start : c.alpha > 1.0 - contact_at_free_end ? e.end : -1;
    return node >= 0 && std::count_if(model.elements.begin(), model.elements.end(), [node](const Element& other) {
                          return other.start == node || other.end == node;
                        }) == 1;
  };
  for (const int k : holding_contacts_) {
    const contact::ContactState& c = state.contacts[k];
    // Released, or held at a free end it has gone past or has reached (α beyond [0, 1] after the
    // hand-over at a free end; beyond an inner node it is a point that stopped hopping, which
    // the step's own reason tells).
    if (!c.active || at_free_end(c)) {  // the cause first: what Newton then met follows from it
      failure.lost_resting_contact = k;
      failure.resting_contact_slid_off = c.active;
      return;
    }
  }
}

bool TsmProblem::release_pulling_contacts(State& state) {
  if (!contacts_) return false;
  bool overwrote_tangent = false;
  const std::vector<int> also = look_ahead_releases(state, overwrote_tangent);
  const contact::ContactChanges changes =
      contacts_->update(physical(state), state.chord_rotations, eval_.contacts, state.contacts, true, state.contact_references);
  if (!changes.any() && !overwrote_tangent) return false;
  switches_ += changes.activated + changes.released;
  if (!also.empty()) switches_ += contacts_->release_as_pulling(also, physical(state), state.chord_rotations, state.contacts);
  // The look-ahead's factorisation took the tangent's place: all of it is evaluated again.
  evaluate(state, Proximity::near, !overwrote_tangent);
  return changes.any() || !also.empty();
}

std::vector<int> TsmProblem::look_ahead_releases(State& state, bool& overwrote_tangent) {
  // Where dozens of contacts close along a beam, the step's predictor runs the free part through
  // it and closes too many; at the converged iterate only the outermost over-held contacts pull
  // (the held zone's edge carries a couple), and releasing them moves the edge by a node or two
  // per converged iterate — a beam pressed onto another took 3 iterates for each. The release is
  // looked ahead on the tangent here instead (forecast_releases; G = Uᵀ K⁻¹ U, one solve per
  // contact that lets go), and those that would pull once the pulling ones have let go let go
  // with them.
  // Newton corrects what the linearised forecast gets wrong (a node released too soon comes back
  // through passed_through).
  overwrote_tangent = false;
  std::vector<int> also;
  // Below `fewest` contacts in touch there is nothing to gain. Above any number it is worth it: the
  // forecast costs a factorisation and one solve per contact that lets go (at most its
  // largest_set), a Newton iterate or a few, where a long beam's two lift-off zones let go a few
  // nodes per three iterates without it (a 300-m press of 3,001 contact nodes ran out of its 50).
  constexpr size_t fewest = 4;
  const std::vector<contact::ActiveContact> active = active_contacts(state);
  if (active.size() < fewest || !system_.follower_rank_one().empty()) return also;
  // The contacts' entries in the order of `active`'s points, which contact_directions keeps
  // (two at a vertex, which stay out of the forecast). Points that share an element are coupled
  // through it: the forecast takes the element's point stiffness C⁻¹ whole.
  std::vector<int> owner, side;
  std::vector<char> may_join;
  bool pulls = false;
  for (const contact::ActiveContact& a : active)
    for (const contact::ActivePoint& p : a.points) {
      const contact::ContactState& c = state.contacts[p.contact];
      if (c.vertex && (-c.side * c.Y < 0.0 || -c.vertex->side * c.vertex->Y < 0.0)) return also;  // a vertex opens: as before
      owner.push_back(p.contact);
      side.push_back(p.vertex ? c.vertex->side : c.side);
      may_join.push_back(!c.vertex);
      pulls = pulls || c.force < 0.0;
    }
  if (!pulls) return also;
  // The forecast is made along the chords' normals. Letting go of a point takes out its load
  // Y u and its stiffness u uᵀ/c; along the bent beam's normal its tangent also carries the
  // normal's turning, Y (g ∇w_αᵀ + ∇w_α gᵀ) with ∇w_α ≈ ½ c_α ∇Y = ½ c_α u/c: a term of the
  // contact's own stiffness 1/c, times Y, that the forecast would leave behind in K as the point
  // lets go. The forecast's balance, 1 − G_ii/c, is the compliance of the beam behind the contact
  // against the contact's own: a few 10⁻³ of it where a flexible beam lies on a stiff one, and
  // there the left-over term decides the sign of the forecast Y (a beam pressed onto another
  // released two contacts per converged iterate, not the whole over-held zone). Whether a point
  // lets go is Y's sign, the same along either normal (Y is the share along n), and the
  // directions differ by the slope w', which vanishes as the mesh is refined. The state's own
  // evaluation (eval_, whose contacts update() reads next) stays the bent beam's: the chords' is
  // a scratch one, its tangent the one factorised below.
  std::vector<contact::ActiveContact> along_chords = active;
  bool bent = false;
  for (contact::ActiveContact& a : along_chords)
    for (contact::ContactElementData& d : a.data) {
      const bool was_bent = std::exchange(d.normal, ContactNormal::chord) != ContactNormal::chord;
      bent = bent || was_bent;
    }
  overwrote_tangent = true;
  if (bent) {
    assembly::Evaluation chords;
    system_.evaluate(physical(state), state.chord_rotations, true, chords, along_chords);
  }
  const std::vector<assembly::ContactDirection> directions =
      system_.contact_directions(physical(state), state.chord_rotations, along_chords);
  analyse_pattern();
  // With more sliding terms than Woodbury takes, the forecast is made on the symmetric part
  // alone: with them (the node-block LU) the 100-m press in one step let 182 of its 974
  // contacts go at once (the symmetric part's forecast: 15, and 959 stay in touch at
  // convergence), and the step failed.
  const std::vector<RankOne>& sliding = system_.contact_rank_one();
  const bool symmetric_part = sliding.size() > LinearSolver::most_rank_one;
  if (!solver_.factorize(system_.tangent_for_factorisation(), symmetric_part ? std::vector<RankOne>{} : sliding))
    return also;
  const int n = static_cast<int>(directions.size());
  contact::PointStiffness stiffness;
  Eigen::VectorXd Y(n);
  for (int j = 0; j < n;) {  // an element's points, its block of C⁻¹
    int end = j + 1;
    while (end < n && directions[end].element == directions[j].element) ++end;
    Eigen::MatrixXd block(end - j, end - j);
    for (int i = j; i < end; ++i) block.row(i - j) = directions[i].stiffness_row;
    stiffness.add(block);
    for (int i = j; i < end; ++i) Y[i] = directions[i].Y;
    j = end;
  }
  bool finite = true;
  const auto column = [&](int j) {  // Uᵀ K⁻¹ u_j: one solve
    Eigen::VectorXd x = Eigen::VectorXd::Zero(system_.dofs().free_count());
    for (size_t e = 0; e < directions[j].equation.size(); ++e)
      if (directions[j].equation[e] >= 0) x[directions[j].equation[e]] += directions[j].u[e];
    solver_.solve_in_place(x);
    Eigen::VectorXd g(n);
    for (int i = 0; i < n; ++i) {
      double sum = 0.0;
      for (size_t e = 0; e < directions[i].equation.size(); ++e)
        if (directions[i].equation[e] >= 0) sum += directions[i].u[e] * x[directions[i].equation[e]];
      g[i] = sum;
    }
    finite = finite && g.allFinite();
    return g;
  };
  const std::vector<char> released = contact::forecast_releases(column, stiffness, Y, side, may_join);
  if (!finite) return also;
  for (int i = 0; i < n; ++i)
    if (released[i] && !(-side[i] * Y[i] < 0.0)) also.push_back(owner[i]);  // beyond those that pull now
  return also;
}

Factorisation TsmProblem::factorisation(bool ok, bool symmetric) const {
  Factorisation f;
  f.ok = ok;
  const std::optional<linalg::Inertia> inertia = solver_.inertia();
  if (!ok || !symmetric || !inertia) return f;
  if (inertia->known()) f.negative_pivots = inertia->negative;
  else f.rounded = RoundedInertia{system_.dofs().block_node(inertia->row), inertia->component, inertia->ratio};
  return f;
}

Factorisation TsmProblem::negative_eigenvalues(State& state, bool evaluated) {
  if (!evaluated) evaluate(state);
  // Not symmetric (a follower load's skew terms, friction's): the inertia tells nothing.
  if (!system_.follower_rank_one().empty() || !system_.friction_rank_one().empty()) return {};
  analyse_pattern();
  solver_.guard_inertia(true);
  return factorisation(solver_.factorize(system_.tangent_for_factorisation()), true);
}

std::vector<ContactPoint> TsmProblem::contact_points(const State& state) const {
  std::vector<ContactPoint> points;
  for (const contact::ContactState& c : state.contacts) {
    ContactPoint p;
    if (c.active) {
      p = {c.element, c.alpha, c.force, c.Y, c.vertex ? c.vertex->element : -1, c.vertex ? c.vertex->Y : 0.0,
           Eigen::Vector2d(c.push[0], c.push[1])};
      const contact::FrictionState& f = c.friction;
      const bool accepted = f.step_status != contact::FrictionStatus::none;
      p.friction = accepted ? f.step_status : f.status;
      p.tangential = accepted ? f.step_tangential : f.tangential;
      p.slip = f.slip;
    }
    points.push_back(p);
  }
  return points;
}

Eigen::VectorXd TsmProblem::element_forces(const State& state) const {
  // A converged state's: its points push along their own normals, whatever model the last
  // evaluation (a failed attempt's far iterate) used.
  const std::vector<contact::ActiveContact> active =
      contacts_ ? contacts_->active_contacts(state.contacts, false) : std::vector<contact::ActiveContact>();
  return system_.element_forces(physical(state), state.chord_rotations, active);
}

Eigen::VectorXd TsmProblem::reactions(double load_factor) const {
  const Model& model = system_.model();
  Eigen::VectorXd reactions = util::zeros_touched(model.dof_count());
  const Eigen::VectorXd &P = reference_load(), &dead = dead_load();
  for (int dof : equations_.constrained_dofs)
    reactions[dof] = eval_.internal_force[dof] - (dead.size() > 0 ? load_factor * P[dof] + dead[dof] : load_factor * P[dof]);
  system_.frames().to_global(reactions);  // a skew roller's normal reaction, in x and y
  return reactions;
}

Eigen::VectorXd TsmProblem::global_internal_force() const {
  Eigen::VectorXd forces = eval_.internal_force;
  system_.frames().to_global(forces);
  return forces;
}

const Eigen::VectorXd& TsmProblem::physical(const State& state) const {
  if (system_.frames().empty()) return state.displacements;
  physical_ = state.displacements;
  system_.frames().to_global(physical_);
  return physical_;
}

int TsmProblem::contact_on(const State& state, int element) const {
  for (size_t k = 0; k < state.contacts.size(); ++k)
    if (state.contacts[k].active &&
        (state.contacts[k].element == element || (state.contacts[k].vertex && state.contacts[k].vertex->element == element)))
      return static_cast<int>(k);
  return -1;
}

}  // namespace tsm::solver
