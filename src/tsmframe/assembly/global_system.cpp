#include "tsmframe/assembly/global_system.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tsm::assembly {
namespace {

std::array<int, 6> element_dofs(const Element& e) {
  const int i = dofs_per_node * e.start, j = dofs_per_node * e.end;
  return {i, i + 1, i + 2, j, j + 1, j + 2};
}

}  // namespace

GlobalSystem::GlobalSystem(const Model& model, const DofMap& dofs) : model_(model), dofs_(dofs) {
  const int n_elements = static_cast<int>(model.elements.size());
  initial_.reserve(n_elements);
  for (const Element& e : model.elements)
    initial_.push_back(element::initial_chord(model.nodes[e.start].position, model.nodes[e.end].position));

  // Pattern: one triplet per coupled pair of free equations, then the slot of each in CSC.
  std::vector<Eigen::Triplet<double, int>> triplets;
  triplets.reserve(36 * static_cast<size_t>(n_elements));
  for (const Element& e : model.elements) {
    const auto g = element_dofs(e);
    for (int b = 0; b < 6; ++b)
      for (int a = 0; a < 6; ++a) {
        const int row = dofs.equation(g[a]), col = dofs.equation(g[b]);
        if (row >= 0 && col >= 0) triplets.emplace_back(row, col, 0.0);
      }
  }
  tangent_.resize(dofs.free_count(), dofs.free_count());
  tangent_.setFromTriplets(triplets.begin(), triplets.end());
  tangent_.makeCompressed();

  slots_.assign(36 * static_cast<size_t>(n_elements), -1);
  const int* outer = tangent_.outerIndexPtr();
  const int* inner = tangent_.innerIndexPtr();
  for (int k = 0; k < n_elements; ++k) {
    const auto g = element_dofs(model.elements[k]);
    for (int b = 0; b < 6; ++b)
      for (int a = 0; a < 6; ++a) {
        const int row = dofs.equation(g[a]), col = dofs.equation(g[b]);
        if (row < 0 || col < 0) continue;
        const int* found = std::lower_bound(inner + outer[col], inner + outer[col + 1], row);
        slots_[36 * static_cast<size_t>(k) + 6 * b + a] = static_cast<int>(found - inner);
      }
  }
  has_prescribed_ = model.reference_prescribed.size() > 0 && model.reference_prescribed.any();
}

void GlobalSystem::evaluate(const Eigen::VectorXd& displacements, const std::vector<double>& previous_rotations,
                            bool with_tangent, Evaluation& out) {
  const int n_elements = static_cast<int>(model_.elements.size());
  out.internal_force.setZero(model_.dof_count());
  out.element_forces.resize(3 * n_elements);
  out.chord_rotations.resize(n_elements);
  out.prescribed_coupling.setZero(dofs_.free_count());
  if (with_tangent) std::fill(tangent_.valuePtr(), tangent_.valuePtr() + tangent_.nonZeros(), 0.0);
  double* values = tangent_.valuePtr();
  double force_floor = 0.0, moment_floor = 0.0;  // sums of squares

  for (int k = 0; k < n_elements; ++k) {
    const Element& e = model_.elements[k];
    const auto g = element_dofs(e);
    element::Vector6 d;
    for (int a = 0; a < 6; ++a) d[a] = displacements[g[a]];
    const element::BeamResponse r =
        element::beam_response(initial_[k], e.section, d, previous_rotations[k], with_tangent);
    out.element_forces.segment<3>(3 * k) = r.forces;
    out.chord_rotations[k] = r.chord.rotation;
    for (int a = 0; a < 6; ++a) out.internal_force[g[a]] += r.nodal_forces[a];
    const element::RoundOffFloor floor = element::round_off_floor(initial_[k], e.section, d, r);
    force_floor += 4.0 * floor.force * floor.force;  // two nodes, two translations each
    moment_floor += 2.0 * floor.moment * floor.moment;
    if (!with_tangent) continue;
    const int* slot = &slots_[36 * static_cast<size_t>(k)];
    for (int b = 0; b < 6; ++b)
      for (int a = 0; a < 6; ++a)
        if (slot[6 * b + a] >= 0) values[slot[6 * b + a]] += r.tangent(a, b);
    if (!has_prescribed_) continue;
    for (int b = 0; b < 6; ++b) {
      const double dp = model_.reference_prescribed[g[b]];
      if (dp == 0.0 || dofs_.equation(g[b]) >= 0) continue;
      for (int a = 0; a < 6; ++a) {
        const int row = dofs_.equation(g[a]);
        if (row >= 0) out.prescribed_coupling[row] += r.tangent(a, b) * dp;
      }
    }
  }
  out.force_floor = std::sqrt(force_floor);
  out.moment_floor = std::sqrt(moment_floor);
}

}  // namespace tsm::assembly
