#include "tsmframe/solver/unbalanced_force.hpp"

#include <algorithm>
#include <cmath>

#include "tsmframe/model/model.hpp"
#include "tsmframe/util/chunked_reduce.hpp"
#include "tsmframe/util/first_touch.hpp"

namespace tsm::solver {
namespace {

// Equations run in elimination order, the model's vectors in node order: a loop over the
// equations reads them in runs (a member's nodes) with jumps between, and each jump misses the
// cache (a frame lattice's most). Each loop fetches the entry this many equations ahead — in
// models whose vectors outgrow the core's caches (from 2¹⁵ equations, 256 kB a vector): below,
// the extra instructions cost more than they save. Written out in each loop: GCC drops a call to
// a helper that only prefetches (no side effects, so a dead call), and the prefetch with it.
constexpr Eigen::Index gather_ahead = 32;
constexpr Eigen::Index gather_from = Eigen::Index{1} << 15;

/// The load applied at a dof: λ P, plus what earlier stages left (dead; null: none).
inline double applied(double load_factor, const double* P, const double* dead, int dof) {
  return dead ? load_factor * P[dof] + dead[dof] : load_factor * P[dof];
}

}  // namespace

const double* UnbalancedForce::dead_load() const {
  const Eigen::VectorXd& dead = problem_.dead_load();
  return dead.size() > 0 ? dead.data() : nullptr;
}

ResidualScale UnbalancedForce::scale(double load_factor) const {
  // As in update_residual, without writing R (the scale at a λ other than the state's).
  const double* F = problem_.internal_force().data();
  const double* P = problem_.reference_load().data();
  const double* dead = dead_load();
  const int* free_dof = equations_.free_dofs.data();
  const unsigned char* is_moment = equations_.is_moment.data();
  const bool gather = equations_.free_count() >= gather_from;
  const std::array<double, 4> free =
      util::chunked_reduce<4>(equations_.free_count(), [&](Eigen::Index begin, Eigen::Index end, std::array<double, 4>& sum) {
        for (Eigen::Index eq = begin; eq < end; ++eq) {
          if (gather && eq + gather_ahead < end) {
            __builtin_prefetch(F + free_dof[eq + gather_ahead]);
            __builtin_prefetch(P + free_dof[eq + gather_ahead]);
          }
          const int dof = free_dof[eq], kind = is_moment[eq];
          const double f = F[dof], p = applied(load_factor, P, dead, dof);
          sum[kind] += p * p;
          sum[2 + kind] += f * f;
        }
      });
  return scale_from({free[0], free[1]}, {free[2], free[3]}, load_factor);
}

ResidualScale UnbalancedForce::scale_from(std::array<double, 2> load, std::array<double, 2> internal, double load_factor) const {
  // Squared sums per kind: applied loads on free dofs (given), reactions, internal forces on all
  // dofs (given over the free ones; the constrained ones are added here).
  const double* F = problem_.internal_force().data();
  const double* P = problem_.reference_load().data();
  const double* dead = dead_load();
  double reaction[2] = {0, 0};
  for (const int dof : equations_.constrained_dofs) {
    const int kind = dof % dofs_per_node == rz ? 1 : 0;
    const double f = F[dof], p = applied(load_factor, P, dead, dof);
    internal[kind] += f * f;
    reaction[kind] += (f - p) * (f - p);
  }
  ResidualScale s;
  s.force = std::sqrt(std::max({load[0], reaction[0], internal[0]}));
  s.moment = std::sqrt(std::max({load[1], reaction[1], internal[1]}));
  // A structure loaded only by forces (or only by moments) still has a scale for the other kind.
  const double force = s.force;
  s.force = std::max(s.force, s.moment / equations_.size);
  s.moment = std::max(s.moment, force * equations_.size);
  return s;
}

ResidualPass UnbalancedForce::update(double load_factor, Eigen::VectorXd& residual) const {
  const Eigen::Index n = equations_.free_count();
  util::resize_touched(residual, n);
  const double* F = problem_.internal_force().data();
  const double* P = problem_.reference_load().data();
  const double* dead = dead_load();
  const int* free_dof = equations_.free_dofs.data();
  const unsigned char* is_moment = equations_.is_moment.data();
  double* R = residual.data();
  const bool gather = n >= gather_from;
  // Squared sums per kind (forces, moments) over the free equations: R, applied loads, internal forces.
  const std::array<double, 6> free = util::chunked_reduce<6>(n, [=](Eigen::Index begin, Eigen::Index end, std::array<double, 6>& sum) {
    // Six running sums in registers, not an array indexed by the kind: through memory every
    // term would wait for the previous one's store. The other kind's sum gains +0.0 (exact).
    double r0 = 0.0, r1 = 0.0, p0 = 0.0, p1 = 0.0, f0 = 0.0, f1 = 0.0;
    for (Eigen::Index eq = begin; eq < end; ++eq) {
      if (gather && eq + gather_ahead < end) {
        __builtin_prefetch(F + free_dof[eq + gather_ahead]);
        __builtin_prefetch(P + free_dof[eq + gather_ahead]);
      }
      const int dof = free_dof[eq];
      const bool moment = is_moment[eq] != 0;
      const double f = F[dof], p = applied(load_factor, P, dead, dof), r = p - f;
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
  for (const int dof : equations_.constrained_dofs) constrained += F[dof];
  pass.finite = std::isfinite(free[0] + free[1] + free[4] + free[5] + constrained);
  return pass;
}

void UnbalancedForce::load_direction(Eigen::VectorXd& out) const {
  const double* P = problem_.reference_load().data();
  out.resize(equations_.free_count());
  for (int eq = 0; eq < equations_.free_count(); ++eq) out[eq] = P[equations_.free_dofs[eq]];
  if (problem_.prescribed_coupling().size() > 0) out -= problem_.prescribed_coupling();
}

void UnbalancedForce::add_load_direction(double dlambda, Eigen::VectorXd& v) const {
  const double* P = problem_.reference_load().data();
  for (int eq = 0; eq < equations_.free_count(); ++eq) v[eq] += dlambda * P[equations_.free_dofs[eq]];
  if (problem_.prescribed_coupling().size() > 0) v -= dlambda * problem_.prescribed_coupling();
}

std::array<double, 2> UnbalancedForce::kind_norms(const Eigen::VectorXd& v) const {
  double sum[2] = {0, 0};
  for (Eigen::Index eq = 0; eq < v.size(); ++eq) sum[equations_.is_moment[eq]] += v[eq] * v[eq];
  return {std::sqrt(sum[0]), std::sqrt(sum[1])};
}

double relative_norm(const std::array<double, 2>& norms, const ResidualScale& s) {
  const auto [force, moment] = norms;
  if (s.force == 0.0 && s.moment == 0.0) return force + moment == 0.0 ? 0.0 : INFINITY;
  return std::max(force / s.force, moment / s.moment);
}

AppliedCorrection UnbalancedForce::apply(const Eigen::VectorXd& correction, State& state) const {
  const int* free_dof = equations_.free_dofs.data();
  const unsigned char* is_moment = equations_.is_moment.data();
  double* D = state.displacements.data();
  const bool gather = correction.size() >= gather_from;
  // Maxima (the same whatever the order) of |c| and |D| per kind, and a fifth entry 1 where a
  // chunk's c is not finite (a NaN would pass through the maxima unnoticed).
  const std::array<double, 5> most = util::chunked_reduce<5>(
      correction.size(),
      [&](Eigen::Index begin, Eigen::Index end, std::array<double, 5>& m) {
        double translation = 0.0, rotation = 0.0, largest_translation = 0.0, largest_rotation = 0.0;
        bool finite = true;
        for (Eigen::Index eq = begin; eq < end; ++eq) {
          if (gather && eq + gather_ahead < end) __builtin_prefetch(D + free_dof[eq + gather_ahead], 1);
          const double c = correction[eq], d = D[free_dof[eq]] + c;
          D[free_dof[eq]] = d;
          finite = finite && std::isfinite(c);
          if (is_moment[eq]) {
            rotation = std::max(rotation, std::abs(c));
            largest_rotation = std::max(largest_rotation, std::abs(d));
          } else {
            translation = std::max(translation, std::abs(c));
            largest_translation = std::max(largest_translation, std::abs(d));
          }
        }
        m = {translation, rotation, largest_translation, largest_rotation, finite ? 0.0 : 1.0};
      },
      util::Larger{});
  if (most[4] != 0.0) return {{NAN, NAN}, {NAN, NAN}};
  return {{most[0], most[1]}, {most[2], most[3]}};
}

std::array<double, 2> UnbalancedForce::largest_displacements(const State& state, std::array<double, 2> free) const {
  const double* D = state.displacements.data();
  for (const int dof : equations_.constrained_dofs) {
    if (dof % dofs_per_node == rz) free[1] = std::max(free[1], std::abs(D[dof]));
    else free[0] = std::max(free[0], std::abs(D[dof]));
  }
  return free;
}

double UnbalancedForce::translation_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  double sum = 0.0;
  for (Eigen::Index eq = 0; eq < a.size(); ++eq)
    if (!equations_.is_moment[eq]) sum += a[eq] * b[eq];
  return sum;
}

void UnbalancedForce::free_displacements(const State& state, Eigen::VectorXd& v) const {
  v.resize(equations_.free_count());
  for (int eq = 0; eq < equations_.free_count(); ++eq) v[eq] = state.displacements[equations_.free_dofs[eq]];
}

}  // namespace tsm::solver
