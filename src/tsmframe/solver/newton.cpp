#include "tsmframe/solver/newton.hpp"

#include <cmath>
#include <optional>
#include <utility>

namespace tsm::solver {
namespace {

// The problem's optional tangent terms — the contacts' sliding terms (FORMULATION §2) — join the
// solve only once the relative residual is below this (and in a step's first solve, from a
// converged state). Far from it the point hops between short elements, where ∂k0/∂α is large and
// changes from element to element, and the consistent tangent sends Newton farther off than the
// symmetric part alone (bench/README.md, a push over 10⁴ elements). Near the solution the terms
// bring back quadratic convergence.
constexpr double sliding_terms_below = 1e-2;

// Far from the solution by that measure (Problem::evaluate, Proximity).
Proximity proximity_of(const NewtonOutcome& out) {
  return out.residual_norms.back() < sliding_terms_below ? Proximity::near : Proximity::far;
}

StepFailure failure_of(StepFailure::Reason reason) {
  StepFailure failure;
  failure.reason = reason;
  return failure;
}

}  // namespace

NewtonSolver::NewtonSolver(Problem& problem, const NewtonSettings& settings)
    : problem_(problem), settings_(settings), passes_(problem), path_(passes_), test_(problem, settings.tolerance) {}

NewtonOutcome& NewtonSolver::fail(NewtonOutcome& out, StepFailure failure, int iteration) {
  failure.iteration = iteration;
  out.failure = std::move(failure);
  out.status = step_status(out.failure);
  return out;
}

NewtonOutcome NewtonSolver::step(const PathConstraint& constraint, State& state) {
  NewtonOutcome out = iterate(constraint, state);
  if (out.status != Status::converged) {
    problem_.explain(state, out.failure);
    // A blow-up from the unloaded state that the explanation finds to be a mechanism is one.
    if (out.failure.reason == StepFailure::Reason::mechanism) out.status = step_status(out.failure);
  }
  return out;
}

PathCorrection NewtonSolver::solve(const PathConstraint& constraint, int iteration, const State& state,
                                   NewtonOutcome& out, Eigen::VectorXd*& correction) {
  const bool with_optional_terms = iteration == 1 || proximity_of(out) == Proximity::near;
  const auto factorized = [&](const Factorisation f) {
    if (f.ok && iteration == 1) out.start_rounded = f.rounded;
    if (f.ok && f.negative_pivots >= 0) {
      if (iteration == 1) out.start_negative_pivots = f.negative_pivots;
      else out.most_negative_pivots = std::max(out.most_negative_pivots, f.negative_pivots);
    }
    return f.ok;
  };
  if (constraint.kind == PathConstraint::Kind::load_increment) {
    // R is not needed after the solve (the next iterate recomputes it): the correction
    // overwrites it, one vector of the model's size less; and the right-hand side is known
    // before the factorisation, which carries its forward substitution along.
    correction = &residual_;
    const double dlambda = iteration == 1 ? constraint.load_increment : 0.0;
    if (dlambda != 0.0) passes_.add_load_direction(dlambda, residual_);
    if (iteration == 1) drive_norms_ = passes_.kind_norms(residual_);
    if (!factorized(problem_.factorize(state, with_optional_terms, &residual_, iteration == 1)))
      return {0.0, StepFailure::Reason::singular_tangent};
    return {dlambda};
  }
  correction = &correction_;
  if (!factorized(problem_.factorize(state, with_optional_terms, nullptr, iteration == 1))) return {0.0, StepFailure::Reason::singular_tangent};
  // δD = δD_R + δλ δD_F: K⁻¹ F_dir into along_load_ and K⁻¹ R into along_residual_.
  passes_.load_direction(along_load_);
  problem_.solve_in_place(along_load_);
  along_residual_ = residual_;
  problem_.solve_in_place(along_residual_);
  const PathCorrection c = path_.correction(constraint, iteration, along_load_, along_residual_, state);
  if (c.failure == StepFailure::Reason::none) correction_ = along_residual_ + c.dlambda * along_load_;
  return c;
}

void NewtonSolver::measure_start(const PathConstraint& constraint, double dlambda, const Eigen::VectorXd& correction,
                                 const State& state, NewtonOutcome& out) {
  if (dlambda != 0.0) {
    const double moved = std::sqrt(passes_.translation_dot(correction, correction));
    if (moved > 0.0) out.start_stiffness = std::abs(dlambda) / moved;
  }
  // Iterate 0: the out-of-balance force that drives the step, at the target λ.
  const ResidualScale scale = dlambda == 0.0 ? pass_.scale : passes_.scale(state.load_factor + dlambda);
  std::array<double, 2> drive = drive_norms_;
  if (constraint.kind != PathConstraint::Kind::load_increment) {  // R is still the step's start
    drive_ = residual_;
    passes_.add_load_direction(dlambda, drive_);
    drive = passes_.kind_norms(drive_);
  }
  out.residual_norms.push_back(test_.set_step_scale(scale, drive));
}

NewtonOutcome NewtonSolver::iterate(const PathConstraint& constraint, State& state) {
  using Reason = StepFailure::Reason;
  NewtonOutcome out;
  pass_ = passes_.update(state.load_factor, residual_);
  problem_.begin_step(state);
  test_.begin_step();
  path_.begin_step(constraint, state);
  drive_norms_ = {};
  been_near_ = false;
  if (problem_.has_contacts()) out.contact_iterates.push_back(problem_.contact_points(state));
  int unsettled = 0;  // iterates that met the criterion but changed the contacts (iterating on)

  for (int it = 1; it <= settings_.max_iterations; ++it) {
    // --- solve: the tangent, the path's δλ and the correction
    Eigen::VectorXd* correction = nullptr;
    const PathCorrection path = solve(constraint, it, state, out, correction);
    if (path.failure != Reason::none) return fail(out, failure_of(path.failure), it);
    if (it == 1) measure_start(constraint, path.dlambda, *correction, state, out);
    out.iterations = it;
    // Cut short where contacts would land deep (landing.hpp); δλ with it unless the load
    // increment is already in the residual (load control).
    PathCorrection taken = path;
    const double fraction = problem_.step_fraction(state, *correction);
    if (fraction < 1.0) {
      *correction *= fraction;
      if (constraint.kind != PathConstraint::Kind::load_increment) taken.dlambda *= fraction;
    }

    // --- update: applied first, checked after (in the same pass); a failed step's state is
    // restored by the caller. A step cut short is judged by the correction Newton asked for: a
    // small part of a large one is no correction at round-off.
    AppliedCorrection applied = passes_.apply(*correction, state);
    if (fraction < 1.0) applied.size = {applied.size[0] / fraction, applied.size[1] / fraction};
    if (!std::isfinite(applied.size[0]) || !std::isfinite(taken.dlambda)) return fail(out, failure_of(Reason::correction_not_finite), it);
    state.load_factor += taken.dlambda;

    // --- the structure at the iterate (its contacts settled there)
    // Near once, near for the rest of the step: the structure's far and near models (contacts
    // along their chords' normals or the bent beams') differ by Y·w', which on a beam bent at
    // element scale is above the 10⁻² that tells far from near, and they would take turns.
    been_near_ = been_near_ || proximity_of(out) == Proximity::near;
    const bool contacts_changed = problem_.evaluate(state, been_near_ ? Proximity::near : Proximity::far);
    if (problem_.has_contacts()) out.contact_iterates.push_back(problem_.contact_points(state));
    if (const std::optional<StepFailure> failure = problem_.after_iterate(state)) return fail(out, *failure, it);

    // --- convergence
    pass_ = passes_.update(state.load_factor, residual_);
    const double relative = relative_norm(pass_.norms, pass_.scale);
    out.residual_norms.push_back(std::isfinite(relative) ? relative : INFINITY);
    if (!std::isfinite(relative) || !pass_.finite) return fail(out, failure_of(Reason::residual_not_finite), it);
    const IterateFacts facts{relative, out.residual_norms[out.residual_norms.size() - 2], pass_, applied.size,
                             passes_.largest_displacements(state, applied.largest_free), contacts_changed};
    const Verdict verdict = test_.judge(facts, state);
    if (verdict.loads_unresolvable) {
      StepFailure failure = failure_of(Reason::loads_unresolvable);
      failure.relative_residual = relative;
      failure.floor = verdict.floor;
      return fail(out, std::move(failure), it);
    }
    if (verdict.criterion != Criterion::none) {
      been_near_ = true;  // balanced: whatever comes of the contacts, near
      const Settlement settlement = problem_.at_convergence(state);
      if (settlement.evaluated_again) {
        pass_ = passes_.update(state.load_factor, residual_);
        if (problem_.has_contacts()) out.contact_iterates.back() = problem_.contact_points(state);
      }
      if (settlement.kind == Settlement::Kind::failed) return fail(out, settlement.failure, it);
      if (settlement.kind == Settlement::Kind::iterate_on) {
        ++unsettled;
        continue;
      }
      out.criterion = verdict.criterion;
      out.slid_off = problem_.accept(state);
      return out;
    }
    if (contacts_changed) test_.widen_step_scale(pass_.scale);  // a new contact brings its own force level
    if (test_.diverged(facts, state.load_factor)) return fail(out, failure_of(Reason::blew_up), it);
  }
  StepFailure failure = failure_of(Reason::max_iterations);
  failure.relative_residual = out.residual_norms.back();
  failure.unsettled = unsettled;
  failure.contact_nodes = static_cast<int>(state.contacts.size());
  return fail(out, std::move(failure), settings_.max_iterations);
}

}  // namespace tsm::solver
