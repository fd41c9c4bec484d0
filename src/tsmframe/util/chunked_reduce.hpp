#pragma once
// A sum (or maximum) over [0, n) that is bit-identical whatever the number of threads: the range
// is cut into fixed chunks, each summed on its own (in parallel where there are enough), and the
// chunk sums are added in order.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <functional>
#include <vector>

#include "tsmframe/util/parallel_for.hpp"

namespace tsm::util {

/// Σ over [0, n) in fixed chunks: body(begin, end, sums) adds its range into sums. With `combine`
/// a maximum (Larger) the chunks' maxima instead.
template <int K, class Body, class Combine = std::plus<double>>
std::array<double, K> chunked_reduce(Eigen::Index n, const Body& body, Combine combine = {}) {
  constexpr Eigen::Index chunk = 16384;
  const Eigen::Index chunks = (n + chunk - 1) / chunk;
  std::vector<std::array<double, K>> partial(chunks);
  parallel_for_static(Eigen::Index{0}, chunks, chunks >= 4, [&](Eigen::Index c) {
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

}  // namespace tsm::util
