// Scaling run (issue 2's benchmark): C independent cantilevers of N elements each (10 m, steel,
// 100 mm square), every one rolled to a quarter circle by a tip moment in 10 load steps.
// Usage: tsmframe_scaling [C=1] [N=1000] [turns=0.25] [steps=10] [runs=1] (max 200 iterations
// per step). Prints one row per run: elements, steps, iterations, ms per iteration, ns per element
// per iteration, total seconds, peak memory. With runs > 1 the model is run again in the same
// process, as a study sweep runs its cases: the first run pays the process's one-time costs (the
// worker thread started, the heap's pages first touched), the others do not. Run one size per process so the peak memory is that size's own:
// bench/run_scaling.sh does. (Why chains of 1,000 and not one chain of 10⁶ elements: see
// bench/README.md — positions X + u carry ~ε|u| of noise, so a single chain of 10 µm elements
// has an axial-force rounding floor far above its loads, in any double-precision code.)
#include <cstdio>
#include <cstdlib>
#include <string>

#include "chains_model.hpp"
#include "measure.hpp"

int main(int argc, char** argv) {
  const int chains = argc > 1 ? std::atoi(argv[1]) : 1;
  const int per_chain = argc > 2 ? std::atoi(argv[2]) : 1000;
  const double turns = argc > 3 ? std::atof(argv[3]) : 0.25;  // 0.25: quarter circle
  const int steps = argc > 4 ? std::atoi(argv[4]) : 10;
  const int runs = argc > 5 ? std::atoi(argv[5]) : 1;
  const auto build = [&] { return tsm::bench::rolled_cantilevers(chains, per_chain, turns, steps); };
  const auto describe = [&](const tsm::Model&, const tsm::solver::RunResult& result) {
    const auto& tip = result.steps.back().displacements;
    if (tip.size() == 0) return std::string("(no state)");
    char text[96];
    std::snprintf(text, sizeof text, "tip=(%.6f, %.6f, %.6f)", tip[3 * per_chain], tip[3 * per_chain + 1],
                  tip[3 * per_chain + 2]);
    return std::string(text);
  };
  int status = 0;
  for (int run = 0; run < runs; ++run) status |= tsm::bench::measure(build, describe);
  return status;
}
