#include "tsmframe/contact/multi_point_element.hpp"

#include <algorithm>
#include <utility>

#include <Eigen/SparseCore>

namespace tsm::contact {
namespace {

/// A 3(2+k)-vector with plane vectors on the translations of nodes i, j and contact node p.
Eigen::VectorXd spread(int size, int point, const Eigen::Vector2d& at_i, const Eigen::Vector2d& at_j,
                       const Eigen::Vector2d& at_point) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(size);
  v.segment<2>(0) = at_i;
  v.segment<2>(3) = at_j;
  v.segment<2>(6 + 3 * point) += at_point;
  return v;
}

/// Adds Y_p ∂²(δy_p)/∂x² (FORMULATION §2's K_G term, for point p) to `tangent`: it lives on the
/// translations of i, j and c_p alone, so it is formed there (6×6), not over every point's dofs.
void add_point_hessian(Eigen::MatrixXd& tangent, int point, const element::Chord& chord, double alpha, double rho,
                       double Y) {
  const Eigen::Vector2d e(chord.cos, chord.sin), n(-chord.sin, chord.cos), zero = Eigen::Vector2d::Zero();
  const double l = chord.length;
  const int place[6] = {0, 1, 3, 4, 6 + 3 * point, 7 + 3 * point};  // u, v of i, j, c_p
  const auto on = [](const Eigen::Vector2d& at_i, const Eigen::Vector2d& at_j, const Eigen::Vector2d& at_point) {
    Eigen::Matrix<double, 6, 1> v;
    v << at_i, at_j, at_point;
    return v;
  };
  const Eigen::Matrix<double, 6, 1> a1 = on(-n, n, zero);  // n · dΔ
  const Eigen::Matrix<double, 6, 1> a2 = on(-e, zero, e);  // e · dr_p
  const Eigen::Matrix<double, 6, 1> a3 = on(-e, e, zero);  // e · dΔ
  const Eigen::Matrix<double, 6, 6> hessian = (-(a1 * a2.transpose() + a2 * a1.transpose()) - (rho / l) * a1 * a1.transpose() +
                                               alpha * (a1 * a3.transpose() + a3 * a1.transpose())) / l;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) tangent(place[r], place[c]) += Y * hessian(r, c);
}

}  // namespace

Eigen::MatrixXd multi_point_equilibrium_matrix(const element::Chord& chord, const Eigen::VectorXd& alpha) {
  const int k = static_cast<int>(alpha.size()), size = 3 * (2 + k);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(size, 3 + k);
  J.topLeftCorner<6, 3>() = element::equilibrium_matrix(chord);
  const Eigen::Vector2d n(-chord.sin, chord.cos);
  for (int p = 0; p < k; ++p) J.col(3 + p) = spread(size, p, -(1.0 - alpha[p]) * n, -alpha[p] * n, n);  // K15
  return J;
}

MultiPointResponse multi_point_response(const MultiPointElementData& data, const Eigen::VectorXd& d,
                                        double previous_rotation, bool with_tangent) {
  const int k = data.size(), size = 3 * (2 + k);
  MultiPointResponse r;
  r.chord = element::current_chord(data.initial, d.head<6>(), previous_rotation);
  const double l = r.chord.length, l0 = data.initial.length;
  const Eigen::Vector2d e(r.chord.cos, r.chord.sin), n(-r.chord.sin, r.chord.cos);
  const double theta_i = d[2] - r.chord.rotation, theta_j = d[5] - r.chord.rotation;
  r.alpha.resize(k);
  r.normal.resize(k);
  r.deformations.resize(3 + k);
  r.deformations.head<3>() << r.chord.elongation, theta_i, theta_j;
  for (int p = 0; p < k; ++p) {
    // r_p = x_c − x_i formed as (X_c − X_i) + (u_c − u_i): no large coordinates cancel.
    const Eigen::Vector2d rel = (data.points[p].start - data.initial.start) +
                                Eigen::Vector2d(d[6 + 3 * p] - d[0], d[7 + 3 * p] - d[1]);
    r.alpha[p] = rel.dot(e) / l;
    r.normal[p] = rel.dot(n);
    r.deformations[3 + p] = r.normal[p] - data.points[p].offset;
  }

  MultiPointLaw law = multi_point_law(data.section, l0, r.alpha, data.edge, data.min_compliance);  // K2–K11
  Eigen::Matrix2d k_plain = data.k0.bottomRightCorner<2, 2>();
  if (data.connected()) {  // a hinge or a spring between an end and its node: condensed out (K12)
    ConnectedMultiPointLaw connected = connected_multi_point_law(law, k_plain, data.flexibility_i, data.flexibility_j);
    law = std::move(connected.law);
    k_plain = connected.k_plain;
  }
  const Eigen::Vector2d theta(theta_i, theta_j);
  const MultiPointForces f = multi_point_forces(law, k_plain, theta, r.deformations.tail(k));
  r.forces.resize(3 + k);
  r.forces << data.k0(0, 0) * r.chord.elongation, f.moments, f.point_forces;

  // J has at most nine entries per column (i, j, c_p): products with it are taken sparse, which
  // keeps an element of k points at O(k²) work there instead of O(k³) (~100 points on one coarse
  // element of a fine strip spent seconds per iteration).
  const Eigen::SparseMatrix<double> J = multi_point_equilibrium_matrix(r.chord, r.alpha).sparseView();
  r.nodal_forces = J * r.forces;
  r.force_per_Y = Eigen::VectorXd::Ones(k);
  const PointForceMap map = point_force_map(law);  // K14
  r.point_u = J * map.P;
  r.point_stiffness = map.stiffness;
  r.sliding_u = Eigen::MatrixXd::Zero(size, k);
  r.sliding_v = Eigen::MatrixXd::Zero(size, k);
  const bool frictional = std::any_of(data.points.begin(), data.points.end(),
                                      [](const ContactPointData& p) { return p.friction.mu != 0.0; });
  if (!with_tangent) {
    if (frictional) add_multi_point_friction(data, f.dpoint_forces, false, r);
    return r;
  }

  const Eigen::MatrixXd JD = J * law_tangent(map, data.k0(0, 0), k_plain);
  r.tangent = JD * J.transpose();  // K14
  // K_G (K15): N ∂²l + (M_i + M_j) ∂²(−β) on i, j, and Y_p ∂²δy_p on the translations of i, j, c_p.
  r.tangent.topLeftCorner<6, 6>() += element::geometric_stiffness(r.chord, r.forces.head<3>());
  for (int p = 0; p < k; ++p) add_point_hessian(r.tangent, p, r.chord, r.alpha[p], r.normal[p], f.point_forces[p]);
  r.symmetric_tangent = r.tangent;

  if (data.sliding_term) {
    // a_p, b_p follow the geometry: J (∂S/∂α_p)(∂α_p/∂x)ᵀ for each point (K13, K15).
    Eigen::MatrixXd dS = Eigen::MatrixXd::Zero(3 + k, k);  // column p: ∂S/∂α_p
    dS.middleRows(1, 2) = f.dmoments;
    dS.bottomRows(k) = f.dpoint_forces;
    r.sliding_u = J * dS;
    for (int p = 0; p < k; ++p) {
      const double rho = r.normal[p], a = r.alpha[p];
      r.sliding_v.col(p) = spread(size, p, ((a - 1.0) / l) * e - (rho / (l * l)) * n, (rho / (l * l)) * n - (a / l) * e, e / l);
    }
    const Eigen::SparseMatrix<double> v = r.sliding_v.sparseView();
    r.tangent += r.sliding_u * v.transpose();
  }
  if (frictional) add_multi_point_friction(data, f.dpoint_forces, true, r);
  return r;
}

}  // namespace tsm::contact
