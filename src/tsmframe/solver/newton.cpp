#include "tsmframe/solver/newton.hpp"

#include <array>
#include <cmath>
#include <sstream>

namespace tsm::solver {
namespace {

constexpr double round_off_ratio = 1e-12;  // ‖ΔD‖∞ ≤ 1e-12 · max(size, ‖D‖∞) ends a step (FORMAT.md)
constexpr double blow_up_ratio = 1e12;     // ‖R‖ > 1e12 · scale is divergence (FORMULATION §4)
constexpr double runaway_ratio = 1e6;      // |u| > 1e6 · (size + prescribed) is divergence
constexpr double floor_ratio = 10.0;       // ‖R‖ ≤ 10 × the estimated rounding floor …
constexpr double stagnation = 0.5;         // … ends a step once Newton no longer halves it
constexpr double floor_check_below = 1e-3; // the floor (a pass of its own) is only worth checking below this

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
  load_free_.resize(dofs.free_count());
  is_moment_.resize(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq) {
    load_free_[eq] = system.model().reference_load[dofs.dof(eq)];
    is_moment_[eq] = dofs.dof(eq) % dofs_per_node == rz ? 1 : 0;
  }
  const Model& model = system.model();
  constrained_.resize(model.dof_count());
  for (int dof = 0; dof < model.dof_count(); ++dof) {
    constrained_[dof] = model.constrained[dof] ? 1 : 0;
    if (constrained_[dof]) constrained_dofs_.push_back(dof);
    if (dof % dofs_per_node != rz) prescribed_squared_ += model.reference_prescribed[dof] * model.reference_prescribed[dof];
  }
  solver_.analyze(system.dofs(), system.tangent());
  analysed_pattern_ = system.pattern_version();
}

bool NewtonSolver::evaluate(State& state) {
  const Model& model = system_.model();
  for (int dof : constrained_dofs_) state.displacements[dof] = state.load_factor * model.reference_prescribed[dof];
  constexpr int max_passes = 4;  // contact changes settled per iterate before Newton goes on
  bool changed = false;
  for (int pass = 0;; ++pass) {
    const std::vector<contact::ActiveContact> active =
        contacts_ ? contacts_->active_contacts(state.contacts) : std::vector<contact::ActiveContact>();
    system_.evaluate(state.displacements, state.chord_rotations, true, eval_, active);
    state.chord_rotations = eval_.chord_rotations;
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
  size_t next = 0;
  for (contact::ContactState& c : state.contacts) {
    if (!c.active || next >= eval_.contacts.size()) continue;
    c.alpha = eval_.contacts[next].alpha;
    c.Y = eval_.contacts[next++].Y;
    c.force = -c.side * c.Y;
  }
  return changed;
}

bool NewtonSolver::release_pulling_contacts(State& state) {
  if (!contacts_) return false;
  const contact::ContactChanges changes =
      contacts_->update(state.displacements, state.chord_rotations, eval_.contacts, state.contacts, true);
  if (!changes.any()) return false;
  switches_ += changes.activated + changes.released;
  evaluate(state);
  return true;
}

void NewtonSolver::reset(State& state) { evaluate(state); }

std::vector<ContactPoint> NewtonSolver::contact_points(const State& state) const {
  std::vector<ContactPoint> points;
  for (const contact::ContactState& c : state.contacts) {
    ContactPoint p;
    if (c.active) p = {c.element, c.alpha, c.force, c.Y};
    points.push_back(p);
  }
  return points;
}

Eigen::VectorXd NewtonSolver::unbalanced_force(double load_factor) const {
  const assembly::DofMap& dofs = system_.dofs();
  Eigen::VectorXd R(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq)
    R[eq] = load_factor * load_free_[eq] - eval_.internal_force[dofs.dof(eq)];
  return R;
}

Eigen::VectorXd NewtonSolver::reactions(double load_factor) const {
  const Model& model = system_.model();
  Eigen::VectorXd reactions = Eigen::VectorXd::Zero(model.dof_count());
  for (int dof : constrained_dofs_) reactions[dof] = eval_.internal_force[dof] - load_factor * model.reference_load[dof];
  return reactions;
}

ResidualScale NewtonSolver::scale(double load_factor) const {
  // Squared sums per kind: applied loads on free dofs, reactions, internal forces on all dofs.
  const Model& model = system_.model();
  const double* F = eval_.internal_force.data();
  const double* P = model.reference_load.data();
  double load[2] = {0, 0}, reaction[2] = {0, 0}, internal[2] = {0, 0};
  for (int node = 0; node < model.node_count(); ++node) {
    for (int d = 0; d < dofs_per_node; ++d) {
      const int dof = dofs_per_node * node + d, kind = d == rz ? 1 : 0;
      const double f = F[dof], p = load_factor * P[dof];
      internal[kind] += f * f;
      if (constrained_[dof]) reaction[kind] += (f - p) * (f - p);
      else load[kind] += p * p;
    }
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

bool NewtonSolver::at_round_off(const Eigen::VectorXd& correction, const State& state) const {
  double largest[2] = {0, 0}, step[2] = {0, 0};
  const double* D = state.displacements.data();
  for (Eigen::Index node = 0; node < state.displacements.size() / dofs_per_node; ++node) {
    largest[0] = std::max({largest[0], std::abs(D[3 * node]), std::abs(D[3 * node + 1])});
    largest[1] = std::max(largest[1], std::abs(D[3 * node + 2]));
  }
  for (Eigen::Index eq = 0; eq < correction.size(); ++eq)
    step[is_moment_[eq]] = std::max(step[is_moment_[eq]], std::abs(correction[eq]));
  return step[0] <= round_off_ratio * std::max(system_.model().size, largest[0]) &&
         step[1] <= round_off_ratio * std::max(1.0, largest[1]);
}

double NewtonSolver::arc_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  double sum = 0.0;
  for (Eigen::Index eq = 0; eq < a.size(); ++eq)
    if (!is_moment_[eq]) sum += a[eq] * b[eq];
  return sum;
}

Eigen::VectorXd NewtonSolver::free_displacements(const State& state) const {
  const assembly::DofMap& dofs = system_.dofs();
  Eigen::VectorXd v(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq) v[eq] = state.displacements[dofs.dof(eq)];
  return v;
}

bool NewtonSolver::within_floor(const std::array<double, 2>& norms, const State& state) const {
  const auto [force, moment] = norms;
  const std::vector<contact::ActiveContact> active =
      contacts_ ? contacts_->active_contacts(state.contacts) : std::vector<contact::ActiveContact>();
  const assembly::RoundingFloor floor = system_.rounding_floor(state.displacements, state.chord_rotations, active);
  return force <= floor_ratio * floor.force && moment <= floor_ratio * floor.moment;
}

NewtonOutcome NewtonSolver::step(const PathConstraint& constraint, State& state) {
  const assembly::DofMap& dofs = system_.dofs();
  const Model& model = system_.model();
  const double prescribed_size = model.reference_prescribed.lpNorm<Eigen::Infinity>();
  NewtonOutcome out;
  Eigen::VectorXd R = unbalanced_force(state.load_factor);
  ResidualScale start_scale;
  switches_ = reversals_ = 0;
  const bool by_arc = constraint.kind == PathConstraint::Kind::arc_length;
  const Eigen::VectorXd start = by_arc ? free_displacements(state) : Eigen::VectorXd();
  const double start_load_factor = state.load_factor;
  const int max_switches = 4 + 4 * static_cast<int>(state.contacts.size());
  // A contact point that keeps hopping back and forth between elements within one step is
  // wandering over iterates far from the path (it may land on another branch, a beam looped
  // around the node): fail the step so that cutback follows the path in smaller steps. Sliding
  // on in one direction, one element per iterate, is not limited here.
  const int max_reversals = 4 * static_cast<int>(state.contacts.size());
  if (contacts_) out.contact_iterates.push_back(contact_points(state));

  for (int it = 1; it <= settings_.max_iterations; ++it) {
    if (system_.pattern_version() != analysed_pattern_) {  // a contact has joined new nodes
      solver_.analyze(system_.dofs(), system_.tangent());
      analysed_pattern_ = system_.pattern_version();
    }
    if (!solver_.factorize(system_.tangent(), system_.contact_rank_one())) {
      out.status = Status::singular;
      out.message = iterate_text("the tangent stiffness is singular (a limit or bifurcation point)", it);
      return out;
    }
    // dR/dλ = F_ref − K_fp D_p,ref: how the load factor drives the free dofs.
    const Eigen::VectorXd load_direction = load_free_ - eval_.prescribed_coupling;
    double dlambda = 0.0;
    Eigen::VectorXd correction;
    if (constraint.kind == PathConstraint::Kind::load_increment) {
      if (it == 1) dlambda = constraint.load_increment;
      correction = solver_.solve(R + dlambda * load_direction);
    } else if (by_arc) {
      // δD = δD_R + δλ δD_F; δλ from the arc-length constraint (Crisfield's cylindrical form).
      const Eigen::VectorXd a = solver_.solve(load_direction), b = solver_.solve(R);
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
        const Eigen::VectorXd increment = free_displacements(state) - start;
        const double dl = state.load_factor - start_load_factor;
        const Eigen::VectorXd u = increment + b;
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
        auto turn = [&](double r) { return arc_dot(increment, u + r * a) + dl * (dl + r) * P2; };
        dlambda = turn(r1) >= turn(r2) ? r1 : r2;
      }
      correction = b + dlambda * a;
    } else {
      const Eigen::VectorXd a = solver_.solve(load_direction), b = solver_.solve(R);
      const int k = constraint.equation;
      if (!(std::abs(a[k]) > 0.0) || !std::isfinite(a[k])) {
        out.status = Status::singular;
        out.message = iterate_text("the controlled dof does not move under the load", it);
        return out;
      }
      dlambda = (constraint.target - state.displacements[dofs.dof(k)] - b[k]) / a[k];
      correction = b + dlambda * a;
    }
    if (it == 1) {  // iterate 0: the out-of-balance force that drives the step
      start_scale = scale(state.load_factor + dlambda);
      out.residual_norms.push_back(relative_norm(kind_norms(R + dlambda * load_direction), start_scale));
    }
    out.iterations = it;
    if (!correction.allFinite() || !std::isfinite(dlambda)) {
      out.status = Status::diverged;
      out.message = iterate_text("the Newton correction is not finite", it);
      return out;
    }
    for (int eq = 0; eq < dofs.free_count(); ++eq) state.displacements[dofs.dof(eq)] += correction[eq];
    state.load_factor += dlambda;
    const bool contacts_changed = evaluate(state);
    if (contacts_) out.contact_iterates.push_back(contact_points(state));
    if (switches_ > max_switches || reversals_ > max_reversals) {
      out.status = Status::contact_chatter;
      out.message = iterate_text(switches_ > max_switches ? "contacts keep switching on and off"
                                                          : "contact points keep hopping between elements", it);
      return out;
    }

    R = unbalanced_force(state.load_factor);
    const std::array<double, 2> norms = kind_norms(R);
    const double relative = relative_norm(norms, scale(state.load_factor));
    out.residual_norms.push_back(std::isfinite(relative) ? relative : INFINITY);
    if (!std::isfinite(relative) || !eval_.internal_force.allFinite()) {
      out.status = Status::diverged;
      out.message = iterate_text("the unbalanced force is not finite", it);
      return out;
    }
    const bool stagnating = relative >= stagnation * out.residual_norms[out.residual_norms.size() - 2];
    const char* criterion = relative <= settings_.tolerance ? "force"
                            : !contacts_changed && (at_round_off(correction, state) || (stagnating && relative < floor_check_below && within_floor(norms, state)))
                                ? "round-off"
                                : nullptr;
    if (criterion) {
      if (release_pulling_contacts(state)) {  // converged with a contact pulling: iterate on without it
        R = unbalanced_force(state.load_factor);
        out.contact_iterates.back() = contact_points(state);
        if (switches_ > max_switches) {
          out.status = Status::contact_chatter;
          out.message = iterate_text("contacts keep switching on and off", it);
          return out;
        }
        continue;
      }
      if (contacts_ && contacts_->passed_through(state.displacements, state.chord_rotations, state.contacts)) {
        out.status = Status::diverged;
        out.message = iterate_text("a contact node passed through a beam after its contact was released", it);
        return out;
      }
      out.criterion = criterion;
      if (contacts_) contacts_->accept(state.displacements, state.chord_rotations, state.contacts);
      return out;
    }
    if (contacts_changed) {  // a new contact brings its own force level into the step
      const ResidualScale now = scale(state.load_factor);
      start_scale.force = std::max(start_scale.force, now.force);
      start_scale.moment = std::max(start_scale.moment, now.moment);
    }
    const double blow_up = relative_norm(norms, start_scale);
    double largest = 0.0;
    for (int dof = 0; dof < model.dof_count(); dof += dofs_per_node)
      largest = std::max({largest, std::abs(state.displacements[dof]), std::abs(state.displacements[dof + 1])});
    if (blow_up > blow_up_ratio ||
        largest > runaway_ratio * (model.size + std::abs(state.load_factor) * prescribed_size)) {
      out.status = Status::diverged;
      out.message = iterate_text("the unbalanced force blew up", it);
      return out;
    }
  }
  out.status = Status::max_iterations;
  std::ostringstream os;
  os << "no convergence in " << settings_.max_iterations << " iterations (last relative residual "
     << out.residual_norms.back() << ")";
  out.message = os.str();
  return out;
}

}  // namespace tsm::solver
