#include "tsmframe/solver/buckling.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/element/chord.hpp"
#include "tsmframe/solver/linear_solver.hpp"

namespace tsm::solver {
namespace {

constexpr int most_iterations = 200;
constexpr double converged_within = 1e-10;  // relative change of every wanted eigenvalue per iteration
// Below this fraction of the largest, an eigenvalue of the Ritz problem is round-off: a direction
// the subspace lost (Xᵀ K_M X), or a mode the load does not compress (μ = 1/λ).
constexpr double regular_above = 1e-12;
// A mode is resolved where ‖K_M φ − λ B φ‖ is below this fraction of ‖K_M φ‖ (the iteration
// settles λ to 1e-10, its shape to ~1e-5; a mode lost in round-off is off by its whole size).
constexpr double resolved_within = 1e-3;
// The linear solution's forces are read from the elements at this fraction of the model's size
// (its largest translation): small enough that the geometry does not change them (O(ε)), large
// enough that rounding does not.
constexpr double linear_move = 1e-7;

using Sparse = Eigen::SparseMatrix<double>;

/// K_G over the free equations (nodal frames), the elements' geometric stiffness at the chords of
/// `displacements` (global; `rotations` the chords' previous turns) under element forces
/// `forces` (N, M_i, M_j per element).
Sparse geometric_stiffness(const Model& model, const assembly::GlobalSystem& system, const Eigen::VectorXd& forces,
                           const Eigen::VectorXd& displacements, const std::vector<double>& rotations) {
  const assembly::DofMap& dofs = system.dofs();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(36 * model.elements.size());
  for (size_t e = 0; e < model.elements.size(); ++e) {
    const Element& element = model.elements[e];
    const element::InitialChord initial =
        element::initial_chord(model.nodes[element.start].position, model.nodes[element.end].position);
    element::Vector6 ends;
    ends << displacements.segment<3>(dofs_per_node * element.start), displacements.segment<3>(dofs_per_node * element.end);
    const element::Chord chord = element::current_chord(initial, ends, rotations[e]);
    const element::Matrix6 k = element::geometric_stiffness(chord, forces.segment<3>(3 * e));
    const int node[2] = {element.start, element.end};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const Eigen::Matrix3d block = system.frames().to_nodal(node[a], node[b], k.block<3, 3>(3 * a, 3 * b));
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const int row = dofs.equation(dofs_per_node * node[a] + i), column = dofs.equation(dofs_per_node * node[b] + j);
            if (row >= 0 && column >= 0 && block(i, j) != 0.0) entries.emplace_back(row, column, block(i, j));
          }
      }
  }
  Sparse K(dofs.free_count(), dofs.free_count());
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

/// Every dof's value (global) from the free equations' (nodal).
Eigen::VectorXd all_dofs(const Model& model, const assembly::GlobalSystem& system, const Eigen::VectorXd& free) {
  Eigen::VectorXd all = Eigen::VectorXd::Zero(model.dof_count());
  for (int eq = 0; eq < system.dofs().free_count(); ++eq) all[system.dofs().dof(eq)] = free[eq];
  system.frames().to_global(all);
  return all;
}

double largest_translation(const Eigen::VectorXd& all, int* at = nullptr) {
  double largest = 0.0;
  for (Eigen::Index k = 0; k + 1 < all.size(); k += dofs_per_node)
    for (int d = 0; d < 2; ++d)
      if (std::abs(all[k + d]) > largest) {
        largest = std::abs(all[k + d]);
        if (at) *at = static_cast<int>(k + d);
      }
  return largest;
}

/// The subspace iteration for K_M φ = λ B φ (B = −K_G, indefinite): X ← K_M⁻¹ B X with
/// Rayleigh–Ritz on (Xᵀ B X) ψ = μ (Xᵀ K_M X) ψ, μ = 1/λ, Xᵀ K_M X taken as Xᵀ (B X_before) (no
/// product with K_M, whose storage holds its factor). B is singular (rotations, stretching), so
/// that K_M⁻¹ B X may have fewer independent columns than X: the Ritz problem is solved on the
/// span Xᵀ K_M X leaves regular. The columns converge to the largest |μ|; the wanted are the
/// largest positive ones. Returns (μ, vector) pairs.
std::vector<std::pair<double, Eigen::VectorXd>> subspace_iteration(const LinearSolver& solver, const Sparse& B, int count) {
  const int n = static_cast<int>(B.rows());
  const int p = std::min(n, std::max(2 * count, count + 8));
  Eigen::MatrixXd X(n, p);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < p; ++j) X(i, j) = std::sin(1.0 + i * (j + 1.0) + 0.37 * j);  // touches every mode
  std::vector<double> before;
  Eigen::VectorXd mu;
  Eigen::MatrixXd vectors;
  for (int iteration = 0; iteration < most_iterations; ++iteration) {
    const Eigen::MatrixXd BX = B * X;
    Eigen::MatrixXd next(n, X.cols());  // the subspace may have shrunk to B's rank
    for (Eigen::Index j = 0; j < X.cols(); ++j) next.col(j) = solver.solve(BX.col(j));
    Eigen::MatrixXd Kr = next.transpose() * BX, Br = next.transpose() * (B * next);
    Kr = 0.5 * (Kr + Kr.transpose()).eval();
    Br = 0.5 * (Br + Br.transpose()).eval();
    // Kr = V S Vᵀ: W = V S^(−1/2) over its regular part, then the plain eigenproblem of Wᵀ Br W.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> regular(Kr);
    const Eigen::VectorXd s = regular.eigenvalues();
    std::vector<int> kept;
    for (int j = 0; j < s.size(); ++j)
      if (s[j] > regular_above * s.maxCoeff()) kept.push_back(j);
    if (kept.empty()) return {};
    Eigen::MatrixXd W(s.size(), kept.size());
    for (size_t j = 0; j < kept.size(); ++j) W.col(j) = regular.eigenvectors().col(kept[j]) / std::sqrt(s[kept[j]]);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(W.transpose() * Br * W);
    const int r = static_cast<int>(kept.size());
    // Columns by |μ| descending: the subspace keeps the largest.
    std::vector<int> order(r);
    for (int j = 0; j < r; ++j) order[j] = j;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return std::abs(eig.eigenvalues()[a]) > std::abs(eig.eigenvalues()[b]); });
    mu.resize(r);
    vectors.resize(n, r);
    const Eigen::MatrixXd NW = next * W;
    for (int j = 0; j < r; ++j) {
      mu[j] = eig.eigenvalues()[order[j]];
      vectors.col(j) = NW * eig.eigenvectors().col(order[j]);
    }
    X = vectors;
    std::vector<double> wanted;
    for (int j = 0; j < mu.size() && static_cast<int>(wanted.size()) < count; ++j)
      if (mu[j] > regular_above * std::abs(mu[0])) wanted.push_back(mu[j]);
    bool settled = wanted.size() == before.size() && !wanted.empty();
    for (size_t k = 0; settled && k < wanted.size(); ++k)
      settled = std::abs(wanted[k] - before[k]) <= converged_within * std::abs(wanted[k]);
    before = wanted;
    if (settled || (iteration > 20 && wanted.empty())) break;
  }
  // Every Ritz pair up to the `count`-th positive one, by |μ| descending (the negative ones too:
  // the caller checks that each is resolved).
  std::vector<std::pair<double, Eigen::VectorXd>> found;
  int positive = 0;
  for (int j = 0; j < mu.size() && positive < count; ++j) {
    if (std::abs(mu[j]) <= regular_above * std::abs(mu[0])) break;
    found.emplace_back(mu[j], vectors.col(j));
    positive += mu[j] > 0.0 ? 1 : 0;
  }
  return found;
}

/// K x over the free equations, K a tangent's node blocks (lower triangle by columns; the fill,
/// no entry of K, skipped; a constrained dof's row and column hold nothing but its 1).
Eigen::VectorXd times(const BlockMatrix& K, const assembly::DofMap& dofs, const Eigen::VectorXd& x) {
  const auto place = [&](int eq) {
    const int dof = dofs.dof(eq);
    return dofs_per_node * dofs.block(dof / dofs_per_node) + dof % dofs_per_node;
  };
  Eigen::VectorXd padded = Eigen::VectorXd::Zero(dofs_per_node * K.size), product = padded;
  for (Eigen::Index eq = 0; eq < x.size(); ++eq) padded[place(static_cast<int>(eq))] = x[eq];
  for (int c = 0; c < K.size; ++c)
    for (int p = K.column[c]; p < K.column[c + 1]; ++p) {
      if (K.is_fill(p)) continue;
      const int r = K.row[p];
      product.segment<3>(3 * r) += K.value[p] * padded.segment<3>(3 * c);
      if (r != c) product.segment<3>(3 * c) += K.value[p].transpose() * padded.segment<3>(3 * r);
    }
  Eigen::VectorXd out(x.size());
  for (Eigen::Index eq = 0; eq < x.size(); ++eq) out[eq] = product[place(static_cast<int>(eq))];
  return out;
}

}  // namespace

Buckling linear_buckling(const Model& model, int count, const BucklingState* at) {
  if (count <= 0) return {};
  assembly::DofMap dofs(model);
  assembly::GlobalSystem system(model, dofs);
  const Eigen::VectorXd start = at ? at->displacements : Eigen::VectorXd::Zero(model.dof_count());
  const std::vector<double> rotations = at ? at->chord_rotations : std::vector<double>(model.elements.size(), 0.0);
  assembly::Evaluation evaluation;
  system.evaluate(start, rotations, true, evaluation);
  LinearSolver solver;
  solver.analyze(dofs, system.tangent());
  if (dofs.free_count() == 0 || !solver.factorize(system.tangent_for_factorisation())) return {};  // a mechanism
  // The linear response to the reference load, and its element forces' increment.
  Eigen::VectorXd load = model.reference_load;
  system.frames().to_nodal(load);
  Eigen::VectorXd free(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq) free[eq] = load[dofs.dof(eq)];
  const Eigen::VectorXd linear = all_dofs(model, system, solver.solve(free));
  const double largest = largest_translation(linear);
  if (!(largest > 0.0) || !std::isfinite(largest)) return {};
  const double scale = linear_move * model.size / largest;
  const Eigen::VectorXd forces =
      (system.element_forces(start + scale * linear, rotations, {}) - system.element_forces(start, rotations, {})) / scale;
  const Sparse B = -geometric_stiffness(model, system, forces, start, rotations);
  const auto found = subspace_iteration(solver, B, count);
  // Each mode checked against K_M itself (evaluated again: the factor took its place): a mode
  // whose stiffness lies below the factorisation's round-off (a member hundreds of thousands of
  // times longer than deep, in short elements) is not resolved in double precision and is left out.
  system.evaluate(start, rotations, true, evaluation);
  Buckling buckling;
  if (at) buckling.step = at->step, buckling.base_load_factor = at->load_factor;
  for (const auto& [mu, vector] : found) {  // by |μ| descending: the positive ones by λ ascending
    const Eigen::VectorXd elastic = times(system.tangent(), dofs, vector);
    if ((mu * elastic - B * vector).norm() > resolved_within * std::abs(mu) * elastic.norm()) {
      buckling.unresolved = true;
      break;
    }
    if (mu <= 0.0) continue;  // buckling under the reversed load
    BucklingMode mode{buckling.base_load_factor + 1.0 / mu, all_dofs(model, system, vector)};
    int at = 0;
    const double size = largest_translation(mode.shape, &at);
    if (size > 0.0) mode.shape /= (mode.shape[at] > 0.0 ? size : -size);
    buckling.modes.push_back(std::move(mode));
  }
  // A compressed element makes −K_G positive along its own sway: some λ > 0 exists. None found is
  // the round-off's doing too.
  bool compressed = false;
  for (size_t e = 0; e < model.elements.size() && !compressed; ++e) compressed = forces[3 * e] < 0.0;
  if (buckling.modes.empty() && compressed) buckling.unresolved = true;
  return buckling;
}

}  // namespace tsm::solver
