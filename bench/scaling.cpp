// Scaling run (issue 2's benchmark): C independent cantilevers of N elements each (10 m, steel,
// 100 mm square), every one rolled to a quarter circle by a tip moment in 10 load steps.
// Usage: tsmframe_scaling [C=1] [N=1000] [turns=0.25] [steps=10] (max 200 iterations per step).
// Prints one row: elements, steps, iterations, ms per iteration, ns per element per iteration,
// total seconds, peak memory. Run one size per process so the peak memory is that size's own:
// bench/run_scaling.sh does. (Why chains of 1,000 and not one chain of 10⁶ elements: see
// bench/README.md — positions X + u carry ~ε|u| of noise, so a single chain of 10 µm elements
// has an axial-force rounding floor far above its loads, in any double-precision code.)
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "measure.hpp"

namespace {

tsm::Model rolled_cantilevers(int chains, int per_chain, double turns, int steps) {
  tsm::Model m;
  const double L = 10.0, E = 2.05e11, h = 0.1, A = h * h, I = h * h * h * h / 12.0, G = 7.9e10;
  const int nodes_per_chain = per_chain + 1;
  m.nodes.reserve(static_cast<size_t>(chains) * nodes_per_chain);
  m.elements.reserve(static_cast<size_t>(chains) * per_chain);
  for (int c = 0; c < chains; ++c) {
    const int first = c * nodes_per_chain;
    for (int k = 0; k <= per_chain; ++k) m.nodes.push_back({first + k + 1, {L * k / per_chain, 2.0 * L * c}});
    for (int k = 0; k < per_chain; ++k) {
      tsm::Element e;
      e.id = static_cast<int>(m.elements.size()) + 1;
      e.start = first + k;
      e.end = first + k + 1;
      e.member = c;
      e.theory = tsm::BeamTheory::timoshenko;
      e.section = {.EA = E * A, .EI = E * I, .shear_flexibility = E * I / (G * 5.0 / 6.0 * A)};
      m.elements.push_back(e);
    }
  }
  m.member_count = chains;
  m.constrained.assign(m.dof_count(), false);
  m.reference_load = Eigen::VectorXd::Zero(m.dof_count());
  for (int c = 0; c < chains; ++c) {
    const int root = 3 * c * nodes_per_chain, tip = root + 3 * per_chain;
    m.constrained[root] = m.constrained[root + 1] = m.constrained[root + 2] = true;
    m.reference_load[tip + 2] = turns * 2.0 * std::numbers::pi * E * I / L;
  }
  m.analysis.control.steps = steps;
  m.analysis.max_iterations = 200;
  m.analysis.output.kind = tsm::OutputSelection::Kind::last;
  m.size = std::hypot(L, 2.0 * L * (chains - 1));
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  const int chains = argc > 1 ? std::atoi(argv[1]) : 1;
  const int per_chain = argc > 2 ? std::atoi(argv[2]) : 1000;
  const double turns = argc > 3 ? std::atof(argv[3]) : 0.25;  // 0.25: quarter circle
  const int steps = argc > 4 ? std::atoi(argv[4]) : 10;
  return tsm::bench::measure([&] { return rolled_cantilevers(chains, per_chain, turns, steps); },
                             [&](const tsm::Model&, const tsm::solver::RunResult& result) {
                               const auto& tip = result.steps.back().displacements;
                               if (tip.size() == 0) return std::string("(no state)");
                               char text[96];
                               std::snprintf(text, sizeof text, "tip=(%.6f, %.6f, %.6f)", tip[3 * per_chain],
                                             tip[3 * per_chain + 1], tip[3 * per_chain + 2]);
                               return std::string(text);
                             });
}
