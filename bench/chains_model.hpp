#pragma once
// The chains of the scaling benchmarks (issues 2 and 5): C independent cantilevers of N
// Timoshenko elements each (10 m, steel, 100 mm square), every one rolled by a tip moment to
// `turns` of a full circle (0.25: a quarter) in `steps` load steps (max 200 iterations per step).

#include <cmath>
#include <numbers>

#include "tsmframe/model/model.hpp"

namespace tsm::bench {

inline tsm::Model rolled_cantilevers(int chains, int per_chain, double turns, int steps) {
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

}  // namespace tsm::bench
