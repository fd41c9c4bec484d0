#include "tsmframe/solver/limit_point.hpp"

#include <algorithm>
#include <cmath>

namespace tsm::solver {

int monotone_equation(const Eigen::VectorXd& before, const Eigen::VectorXd& after, const Eigen::VectorXd& scale) {
  int best = -1;
  double most = 0.0;
  for (Eigen::Index eq = 0; eq < std::min(before.size(), after.size()); ++eq) {
    if (before[eq] * after[eq] <= 0.0 || scale[eq] == 0.0) continue;
    const double moved = scale[eq] * std::min(std::abs(before[eq]), std::abs(after[eq]));
    if (moved > most) most = moved, best = static_cast<int>(eq);
  }
  return best;
}

namespace {

/// The vertex of the parabola through (a, fa), (b, fb), (c, fc); NaN where they are in a line.
double parabola_vertex(double a, double fa, double b, double fb, double c, double fc) {
  const double p = (b - a) * (fb - fc), q = (b - c) * (fb - fa);
  const double denominator = p - q;
  if (denominator == 0.0) return std::nan("");
  return b - 0.5 * ((b - a) * p - (b - c) * q) / denominator;
}

}  // namespace

std::optional<RefinedLimit> refine_limit_point(const LimitBracket& bracket, const State& start,
                                               const assembly::DofMap& dofs, NewtonSolver& newton) {
  // f = ±λ, so that the search is for a maximum; points kept ascending in u.
  const double sign = bracket.maximum ? 1.0 : -1.0;
  std::array<double, 3> u = bracket.u, f;
  for (int k = 0; k < 3; ++k) f[k] = sign * bracket.load_factor[k];
  if (u[0] > u[2]) std::swap(u[0], u[2]), std::swap(f[0], f[2]);
  RefinedLimit refined{bracket.step, bracket.load_factor[1], dofs.dof(bracket.equation), u[1], 0};
  PathConstraint control;
  control.kind = PathConstraint::Kind::displacement_target;
  control.equation = bracket.equation;
  constexpr int most_evaluations = 16;
  for (int n = 0; n < most_evaluations; ++n) {
    double v = parabola_vertex(u[0], f[0], u[1], f[1], u[2], f[2]);
    if (!(v > u[0] && v < u[2]) || v == u[1])  // the larger side's middle where the parabola does not help
      v = u[1] - u[0] > u[2] - u[1] ? 0.5 * (u[0] + u[1]) : 0.5 * (u[1] + u[2]);
    State trial = start;
    newton.reset(trial);
    control.target = v;
    if (newton.step(control, trial).status != Status::converged) return std::nullopt;
    ++refined.evaluations;
    const double fv = sign * trial.load_factor, best = f[1];
    if (fv > f[1]) {  // the new best: the bracket closes around it
      if (v < u[1]) u = {u[0], v, u[1]}, f = {f[0], fv, f[1]};
      else u = {u[1], v, u[2]}, f = {f[1], fv, f[2]};
    } else {
      if (v < u[1]) u[0] = v, f[0] = fv;
      else u[2] = v, f[2] = fv;
    }
    refined.load_factor = sign * f[1];
    refined.value = u[1];
    // The trial lands on the flat top: within the tolerance of the best λ found before it.
    if (std::abs(fv - best) <= limit_point_tolerance * std::abs(fv)) return refined;
  }
  return refined;
}

}  // namespace tsm::solver
