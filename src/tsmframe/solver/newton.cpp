#include "tsmframe/solver/newton.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>

#include "tsmframe/util/first_touch.hpp"
#include "tsmframe/util/parallel_for.hpp"
#include "tsmframe/model/mechanism.hpp"
#include "tsmframe/model/resting_contact.hpp"
#include "tsmframe/solver/release_forecast.hpp"

namespace tsm::solver {
namespace {

constexpr double round_off_ratio = 1e-12;  // ‖ΔD‖∞ ≤ 1e-12 · max(size, ‖D‖∞) ends a step (FORMAT.md)
constexpr double blow_up_ratio = 1e12;     // ‖R‖ > 1e12 · scale is divergence (FORMULATION §4)
constexpr double runaway_ratio = 1e6;      // |u| > 1e6 · (size + prescribed) is divergence, unless …
// … the iterate's coordinates still give every element's chord to this fraction of its length
// (|u| · ε below it × the shortest l0): a flexible structure's first iterate from a straight
// state (a cable, EI alone against its weight) overshoots in proportion to the load and comes
// back from far, chords and all, where the geometry stays resolved.
constexpr double chord_resolution = 1e-4;
constexpr double floor_ratio = 10.0;       // ‖R‖ ≤ 10 × the estimated rounding floor …
constexpr double stagnation = 0.5;         // … ends a step once Newton no longer halves it
constexpr double floor_check_below = 1e-3; // the floor (a pass of its own) is only worth checking below this
constexpr double largest_end_rotation = std::numbers::pi / 2;  // |θ| an element end may turn against its chord
// The contacts' sliding terms (FORMULATION §2) join the solve only once the relative residual is
// below this (and in a step's first solve, from a converged state). Far from it the point hops
// between short elements, where ∂k0/∂α is large and changes from element to element, and the
// consistent tangent sent Newton farther off: a 10⁴-element push took 8–24 iterates a step with
// it, 6–9 with the symmetric part alone (bench/README "Seventh session"). Near the solution
// the terms bring back quadratic convergence.
constexpr double sliding_terms_below = 1e-2;

constexpr int iterates_without_progress = 5;  // then a residual far from the tolerance is held against the floor

/// Σ over [0, n) in fixed chunks (the same chunks whatever the number of threads), the chunk
/// sums added in order: bit-identical for any number of threads. body(begin, end, sums) adds its
/// range into sums. With `combine` a maximum (Larger) the chunks' maxima instead.
template <int K, class Body, class Combine = std::plus<double>>
std::array<double, K> chunked_reduce(Eigen::Index n, const Body& body, Combine combine = {}) {
  constexpr Eigen::Index chunk = 16384;
  const Eigen::Index chunks = (n + chunk - 1) / chunk;
  std::vector<std::array<double, K>> partial(chunks);
  util::parallel_for_static(Eigen::Index{0}, chunks, chunks >= 4, [&](Eigen::Index c) {
    std::array<double, K> sums{};
    body(c * chunk, std::min(n, (c + 1) * chunk), sums);
    partial[c] = sums;
  });
  std::array<double, K> total{};
  for (const std::array<double, K>& p : partial)
    for (int k = 0; k < K; ++k) total[k] = combine(total[k], p[k]);
  return total;
}

struct Larger {
  double operator()(double a, double b) const { return std::max(a, b); }
};

// Equations run in elimination order, the model's vectors in node order: a loop over the
// equations reads them in runs (a member's nodes) with jumps between, and each jump missed the
// cache (the lattice of bench/: 0.83 ms an update_residual, the chains 0.31). Each loop fetches
// the entry this many equations ahead — in models whose vectors outgrow the core's caches
// (from 2¹⁵ equations, 256 kB a vector): below, the extra instructions cost a 10³-element
// chain 3 % an iteration. Written out in each loop: GCC drops a call to a helper that only
// prefetches (no side effects, so a dead call), and the prefetch with it.
constexpr Eigen::Index gather_ahead = 32;
constexpr Eigen::Index gather_from = Eigen::Index{1} << 15;

std::string iterate_text(const char* what, int iteration) {
  std::ostringstream os;
  os << what << " at iteration " << iteration;
  return os.str();
}

}  // namespace

NewtonSolver::NewtonSolver(assembly::GlobalSystem& system, const NewtonSettings& settings,
                           const contact::ContactTracker* contacts)
    : system_(system), settings_(settings), contacts_(contacts && contacts->contact_count() > 0 ? contacts : nullptr) {
  const assembly::DofMap& dofs = system.dofs();
  is_moment_.resize(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq) is_moment_[eq] = dofs.dof(eq) % dofs_per_node == rz ? 1 : 0;
  const Model& model = system.model();
  if (contacts_ && !find_mechanism(model) && find_mechanism(model, false))
    for (int k = 0; k < static_cast<int>(model.contacts.size()); ++k)
      if (resting_contact(model, model.contacts[k])) holding_contacts_.push_back(k);
  for (int dof = 0; dof < model.dof_count(); ++dof) {
    if (model.constrained[dof]) constrained_dofs_.push_back(dof);
    if (dof % dofs_per_node != rz) prescribed_squared_ += model.prescribed(dof) * model.prescribed(dof);
  }
  solver_.analyze(system.dofs(), system.tangent());
  analysed_pattern_ = system.pattern_version();
  double shortest = model.elements.empty() ? 0.0 : std::numeric_limits<double>::infinity();
  for (const Element& e : model.elements)
    shortest = std::min(shortest, (model.nodes[e.end].position - model.nodes[e.start].position).norm());
  resolvable_move_ = chord_resolution * shortest / std::numeric_limits<double>::epsilon();
}

bool NewtonSolver::evaluate(State& state, bool contacts_only) {
  const Model& model = system_.model();
  system_.set_load_factor(state.load_factor);
  for (int dof : constrained_dofs_) state.displacements[dof] = state.load_factor * model.prescribed(dof);
  constexpr int max_passes = 4;  // contact changes settled per iterate before Newton goes on
  bool changed = false;
  for (int pass = 0;; ++pass) {
    const std::vector<contact::ActiveContact> active = active_contacts(state);
    // The rotations are continued in place (one vector, not two): lent to the evaluation.
    std::swap(state.chord_rotations, eval_.chord_rotations);
    if (pass > 0 || contacts_only) system_.evaluate_contact_change(state.displacements, eval_.chord_rotations, eval_, active);
    else system_.evaluate(state.displacements, eval_.chord_rotations, true, eval_, active);
    std::swap(state.chord_rotations, eval_.chord_rotations);
    if (!contacts_) return false;
    if (pass == max_passes) break;
    const contact::ContactChanges changes =
        contacts_->update(state.displacements, state.chord_rotations, eval_.contacts, state.contacts, false);
    if (!changes.any()) break;
    changed = true;
    switches_ += changes.activated + changes.released;
    reversals_ += changes.reversed;
  }
  // α and force of the evaluation that stands (update() has set them unless the passes ran out).
  contacts_->record(state.displacements, state.chord_rotations, eval_.contacts, state.contacts);
  return changed;
}

bool NewtonSolver::release_pulling_contacts(State& state) {
  if (!contacts_) return false;
  bool overwrote_tangent = false;
  const std::vector<int> also = look_ahead_releases(state, overwrote_tangent);
  const contact::ContactChanges changes =
      contacts_->update(state.displacements, state.chord_rotations, eval_.contacts, state.contacts, true);
  if (!changes.any() && !overwrote_tangent) return false;
  switches_ += changes.activated + changes.released;
  if (!also.empty()) switches_ += contacts_->release_as_pulling(also, state.displacements, state.chord_rotations, state.contacts);
  // The look-ahead's factorisation took the tangent's place: all of it is evaluated again.
  evaluate(state, !overwrote_tangent);
  return changes.any() || !also.empty();
}

std::vector<int> NewtonSolver::look_ahead_releases(State& state, bool& overwrote_tangent) {
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
  constexpr size_t fewest = 4, most = 2000;  // contacts in touch: below, nothing to gain; above, the solves cost
  const std::vector<contact::ActiveContact> active = active_contacts(state);
  if (active.size() < fewest || active.size() > most || !system_.follower_rank_one().empty()) return also;
  // Contact k's entries in `active` (two at a vertex, which stay out of the forecast).
  std::vector<int> owner, side;
  std::vector<char> may_join;
  bool pulls = false;
  for (size_t k = 0; k < state.contacts.size(); ++k) {
    const contact::ContactState& c = state.contacts[k];
    if (!c.active) continue;
    owner.push_back(static_cast<int>(k));
    side.push_back(c.side);
    may_join.push_back(c.partner < 0);
    if (c.partner >= 0) {
      owner.push_back(static_cast<int>(k));
      side.push_back(c.partner_side);
      may_join.push_back(0);
      if (-c.side * c.Y < 0.0 || -c.partner_side * c.partner_Y < 0.0) return also;  // a vertex opens: as before
    }
    pulls = pulls || c.force < 0.0;
  }
  if (!pulls || owner.size() != active.size()) return also;
  const std::vector<assembly::ContactDirection> directions =
      system_.contact_directions(state.displacements, state.chord_rotations, active);
  if (system_.pattern_version() != analysed_pattern_) {
    solver_.analyze(system_.dofs(), system_.tangent());
    analysed_pattern_ = system_.pattern_version();
  }
  overwrote_tangent = true;
  if (!solver_.factorize(system_.tangent_for_factorisation(), system_.contact_rank_one())) return also;
  const int n = static_cast<int>(directions.size());
  Eigen::VectorXd stiffness(n), Y(n);
  for (int j = 0; j < n; ++j) {
    stiffness[j] = directions[j].stiffness;
    Y[j] = directions[j].Y;
  }
  bool finite = true;
  const auto column = [&](int j) {  // Uᵀ K⁻¹ u_j: one solve
    Eigen::VectorXd x = Eigen::VectorXd::Zero(system_.dofs().free_count());
    for (int e = 0; e < 9; ++e)
      if (directions[j].equation[e] >= 0) x[directions[j].equation[e]] += directions[j].u[e];
    solver_.solve_in_place(x);
    Eigen::VectorXd g(n);
    for (int i = 0; i < n; ++i) {
      double sum = 0.0;
      for (int e = 0; e < 9; ++e)
        if (directions[i].equation[e] >= 0) sum += directions[i].u[e] * x[directions[i].equation[e]];
      g[i] = sum;
    }
    finite = finite && g.allFinite();
    return g;
  };
  const std::vector<char> released = forecast_releases(column, stiffness, Y, side, may_join);
  if (!finite) return also;
  for (int i = 0; i < n; ++i)
    if (released[i] && !(-side[i] * Y[i] < 0.0)) also.push_back(owner[i]);  // beyond those that pull now
  return also;
}

void NewtonSolver::reset(State& state) { evaluate(state); }

int NewtonSolver::negative_eigenvalues(State& state, bool evaluated) {
  if (!evaluated) evaluate(state);
  if (!system_.follower_rank_one().empty()) return -1;  // not symmetric: the inertia tells nothing
  if (system_.pattern_version() != analysed_pattern_) {
    solver_.analyze(system_.dofs(), system_.tangent());
    analysed_pattern_ = system_.pattern_version();
  }
  if (!solver_.factorize(system_.tangent_for_factorisation())) return -1;
  return solver_.negative_pivots();
}

std::vector<contact::ActiveContact> NewtonSolver::active_contacts(const State& state) const {
  return contacts_ ? contacts_->active_contacts(state.contacts) : std::vector<contact::ActiveContact>();
}

std::vector<ContactPoint> NewtonSolver::contact_points(const State& state) const {
  std::vector<ContactPoint> points;
  for (const contact::ContactState& c : state.contacts) {
    ContactPoint p;
    if (c.active) p = {c.element, c.alpha, c.force, c.Y, c.partner, c.partner_Y};
    points.push_back(p);
  }
  return points;
}

Eigen::VectorXd NewtonSolver::element_forces(const State& state) const {
  const std::vector<contact::ActiveContact> active = active_contacts(state);
  return system_.element_forces(state.displacements, state.chord_rotations, active);
}

Eigen::VectorXd NewtonSolver::reactions(double load_factor) const {
  const Model& model = system_.model();
  Eigen::VectorXd reactions = util::zeros_touched(model.dof_count());
  const Eigen::VectorXd& P = reference_load();
  for (int dof : constrained_dofs_) reactions[dof] = eval_.internal_force[dof] - load_factor * P[dof];
  return reactions;
}

ResidualScale NewtonSolver::scale(double load_factor) const {
  // As in update_residual, without writing R (the scale at a λ other than the state's).
  const assembly::DofMap& dofs = system_.dofs();
  const double* F = eval_.internal_force.data();
  const double* P = reference_load().data();
  const int* free_dof = dofs.free_dofs().data();
  const bool gather = dofs.free_count() >= gather_from;
  const std::array<double, 4> free =
      chunked_reduce<4>(dofs.free_count(), [&](Eigen::Index begin, Eigen::Index end, std::array<double, 4>& sum) {
        for (Eigen::Index eq = begin; eq < end; ++eq) {
          if (gather && eq + gather_ahead < end) {
            __builtin_prefetch(F + free_dof[eq + gather_ahead]);
            __builtin_prefetch(P + free_dof[eq + gather_ahead]);
          }
          const int dof = free_dof[eq], kind = is_moment_[eq];
          const double f = F[dof], p = load_factor * P[dof];
          sum[kind] += p * p;
          sum[2 + kind] += f * f;
        }
      });
  return scale_from({free[0], free[1]}, {free[2], free[3]}, load_factor);
}

ResidualScale NewtonSolver::scale_from(std::array<double, 2> load, std::array<double, 2> internal, double load_factor) const {
  // Squared sums per kind: applied loads on free dofs (given), reactions, internal forces on all
  // dofs (given over the free ones; the constrained ones are added here).
  const Model& model = system_.model();
  const double* F = eval_.internal_force.data();
  const double* P = reference_load().data();
  double reaction[2] = {0, 0};
  for (const int dof : constrained_dofs_) {
    const int kind = dof % dofs_per_node == rz ? 1 : 0;
    const double f = F[dof], p = load_factor * P[dof];
    internal[kind] += f * f;
    reaction[kind] += (f - p) * (f - p);
  }
  ResidualScale s;
  s.force = std::sqrt(std::max({load[0], reaction[0], internal[0]}));
  s.moment = std::sqrt(std::max({load[1], reaction[1], internal[1]}));
  // A structure loaded only by forces (or only by moments) still has a scale for the other kind.
  const double force = s.force;
  s.force = std::max(s.force, s.moment / model.size);
  s.moment = std::max(s.moment, force * model.size);
  return s;
}

NewtonSolver::ResidualPass NewtonSolver::update_residual(double load_factor) {
  const assembly::DofMap& dofs = system_.dofs();
  const Eigen::Index n = dofs.free_count();
  util::resize_touched(residual_, n);
  const double* F = eval_.internal_force.data();
  const double* P = reference_load().data();
  const int* free_dof = dofs.free_dofs().data();
  double* R = residual_.data();
  const bool gather = n >= gather_from;
  // Squared sums per kind (forces, moments) over the free equations: R, applied loads, internal forces.
  const std::array<double, 6> free = chunked_reduce<6>(n, [&](Eigen::Index begin, Eigen::Index end, std::array<double, 6>& sum) {
    // Six running sums in registers, not an array indexed by the kind: through memory every
    // term would wait for the previous one's store. The other kind's sum gains +0.0 (exact).
    double r0 = 0.0, r1 = 0.0, p0 = 0.0, p1 = 0.0, f0 = 0.0, f1 = 0.0;
    for (Eigen::Index eq = begin; eq < end; ++eq) {
      if (gather && eq + gather_ahead < end) {
        __builtin_prefetch(F + free_dof[eq + gather_ahead]);
        __builtin_prefetch(P + free_dof[eq + gather_ahead]);
      }
      const int dof = free_dof[eq];
      const bool moment = is_moment_[eq] != 0;
      const double f = F[dof], p = load_factor * P[dof], r = p - f;
      R[eq] = r;
      const double rr = r * r, pp = p * p, ff = f * f;
      r0 += moment ? 0.0 : rr;
      r1 += moment ? rr : 0.0;
      p0 += moment ? 0.0 : pp;
      p1 += moment ? pp : 0.0;
      f0 += moment ? 0.0 : ff;
      f1 += moment ? ff : 0.0;
    }
    sum = {r0, r1, p0, p1, f0, f1};
  });
  ResidualPass pass;
  pass.norms = {std::sqrt(free[0]), std::sqrt(free[1])};
  pass.scale = scale_from({free[2], free[3]}, {free[4], free[5]}, load_factor);
  double constrained = 0.0;
  for (const int dof : constrained_dofs_) constrained += F[dof];
  pass.finite = std::isfinite(free[0] + free[1] + free[4] + free[5] + constrained);
  return pass;
}

void NewtonSolver::load_direction(Eigen::VectorXd& out) const {
  const assembly::DofMap& dofs = system_.dofs();
  const double* P = reference_load().data();
  out.resize(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq) out[eq] = P[dofs.dof(eq)];
  if (eval_.prescribed_coupling.size() > 0) out -= eval_.prescribed_coupling;
}

void NewtonSolver::solve_along_load_and_residual() {
  load_direction(along_load_);
  solver_.solve_in_place(along_load_);
  along_residual_ = residual_;
  solver_.solve_in_place(along_residual_);
}

void NewtonSolver::add_load_direction(double dlambda, Eigen::VectorXd& v) const {
  const assembly::DofMap& dofs = system_.dofs();
  const double* P = reference_load().data();
  for (int eq = 0; eq < dofs.free_count(); ++eq) v[eq] += dlambda * P[dofs.dof(eq)];
  if (eval_.prescribed_coupling.size() > 0) v -= dlambda * eval_.prescribed_coupling;
}

std::array<double, 2> NewtonSolver::kind_norms(const Eigen::VectorXd& v) const {
  double sum[2] = {0, 0};
  for (Eigen::Index eq = 0; eq < v.size(); ++eq) sum[is_moment_[eq]] += v[eq] * v[eq];
  return {std::sqrt(sum[0]), std::sqrt(sum[1])};
}

double NewtonSolver::relative_norm(const std::array<double, 2>& norms, const ResidualScale& s) const {
  const auto [force, moment] = norms;
  if (s.force == 0.0 && s.moment == 0.0) return force + moment == 0.0 ? 0.0 : INFINITY;
  return std::max(force / s.force, moment / s.moment);
}

NewtonSolver::Correction NewtonSolver::apply_correction(const Eigen::VectorXd& correction, State& state) const {
  const int* free_dof = system_.dofs().free_dofs().data();
  double* D = state.displacements.data();
  const bool gather = correction.size() >= gather_from;
  // Maxima (the same whatever the order) of |c| and |D| per kind, and a fifth entry 1 where a
  // chunk's c is not finite (a NaN would pass through the maxima unnoticed).
  const std::array<double, 5> most = chunked_reduce<5>(
      correction.size(),
      [&](Eigen::Index begin, Eigen::Index end, std::array<double, 5>& m) {
        double translation = 0.0, rotation = 0.0, largest_translation = 0.0, largest_rotation = 0.0;
        bool finite = true;
        for (Eigen::Index eq = begin; eq < end; ++eq) {
          if (gather && eq + gather_ahead < end) __builtin_prefetch(D + free_dof[eq + gather_ahead], 1);
          const double c = correction[eq], d = D[free_dof[eq]] + c;
          D[free_dof[eq]] = d;
          finite = finite && std::isfinite(c);
          if (is_moment_[eq]) {
            rotation = std::max(rotation, std::abs(c));
            largest_rotation = std::max(largest_rotation, std::abs(d));
          } else {
            translation = std::max(translation, std::abs(c));
            largest_translation = std::max(largest_translation, std::abs(d));
          }
        }
        m = {translation, rotation, largest_translation, largest_rotation, finite ? 0.0 : 1.0};
      },
      Larger{});
  if (most[4] != 0.0) return {{NAN, NAN}, {NAN, NAN}};
  return {{most[0], most[1]}, {most[2], most[3]}};
}

std::array<double, 2> NewtonSolver::largest_displacements(const State& state, std::array<double, 2> free) const {
  const double* D = state.displacements.data();
  for (const int dof : constrained_dofs_) {
    if (dof % dofs_per_node == rz) free[1] = std::max(free[1], std::abs(D[dof]));
    else free[0] = std::max(free[0], std::abs(D[dof]));
  }
  return free;
}

double NewtonSolver::arc_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  double sum = 0.0;
  for (Eigen::Index eq = 0; eq < a.size(); ++eq)
    if (!is_moment_[eq]) sum += a[eq] * b[eq];
  return sum;
}

void NewtonSolver::free_displacements(const State& state, Eigen::VectorXd& v) const {
  const assembly::DofMap& dofs = system_.dofs();
  v.resize(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq) v[eq] = state.displacements[dofs.dof(eq)];
}

bool NewtonSolver::within_floor(const std::array<double, 2>& norms, const State& state) const {
  return within_floor(norms, system_.rounding_floor(state.displacements, state.chord_rotations, active_contacts(state)));
}

bool NewtonSolver::within_floor(const std::array<double, 2>& norms, const assembly::RoundingFloor& floor) {
  const auto [force, moment] = norms;
  return force <= floor_ratio * floor.force && moment <= floor_ratio * floor.moment;
}

NewtonOutcome NewtonSolver::step(const PathConstraint& constraint, State& state) {
  NewtonOutcome out = iterate_step(constraint, state);
  if (out.status == Status::converged) return out;
  if (holding_contacts_.empty()) return out;
  const Model& model = system_.model();
  for (const int k : holding_contacts_) {
    const contact::ContactState& c = state.contacts[k];
    // Released, or held at a free end it has gone past (α beyond [0, 1] after the hand-over).
    if (!c.active || c.alpha < 0.0 || c.alpha > 1.0) {  // the cause first: what Newton then met follows from it
      out.message = "the structure is held only by the contacts resting on it and the one at node " +
                    std::to_string(model.nodes[model.contacts[k].node].id) +
                    (c.active ? " has slid off the beam's end" : " let go") + ": nothing else supports it (then " +
                    out.message + ")";
      break;
    }
  }
  return out;
}

int NewtonSolver::contact_on(const State& state, int element) const {
  for (size_t k = 0; k < state.contacts.size(); ++k)
    if (state.contacts[k].active && (state.contacts[k].element == element || state.contacts[k].partner == element))
      return static_cast<int>(k);
  return -1;
}

bool NewtonSolver::carries_nothing(const ResidualScale& scale, const State& state) const {
  const assembly::RoundingFloor floor = system_.rounding_floor(state.displacements, state.chord_rotations, {});
  // Forces at rounding level leave moments at that level times a lever up to the model's size:
  // a ring moved as a rigid body by a prescribed displacement (61 elements, EI 2e3) had its
  // moments at 2.6e-8, ten times its elements' own moment floor, from its forces' 1e-6.
  const double moment_floor = std::max(floor.moment, floor.force * system_.model().size);
  return scale.force <= floor_ratio * floor.force && scale.moment <= floor_ratio * moment_floor;
}

NewtonOutcome NewtonSolver::iterate_step(const PathConstraint& constraint, State& state) {
  const assembly::DofMap& dofs = system_.dofs();
  const Model& model = system_.model();
  const double prescribed_size = model.reference_prescribed.lpNorm<Eigen::Infinity>();
  NewtonOutcome out;
  ResidualPass pass = update_residual(state.load_factor);
  const Eigen::VectorXd& R = residual_;
  ResidualScale start_scale;
  switches_ = reversals_ = 0;
  const bool by_arc = constraint.kind == PathConstraint::Kind::arc_length;
  if (by_arc) free_displacements(state, start_);
  const double start_load_factor = state.load_factor;
  const int max_switches = 4 + 4 * static_cast<int>(state.contacts.size());
  // A contact point that keeps hopping back and forth between elements within one step is
  // wandering over iterates far from the path (it may land on another branch, a beam looped
  // around the node): fail the step so that cutback follows the path in smaller steps. Sliding
  // on in one direction, one element per iterate, is not limited here.
  const int max_reversals = 4 * static_cast<int>(state.contacts.size());
  if (contacts_) out.contact_iterates.push_back(contact_points(state));
  int unsettled = 0;  // iterates that met the criterion but changed the contacts (iterating on)
  bool resolution_checked = false;  // whether a stagnating iterate far from the tolerance was held against the floor
  double lowest = INFINITY;  // the lowest relative residual of the step that halved the one before it
  int since_lowest = 0;      // iterates since then

  for (int it = 1; it <= settings_.max_iterations; ++it) {
    if (system_.pattern_version() != analysed_pattern_) {  // a contact has joined new nodes
      solver_.analyze(system_.dofs(), system_.tangent());
      analysed_pattern_ = system_.pattern_version();
    }
    // The SparseLU fallback (contacts only) needs the tangent the in-place LDLᵀ overwrote: it is
    // evaluated again at the same state, which stays as it is (a scratch evaluation).
    const auto refill = [&](BlockMatrix&) {
      const std::vector<contact::ActiveContact> active = active_contacts(state);
      assembly::Evaluation scratch;
      system_.evaluate(state.displacements, state.chord_rotations, true, scratch, active);
    };
    const auto singular = [&] {
      out.status = Status::singular;
      // Hinges can leave a mechanism inside a part (pinned bars in a row) that the supports'
      // check, which looks at parts as rigid bodies, does not see.
      const bool hinged = std::any_of(model.elements.begin(), model.elements.end(),
                                      [](const Element& e) { return e.release_start || e.release_end; });
      out.message = iterate_text(hinged ? "the tangent stiffness is singular (a limit or bifurcation point, or the member "
                                          "releases leave a mechanism, e.g. three hinges in a line)"
                                        : "the tangent stiffness is singular (a limit or bifurcation point)",
                                 it);
      return out;
    };
    // dR/dλ = F_dir = F_ref − K_fp D_p,ref: how the load factor drives the free dofs.
    double dlambda = 0.0;
    std::array<double, 2> drive{};  // norms of R + Δλ F_dir at iterate 0
    // Under load control R is not needed after the solve (the next iterate recomputes it): the
    // correction overwrites it, one vector of the model's size less; and the right-hand side is
    // known before the factorisation, which carries its forward substitution along.
    Eigen::VectorXd& correction = constraint.kind == PathConstraint::Kind::load_increment ? residual_ : correction_;
    // K_ff = tangent + the sliding terms in use (all, or none: sliding_terms_below); with `rhs`,
    // solved for it in place. Without the terms the symmetric part alone may be singular where
    // the whole is not: then once more with them.
    const auto factorise = [&](Eigen::VectorXd* rhs) {
      // A follower load's skew terms always join; the contacts' sliding terms as said above.
      const std::vector<RankOne>& skew = system_.follower_rank_one();
      const std::vector<RankOne>& contact = system_.contact_rank_one();
      const bool follower = !skew.empty();
      std::vector<RankOne> both;  // only in a model with both
      if (follower && !contact.empty()) {
        both = skew;
        both.insert(both.end(), contact.begin(), contact.end());
      }
      const std::vector<RankOne>& sliding = !follower ? contact : contact.empty() ? skew : both;
      const std::vector<RankOne>& none = skew;  // without the sliding terms
      const bool all = it == 1 || contact.empty() || out.residual_norms.back() < sliding_terms_below;
      BlockMatrix& K = system_.tangent_for_factorisation();
      auto attempt = [&](const std::vector<RankOne>& terms, Eigen::VectorXd* x) {
        const bool ok = x ? solver_.factorize_and_solve(K, terms, *x, refill) : solver_.factorize(K, terms, refill);
        // With a follower load's skew terms the tangent is not symmetric: its symmetric part's
        // inertia tells nothing of stability (a non-conservative load).
        if (const int negatives = follower ? -1 : solver_.negative_pivots(); ok && negatives >= 0) {
          if (it == 1) out.start_negative_pivots = negatives;
          else out.most_negative_pivots = std::max(out.most_negative_pivots, negatives);
        }
        return ok;
      };
      if (all) return attempt(sliding, rhs);
      if (rhs) kept_rhs_ = *rhs;  // the solve runs along the factorisation
      if (attempt(none, rhs)) return true;
      refill(K);  // the failed factorisation has overwritten part of it
      if (rhs) *rhs = kept_rhs_;
      return attempt(sliding, rhs);
    };
    if (constraint.kind == PathConstraint::Kind::load_increment) {
      if (it == 1) dlambda = constraint.load_increment;
      if (dlambda != 0.0) add_load_direction(dlambda, correction);
      if (it == 1) drive = kind_norms(correction);
      if (!factorise(&correction)) return singular();
    } else if (!factorise(nullptr)) {
      return singular();
    } else if (by_arc) {
      // δD = δD_R + δλ δD_F; δλ from the arc-length constraint (Crisfield's cylindrical form).
      const Eigen::VectorXd& a = along_load_;
      const Eigen::VectorXd& b = along_residual_;
      solve_along_load_and_residual();
      const double P2 = prescribed_squared_, s2 = constraint.arc_length * constraint.arc_length;
      const double qa = arc_dot(a, a) + P2;
      if (!(qa > 0.0) || !std::isfinite(qa)) {
        out.status = Status::singular;
        out.message = iterate_text("the load moves no translation (arc length undefined)", it);
        return out;
      }
      if (it == 1) {  // predictor along the tangent, continuing the direction of the last step
        double direction = 1.0;
        if (constraint.previous_increment.size() > 0) {
          const double along = arc_dot(constraint.previous_increment, a) + constraint.previous_load_increment * P2;
          direction = along < 0.0 ? -1.0 : 1.0;
        }
        dlambda = direction * constraint.arc_length / std::sqrt(qa);
      } else {
        free_displacements(state, increment_);
        increment_ -= start_;
        const Eigen::VectorXd& increment = increment_;
        const double dl = state.load_factor - start_load_factor;
        trial_ = increment + b;
        const Eigen::VectorXd& u = trial_;
        const double qb = 2.0 * (arc_dot(u, a) + dl * P2);
        const double qc = arc_dot(u, u) + dl * dl * P2 - s2;
        const double disc = qb * qb - 4.0 * qa * qc;
        if (!(disc >= 0.0)) {
          out.status = Status::diverged;
          out.message = iterate_text("the arc-length constraint has no real root", it);
          return out;
        }
        const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
        const double r1 = q / qa, r2 = q != 0.0 ? qc / q : -r1;
        // The root whose new increment turns least from the current one: no doubling back.
        auto turn = [&](double r) { return arc_dot(increment, u) + r * arc_dot(increment, a) + dl * (dl + r) * P2; };
        dlambda = turn(r1) >= turn(r2) ? r1 : r2;
      }
      correction = b + dlambda * a;
    } else {
      const Eigen::VectorXd& a = along_load_;
      const Eigen::VectorXd& b = along_residual_;
      solve_along_load_and_residual();
      const int k = constraint.equation;
      if (!(std::abs(a[k]) > 0.0) || !std::isfinite(a[k])) {
        out.status = Status::singular;
        // Where the load reaches the dof only through a contact still open (a beam pressed onto
        // another, the lower one's dof controlled), nothing moves it until that contact closes.
        out.message = iterate_text(contacts_ ? "the controlled dof does not move under the load (if the load reaches it only "
                                               "through a contact still open, it does not until that closes: control a dof "
                                               "the load moves from the start, or use arc-length control)"
                                             : "the controlled dof does not move under the load",
                                   it);
        out.size_independent = it == 1;  // the tangent at the step's start: a smaller step meets it too
        return out;
      }
      dlambda = (constraint.target - state.displacements[dofs.dof(k)] - b[k]) / a[k];
      correction = b + dlambda * a;
    }
    if (it == 1 && dlambda != 0.0) {
      const double moved = std::sqrt(arc_dot(correction, correction));
      if (moved > 0.0) out.start_stiffness = std::abs(dlambda) / moved;
    }
    if (it == 1) {  // iterate 0: the out-of-balance force that drives the step, at the target λ
      start_scale = dlambda == 0.0 ? pass.scale : scale(state.load_factor + dlambda);
      if (constraint.kind != PathConstraint::Kind::load_increment) {  // R is still the step's start
        drive_ = R;
        add_load_direction(dlambda, drive_);
        drive = kind_norms(drive_);
      }
      // The drive is a force level of the step too: a step that only moves supports of an
      // unstressed structure has no other (no loads, no internal forces yet), and its iterates
      // would be measured against nothing (a blow-up at once).
      start_scale.force = std::max(start_scale.force, drive[0]);
      start_scale.moment = std::max(start_scale.moment, drive[1]);
      out.residual_norms.push_back(relative_norm(drive, start_scale));
    }
    out.iterations = it;
    // Applied first, checked after (in the same pass): a failed step's state is restored by the caller.
    const Correction applied = apply_correction(correction, state);
    const std::array<double, 2>& step_size = applied.size;
    if (!std::isfinite(step_size[0]) || !std::isfinite(dlambda)) {
      out.status = Status::diverged;
      out.message = iterate_text("the Newton correction is not finite", it);
      return out;
    }
    state.load_factor += dlambda;
    const bool contacts_changed = evaluate(state);
    if (contacts_) out.contact_iterates.push_back(contact_points(state));
    if (switches_ > max_switches || reversals_ > max_reversals) {
      out.status = Status::contact_chatter;
      std::ostringstream what;
      if (switches_ > max_switches) {
        what << "contacts keep switching on and off";
      } else {
        what << "contact points keep hopping between elements";
        // A point that rests on a beam node where two elements meet at an angle (a symmetric push
        // on a node) is pushed along one chord's normal, then the other's (README, Contact).
        const auto hops = std::find_if(state.contacts.begin(), state.contacts.end(),
                                       [](const contact::ContactState& c) { return c.hop_node >= 0; });
        if (hops != state.contacts.end())
          what << " (node " << model.nodes[model.contacts[hops - state.contacts.begin()].node].id
               << " back and forth across beam node " << model.nodes[hops->hop_node].id
               << ": if it rests on that node, move it off, e.g. with an odd number of divisions)";
      }
      out.message = iterate_text(what.str().c_str(), it);
      return out;
    }

    pass = update_residual(state.load_factor);
    const double relative = relative_norm(pass.norms, pass.scale);
    out.residual_norms.push_back(std::isfinite(relative) ? relative : INFINITY);
    if (!std::isfinite(relative) || !pass.finite) {
      out.status = Status::diverged;
      out.message = iterate_text("the unbalanced force is not finite", it);
      return out;
    }
    const std::array<double, 2> largest = largest_displacements(state, applied.largest_free);
    const bool at_round_off = step_size[0] <= round_off_ratio * std::max(model.size, largest[0]) &&
                              step_size[1] <= round_off_ratio * std::max(1.0, largest[1]);
    const bool stagnating = relative >= stagnation * out.residual_norms[out.residual_norms.size() - 2];
    if (relative < stagnation * lowest) lowest = relative, since_lowest = 0;  // halved the best so far: progress
    else ++since_lowest;
    const char* criterion = nullptr;
    bool nothing_carried = false;  // round-off because the structure carries next to nothing
    if (relative <= settings_.tolerance) {
      criterion = "force";
    } else if (!contacts_changed) {
      if (at_round_off && (relative < floor_check_below || (nothing_carried = carries_nothing(pass.scale, state))))
        criterion = "round-off";
      else if (stagnating && relative < floor_check_below && within_floor(pass.norms, state))
        criterion = "round-off";
      else if (relative >= floor_check_below && !resolution_checked && since_lowest >= iterates_without_progress) {
        // Far from the tolerance and no longer falling: if the residual is already at the rounding
        // level of the internal forces, the loads are too small to be resolved against them (6 mN
        // on a knife edge under a 10 m steel beam: its contact force's rounding is ~1e-6 N), and
        // iterating on only ran out of iterations (there the residual cycled, four iterates level
        // and one four times higher). Checked once a step, after iterates_without_progress
        // iterates that did not halve the step's best residual (a pass over the elements:
        // converging steps never get there — checked after three level iterates, the 10⁵ chains'
        // runs paid 8 % for it). A structure that carries nothing (unloaded again) is accepted on
        // round-off once its corrections are: the case above, not this one.
        resolution_checked = true;
        const assembly::RoundingFloor floor = system_.rounding_floor(state.displacements, state.chord_rotations, active_contacts(state));
        if (within_floor(pass.norms, floor) && !carries_nothing(pass.scale, state)) {
          out.status = Status::diverged;
          out.loads_unresolvable = true;
          std::ostringstream os;
          os << "the unbalanced force stays at the rounding level of the internal forces (relative residual "
             << relative << "): the loads are too small against what rounding leaves in this model's forces to be "
             << "resolved (a larger load, in proportion, is)";
          out.message = iterate_text(os.str().c_str(), it);
          // Most of that rounding in one contact's force: say which, and what makes it so stiff.
          // Or in many contacts' forces together: say how many, and the stiffest.
          const bool one = 6.0 * floor.contact_force * floor.contact_force >= 0.5 * floor.force * floor.force;
          const bool together = floor.contacts > 1 && floor.contacts_force * floor.contacts_force >= 0.5 * floor.force * floor.force;
          if (floor.contact_node >= 0 && (one || together)) {
            std::ostringstream contact;
            if (one)
              contact << "; most of that rounding is in the force of the contact at node " << model.nodes[floor.contact_node].id
                      << " (±" << floor.contact_force << ")";
            else
              contact << "; most of that rounding is in the forces of the " << floor.contacts
                      << " contacts in touch (together ±" << floor.contacts_force << "; the largest ±" << floor.contact_force
                      << ", at node " << model.nodes[floor.contact_node].id << ")";
            contact << ", as stiff as the element it touches is at its point (1/c = " << 1.0 / floor.compliance
                    << "; a member far stiffer than what presses on it makes it so)";
            if (floor.at_cap)
              contact << ": that is the contact's cap, \"max_stiffness_ratio\" times the stiffest element holding its "
                         "node (a smaller ratio softens it)";
            else if (floor.at_edge)
              contact << ": the point is at a beam node, where the contact's \"edge\" sets that compliance (a larger "
                         "edge, 0.1 say, softens it)";
            else if (floor.uncapped)
              contact << ": a node no element holds (a rigid pusher) has no stiffness cap; a touched member 100× "
                         "stiffer than what loads it worked in our tests";
            out.message += contact.str();
          }
          return out;
        }
      }
    }
    if (criterion) {
      if (release_pulling_contacts(state)) {  // converged with a contact pulling: iterate on without it
        ++unsettled;
        pass = update_residual(state.load_factor);
        out.contact_iterates.back() = contact_points(state);
        if (switches_ > max_switches) {
          out.status = Status::contact_chatter;
          out.message = iterate_text("contacts keep switching on and off", it);
          return out;
        }
        continue;
      }
      if (contacts_ && contacts_->passed_through(state.displacements, state.chord_rotations, state.contacts)) {
        // A contact released in this step let its node through a beam: it takes part again
        // (the active set needs it), and Newton iterates on; the switch count bounds the cycling.
        ++unsettled;
        switches_ += contacts_->allow_touching_again(state.displacements, state.chord_rotations, state.contacts);
        if (switches_ > max_switches) {
          out.status = Status::contact_chatter;
          out.message = iterate_text("a contact node passed through a beam after its contact was released", it);
          return out;
        }
        evaluate(state, true);
        pass = update_residual(state.load_factor);
        if (contacts_) out.contact_iterates.back() = contact_points(state);
        continue;
      }
      if (eval_.largest_end_rotation > largest_end_rotation) {
        // Eq. 3–5 describe an element by its chord: an end turned past a right angle against it
        // is no state of the beam, but a branch the mesh cannot carry (Newton with a large step
        // can land there, e.g. a beam looped around a contact node). The step fails and is cut back.
        out.status = Status::diverged;
        std::ostringstream os;
        os << "an element end turned " << eval_.largest_end_rotation
           << " rad against its chord, beyond what an element describes (refine the mesh or take smaller steps)";
        out.message = iterate_text(os.str().c_str(), it);
        return out;
      }
      if (const auto [k, element] = contacts_ ? contacts_->blocked(state.contacts) : std::pair{-1, -1}; k >= 0) {
        // Its node lies through an element another contact is on: the state is not acceptable,
        // and no iterate can change that (one contact element per element).
        const int other = contact_on(state, element);
        out.status = Status::diverged;
        std::ostringstream os;
        os << "contact node " << model.nodes[model.contacts[k].node].id << " reached element " << model.elements[element].id
           << ", which contact node " << (other >= 0 ? model.nodes[model.contacts[other].node].id : -1)
           << " is on: one contact per element (give that member more divisions)";
        out.message = iterate_text(os.str().c_str(), it);
        return out;
      }
      out.criterion = criterion;
      out.carried_nothing = nothing_carried;
      for (size_t k = 0; k < state.contacts.size(); ++k)
        if (!state.contacts[k].active && state.contacts[k].slid_off_element >= 0)
          out.slid_off.emplace_back(static_cast<int>(k), state.contacts[k].slid_off_element);
      if (contacts_) contacts_->accept(state.displacements, state.chord_rotations, state.contacts);
      return out;
    }
    if (contacts_changed) {  // a new contact brings its own force level into the step
      start_scale.force = std::max(start_scale.force, pass.scale.force);
      start_scale.moment = std::max(start_scale.moment, pass.scale.moment);
    }
    const double blow_up = relative_norm(pass.norms, start_scale);
    const double runaway =
        std::max(runaway_ratio * (model.size + std::abs(state.load_factor) * prescribed_size), resolvable_move_);
    if (blow_up > blow_up_ratio || largest[0] > runaway) {
      out.status = Status::diverged;
      out.message = iterate_text("the unbalanced force blew up", it);
      return out;
    }
  }
  out.status = Status::max_iterations;
  std::ostringstream os;
  os << "no convergence in " << settings_.max_iterations << " iterations (last relative residual "
     << out.residual_norms.back() << ")";
  if (unsettled > 0) {  // the equilibrium was found, but never with a set of contacts that all press
    os << ": " << unsettled << " converged iterates had a contact pull or a node through a beam, so the set of "
       << "contacts in touch did not settle";
    // Many contacts closing together settle a few per converged iterate: a beam pressed onto
    // another along its length (165 contacts) needed 300 iterations for its first step.
    if (state.contacts.size() > 8)
      os << " (with " << state.contacts.size() << " contact nodes it may settle given more: analysis.max_iterations, now "
         << settings_.max_iterations << ", or smaller steps)";
  }
  out.message = os.str();
  return out;
}

}  // namespace tsm::solver
