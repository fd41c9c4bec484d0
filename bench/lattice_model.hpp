#pragma once
// The lattice frame of the benchmarks (issue 5): a rectangular grid of B × B bays (1 m), every
// member divided into D Timoshenko elements (steel, 100 mm square), the bottom row clamped, each
// top node pushed sideways and down by F in 10 load steps.

#include <cmath>

#include "tsmframe/model/model.hpp"

namespace tsm::bench {

inline tsm::Model lattice(int bays, int divisions, double force) {
  tsm::Model m;
  const double E = 2.05e11, h = 0.1, A = h * h, I = h * h * h * h / 12.0, G = 7.9e10;
  const tsm::element::SectionStiffness section{.EA = E * A, .EI = E * I, .shear_flexibility = E * I / (G * 5.0 / 6.0 * A)};
  const int n = bays + 1;
  auto joint = [n](int x, int y) { return y * n + x; };
  const size_t members = 2 * static_cast<size_t>(n) * bays;  // as a user's model would be read: no growth slack
  m.nodes.reserve(static_cast<size_t>(n) * n + members * (divisions - 1));
  m.elements.reserve(members * divisions);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) m.nodes.push_back({joint(x, y) + 1, {double(x), double(y)}});
  auto member = [&](int a, int b) {
    int previous = a;
    for (int d = 1; d <= divisions; ++d) {
      int current = b;
      if (d < divisions) {
        const Eigen::Vector2d p = m.nodes[a].position + (m.nodes[b].position - m.nodes[a].position) * (double(d) / divisions);
        m.nodes.push_back({static_cast<int>(m.nodes.size()) + 1, p});
        current = static_cast<int>(m.nodes.size()) - 1;
      }
      tsm::Element e;
      e.id = static_cast<int>(m.elements.size()) + 1;
      e.start = previous;
      e.end = current;
      e.member = m.member_count;
      e.theory = tsm::BeamTheory::timoshenko;
      e.section = section;
      m.elements.push_back(e);
      previous = current;
    }
    ++m.member_count;
  };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x + 1 < n; ++x) member(joint(x, y), joint(x + 1, y));
  for (int y = 0; y + 1 < n; ++y)
    for (int x = 0; x < n; ++x) member(joint(x, y), joint(x, y + 1));
  m.constrained.assign(m.dof_count(), false);
  m.reference_load = Eigen::VectorXd::Zero(m.dof_count());
  for (int x = 0; x < n; ++x) {
    for (int d = 0; d < 3; ++d) m.constrained[3 * joint(x, 0) + d] = true;
    m.reference_load[3 * joint(x, bays)] = force;
    m.reference_load[3 * joint(x, bays) + 1] = -force;
  }
  m.analysis.control.steps = 10;
  m.analysis.output.kind = tsm::OutputSelection::Kind::last;
  m.size = std::sqrt(2.0) * bays;
  return m;
}

}  // namespace tsm::bench
