#pragma once
// One classical Runge–Kutta step for the reference solutions the verification tests shoot
// (elasticas): q ← q + ds/6 (k1 + 2k2 + 2k3 + k4) for q' = f(q).

#include <array>
#include <cstddef>

namespace tsm::test {

template <std::size_t N, class F>
std::array<double, N> rk4_step(const F& f, const std::array<double, N>& q, double ds) {
  std::array<double, N> k1 = f(q), t, k2, k3, k4, out;
  for (std::size_t i = 0; i < N; ++i) t[i] = q[i] + 0.5 * ds * k1[i];
  k2 = f(t);
  for (std::size_t i = 0; i < N; ++i) t[i] = q[i] + 0.5 * ds * k2[i];
  k3 = f(t);
  for (std::size_t i = 0; i < N; ++i) t[i] = q[i] + ds * k3[i];
  k4 = f(t);
  for (std::size_t i = 0; i < N; ++i) out[i] = q[i] + ds / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  return out;
}

}  // namespace tsm::test
