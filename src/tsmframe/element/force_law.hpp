#pragma once
// Element force equations of the two-node beam element: S = k0 · d (paper Eq. 3–5).
// Pure and local: nothing here knows about nodes, coordinates or the global model.

#include <Eigen/Core>

namespace tsm::element {

/// Stiffness data of a cross-section, in the user's consistent units.
struct SectionStiffness {
  double EA = 0.0;                 ///< axial rigidity
  double EI = 0.0;                 ///< bending rigidity
  double shear_flexibility = 0.0;  ///< Ψ = EI / (G A_s); 0 for Euler–Bernoulli (FORMULATION §1)
};

/// Element deformations d = (δl, θ_i, θ_j) and forces S = (N, M_i, M_j) in the chord frame.
using Vector3 = Eigen::Vector3d;
using Matrix3 = Eigen::Matrix3d;

/// Bending-shear factor q = 12 Ψ / l0² (Eq. 5, with the square the OCR text lacks).
double shear_factor(const SectionStiffness& section, double l0);

/// k0 in the three numbers it holds (k0 is symmetric and k_ii = k_jj): what an element keeps.
struct BasicStiffness {
  double axial = 0.0;   ///< EA / l0
  double direct = 0.0;  ///< k_ii = k_jj
  double cross = 0.0;   ///< k_ij
  /// k0(a, b), as Matrix3 would give it (the zeros fold away where a and b are constants).
  constexpr double operator()(int a, int b) const {
    if (a == 0 || b == 0) return a == b ? axial : 0.0;
    return a == b ? direct : cross;
  }
  Matrix3 matrix() const {
    Matrix3 k;
    k << axial, 0.0, 0.0, 0.0, direct, cross, 0.0, cross, direct;
    return k;
  }
};
BasicStiffness basic_stiffness_terms(const SectionStiffness& section, double l0);

/// k0 of Eq. 4 (Timoshenko); with Ψ = 0 it is exactly Eq. 3 (Euler–Bernoulli).
Matrix3 basic_stiffness(const SectionStiffness& section, double l0);

/// k0 with the moment released at end i and/or j (a hinge): the released end's rotation is
/// condensed out of the bending block (its moment stays 0), e.g. at i the bending stiffness at j
/// becomes k_jj − k_ij²/k_ii (3EI/l0 for Euler–Bernoulli, 12EI/(l0(4 + q)) for Timoshenko);
/// released at both ends the element is a bar.
Matrix3 released_stiffness(const BasicStiffness& k0, bool at_i, bool at_j);

/// k0 with a rotational spring between each end and its node (a semi-rigid connection), given by
/// its flexibility 1/k (0: rigid; INFINITY: a hinge, as released_stiffness). The element's end
/// rotation is the node's less M/k, condensed out: the bending block becomes (B⁻¹ + F)⁻¹, F =
/// diag(f_i, f_j) — the element and its springs in series.
Matrix3 connected_stiffness(const BasicStiffness& k0, double flexibility_i, double flexibility_j);

}  // namespace tsm::element
