#include "tsmframe/element/section_forces.hpp"

#include <algorithm>

namespace tsm::element {

std::vector<SectionStation> section_forces(double l, const Eigen::Vector3d& forces, std::span<const PointForce> points) {
  const double Mi = forces[1], Mj = forces[2];
  std::vector<PointForce> sorted(points.begin(), points.end());
  std::sort(sorted.begin(), sorted.end(), [](const PointForce& a, const PointForce& b) { return a.alpha < b.alpha; });
  // The element as a beam on its two end nodes. The end moments' part, M = −M_i (1 − ξ) + M_j ξ;
  // each point's, a simply supported beam's: its Y (along +n, bending the element towards −n)
  // −Y l ξ (1 − α) before it and −Y l α (1 − ξ) after it, its couple C = −ρT C ξ before it and
  // C (ξ − 1) after it. `after`: the value just past a point at ξ.
  const auto moment = [&](double xi, bool after) {
    double M = -Mi * (1.0 - xi) + Mj * xi;
    for (const PointForce& p : sorted) {
      const bool behind = xi > p.alpha || (after && xi == p.alpha);
      const double C = -p.rho * p.T;
      M -= p.Y * l * (behind ? p.alpha * (1.0 - xi) : xi * (1.0 - p.alpha));
      M += behind ? C * (xi - 1.0) : C * xi;
    }
    return M;
  };
  // V = dM/dx: (M_i + M_j)/l, less Y(1 − α) and plus C/l for every point; N: the law's N, plus
  // (1 − α)T for every point ahead, less αT for every point behind (N8's lever rule).
  double V = (Mi + Mj) / l, N = forces[0];
  for (const PointForce& p : sorted) {
    V += -p.Y * (1.0 - p.alpha) - p.rho * p.T / l;
    N += (1.0 - p.alpha) * p.T;
  }
  std::vector<SectionStation> stations;
  stations.reserve(2 * sorted.size() + 2);
  stations.push_back({0.0, N, V, moment(0.0, false)});
  for (const PointForce& p : sorted) {
    stations.push_back({p.alpha * l, N, V, moment(p.alpha, false)});
    V += p.Y;
    N -= p.T;
    stations.push_back({p.alpha * l, N, V, moment(p.alpha, true)});
  }
  stations.push_back({l, N, V, moment(1.0, false)});
  return stations;
}

SectionStation section_at(std::span<const SectionStation> stations, double x) {
  size_t k = 0;  // the stretch [k, k + 1] holding x: the last that starts at or before it
  while (k + 2 < stations.size() && stations[k + 1].x <= x) ++k;
  const SectionStation &a = stations[k], &b = stations[k + 1];
  const double t = b.x > a.x ? std::clamp((x - a.x) / (b.x - a.x), 0.0, 1.0) : 0.0;
  return {x, a.N, a.V, a.M + t * (b.M - a.M)};
}

}  // namespace tsm::element
