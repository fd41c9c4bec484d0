#pragma once
// ∂(internal force − λ · reference load − dead load)/∂D over the free equations by central differences, for
// the tests of tangents whose loads turn with the structure (follower loads): the Jacobian the
// assembled tangent with its rank-one terms must equal.

#include <Eigen/Dense>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"

namespace tsm::test {

/// At displacements D from chord rotations `rotations` (each evaluation continues a copy), with
/// the system's load factor `lambda` (set_load_factor already called), step h.
inline Eigen::MatrixXd unbalanced_force_jacobian(assembly::GlobalSystem& system, const assembly::DofMap& dofs,
                                                 const Eigen::VectorXd& D, const std::vector<double>& rotations,
                                                 double lambda, double h = 1e-6) {
  const int n = dofs.free_count();
  Eigen::MatrixXd J(n, n);
  for (int c = 0; c < n; ++c) {
    Eigen::VectorXd plus = D, minus = D;
    plus[dofs.dof(c)] += h;
    minus[dofs.dof(c)] -= h;
    assembly::Evaluation ep, em;
    std::vector<double> rp = rotations, rm = rotations;
    system.evaluate(plus, rp, false, ep);
    system.evaluate(minus, rm, false, em);
    // An evaluation leaves the reference load empty when no load turns (it is the model's then).
    const Eigen::VectorXd& model_load = system.model().reference_load;
    Eigen::VectorXd fp = ep.internal_force - lambda * (ep.reference_load.size() > 0 ? ep.reference_load : model_load);
    Eigen::VectorXd fm = em.internal_force - lambda * (em.reference_load.size() > 0 ? em.reference_load : model_load);
    if (ep.dead_load.size() > 0) fp -= ep.dead_load, fm -= em.dead_load;  // an earlier stage's follower loads
    for (int r = 0; r < n; ++r) J(r, c) = (fp[dofs.dof(r)] - fm[dofs.dof(r)]) / (2 * h);
  }
  return J;
}

}  // namespace tsm::test
