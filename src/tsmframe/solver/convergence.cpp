#include "tsmframe/solver/convergence.hpp"

#include <algorithm>
#include <limits>

namespace tsm::solver {
namespace {

constexpr double round_off_ratio = 1e-12;  // ‖ΔD‖∞ ≤ 1e-12 · max(size, ‖D‖∞) ends a step (docs/format.md)
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
constexpr int iterates_without_progress = 5;  // then a residual far from the tolerance is held against the floor

}  // namespace

double resolvable_move(double shortest_element) {
  return chord_resolution * shortest_element / std::numeric_limits<double>::epsilon();
}

bool within_floor(const std::array<double, 2>& norms, const assembly::RoundingFloor& floor) {
  const auto [force, moment] = norms;
  return force <= floor_ratio * floor.force && moment <= floor_ratio * floor.moment;
}

void ConvergenceTest::begin_step() {
  step_scale_ = {};
  resolution_checked_ = false;
  lowest_ = INFINITY;
  since_lowest_ = 0;
}

double ConvergenceTest::set_step_scale(ResidualScale scale, const std::array<double, 2>& drive) {
  // The drive is a force level of the step too: a step that only moves supports of an
  // unstressed structure has no other (no loads, no internal forces yet), and its iterates
  // would be measured against nothing (a blow-up at once).
  scale.force = std::max(scale.force, drive[0]);
  scale.moment = std::max(scale.moment, drive[1]);
  step_scale_ = scale;
  return relative_norm(drive, step_scale_);
}

void ConvergenceTest::widen_step_scale(const ResidualScale& scale) {
  step_scale_.force = std::max(step_scale_.force, scale.force);
  step_scale_.moment = std::max(step_scale_.moment, scale.moment);
}

Verdict ConvergenceTest::judge(const IterateFacts& iterate, const State& state) {
  const double relative = iterate.relative;
  const double size = problem_.equations().size;
  const bool at_round_off = iterate.correction[0] <= round_off_ratio * std::max(size, iterate.largest[0]) &&
                            iterate.correction[1] <= round_off_ratio * std::max(1.0, iterate.largest[1]);
  const bool stagnating = relative >= stagnation * iterate.previous;
  if (relative < stagnation * lowest_) lowest_ = relative, since_lowest_ = 0;  // halved the best so far: progress
  else ++since_lowest_;
  Verdict verdict;
  if (relative <= tolerance_) {
    verdict.criterion = Criterion::force;
    return verdict;
  }
  if (iterate.contacts_changed) return verdict;
  if (at_round_off && relative < floor_check_below) {
    verdict.criterion = Criterion::round_off;
  } else if (at_round_off && carries_nothing(iterate.residual.scale, state)) {
    verdict.criterion = Criterion::nothing_carried;
  } else if (stagnating && relative < floor_check_below &&
             within_floor(iterate.residual.norms, problem_.rounding_floor(state, true))) {
    verdict.criterion = Criterion::round_off;
  } else if (relative >= floor_check_below && !resolution_checked_ && since_lowest_ >= iterates_without_progress) {
    // Far from the tolerance and no longer falling: if the residual is already at the rounding
    // level of the internal forces, the loads are too small to be resolved against them (6 mN
    // on a knife edge under a 10 m steel beam: its contact force's rounding is ~1e-6 N), and
    // iterating on only ran out of iterations (there the residual cycled, four iterates level
    // and one four times higher). Checked once a step, after iterates_without_progress
    // iterates that did not halve the step's best residual (a pass over the elements:
    // converging steps never get there — checked after three level iterates, the 10⁵ chains'
    // runs paid 8 % for it). A structure that carries nothing (unloaded again) is accepted on
    // round-off once its corrections are: the case above, not this one.
    resolution_checked_ = true;
    verdict.floor = problem_.rounding_floor(state, true);
    verdict.loads_unresolvable =
        within_floor(iterate.residual.norms, verdict.floor) && !carries_nothing(iterate.residual.scale, state);
  }
  return verdict;
}

bool ConvergenceTest::diverged(const IterateFacts& iterate, double load_factor) const {
  const Equations& equations = problem_.equations();
  const double blow_up = relative_norm(iterate.residual.norms, step_scale_);
  const double runaway = std::max(runaway_ratio * (equations.size + std::abs(load_factor) * equations.prescribed_size),
                                  equations.resolvable_move);
  return blow_up > blow_up_ratio || iterate.largest[0] > runaway;
}

bool ConvergenceTest::carries_nothing(const ResidualScale& scale, const State& state) const {
  const assembly::RoundingFloor floor = problem_.rounding_floor(state, false);
  // Forces at rounding level leave moments at that level times a lever up to the model's size:
  // a ring moved as a rigid body by a prescribed displacement (61 elements, EI 2e3) had its
  // moments at 2.6e-8, ten times its elements' own moment floor, from its forces' 1e-6.
  const double moment_floor = std::max(floor.moment, floor.force * problem_.equations().size);
  return scale.force <= floor_ratio * floor.force && scale.moment <= floor_ratio * moment_floor;
}

}  // namespace tsm::solver
