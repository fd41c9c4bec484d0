#pragma once
// Shared by the scaling benches: run a model, time it, and print the standard row
// (elements, steps, iterations, ms/iteration, ns/element/iteration, total s, peak MB).

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>

#include "tsmframe/model/model.hpp"
#include "tsmframe/solver/analysis.hpp"

namespace tsm::bench {

/// Builds the model with `build`, runs it and prints one row followed by `describe(result)`.
/// Returns the process exit status (0 if converged).
inline int measure(const std::function<Model()>& build,
                   const std::function<std::string(const Model&, const solver::RunResult&)>& describe) {
  const auto t0 = std::chrono::steady_clock::now();
  const Model model = build();
  const auto t1 = std::chrono::steady_clock::now();
  const solver::RunResult result = solver::run_analysis(model);
  const auto t2 = std::chrono::steady_clock::now();
  int iterations = 0;
  for (const auto& s : result.steps) iterations += s.iterations;
  const double solve = std::chrono::duration<double>(t2 - t1).count();
  const double total = std::chrono::duration<double>(t2 - t0).count();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double elements = static_cast<double>(model.elements.size());
  std::printf("%9zu %5zu %6d %10.3f %9.1f %8.3f %8.1f  %s %s\n", model.elements.size(), result.steps.size(), iterations,
              1e3 * solve / iterations, 1e9 * solve / iterations / elements, total, usage.ru_maxrss / 1024.0,
              solver::status_name(result.status), describe(model, result).c_str());
  return result.status == solver::Status::converged ? 0 : 1;
}

}  // namespace tsm::bench
