#include "tsmframe/contact/multi_point_cantilever_frame.hpp"

#include <cmath>

#include "tsmframe/contact/cantilever_frame_element.hpp"

namespace tsm::contact {
namespace {

/// The frame clamped at node i and the points' places in it.
struct CantileverFrame {
  Eigen::Vector2d t, m;
  double sj = 0.0, vj = 0.0;  ///< r_j·t, r_j·m
  Eigen::VectorXd s, v;       ///< r_p·t, r_p·m
};

CantileverFrame frame_at(const MultiPointElementData& data, const Eigen::VectorXd& d) {
  const int k = data.size();
  CantileverFrame f;
  const double angle = data.initial.angle + d[2];  // ψ = φ0 + Θ_i
  f.t = Eigen::Vector2d(std::cos(angle), std::sin(angle));
  f.m = Eigen::Vector2d(-f.t.y(), f.t.x());
  // r = x − x_i formed as (X − X_i) + (u − u_i): no large coordinates cancel.
  const Eigen::Vector2d rj = (data.initial.end - data.initial.start) + Eigen::Vector2d(d[3] - d[0], d[4] - d[1]);
  f.sj = rj.dot(f.t);
  f.vj = rj.dot(f.m);
  f.s.resize(k);
  f.v.resize(k);
  for (int p = 0; p < k; ++p) {
    const Eigen::Vector2d rp = (data.points[p].start - data.initial.start) + Eigen::Vector2d(d[6 + 3 * p] - d[0], d[7 + 3 * p] - d[1]);
    f.s[p] = rp.dot(f.t);
    f.v[p] = rp.dot(f.m);
  }
  return f;
}

/// J (3(2+k) × (3+k); §2b): columns N, Q, M, then Y_p — node i −m and −s_p, node c_p +m.
Eigen::MatrixXd cantilever_equilibrium_matrix(const CantileverFrame& f) {
  const int k = static_cast<int>(f.s.size()), size = 3 * (2 + k);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(size, 3 + k);
  J.block<2, 1>(0, 0) = -f.t, J(2, 0) = f.vj, J.block<2, 1>(3, 0) = f.t;
  J.block<2, 1>(0, 1) = -f.m, J(2, 1) = -f.sj, J.block<2, 1>(3, 1) = f.m;
  J(2, 2) = -1.0, J(5, 2) = 1.0;
  for (int p = 0; p < k; ++p) {
    J.block(0, 3 + p, 2, 1) = -f.m;
    J(2, 3 + p) = -f.s[p];
    J.block(6 + 3 * p, 3 + p, 2, 1) = f.m;
  }
  return J;
}

/// K_G (§2b), only in the Θ_i row and column: the frame turns with Θ_i.
void add_frame_turning(Eigen::MatrixXd& tangent, const CantileverFrame& f, double N, double Q, const Eigen::VectorXd& Y) {
  const int k = static_cast<int>(Y.size());
  Eigen::VectorXd row = Eigen::VectorXd::Zero(tangent.rows());
  const Eigen::Vector2d at_j = N * f.m - Q * f.t;
  row.segment<2>(0) = -(at_j - Y.sum() * f.t);
  row[2] = -(N * f.sj + Q * f.vj + Y.dot(f.v));
  row.segment<2>(3) = at_j;
  for (int p = 0; p < k; ++p) row.segment<2>(6 + 3 * p) = -Y[p] * f.t;
  tangent.row(2) += row.transpose();
  tangent.col(2) += row;
  tangent(2, 2) -= row[2];  // the diagonal entry once
}

}  // namespace

MultiPointResponse multi_point_cantilever_response(const MultiPointElementData& data, const Eigen::VectorXd& d,
                                                   double previous_rotation, bool with_tangent) {
  const int k = data.size(), size = 3 * (2 + k);
  MultiPointResponse r;
  r.chord = element::current_chord(data.initial, d.head<6>(), previous_rotation);
  const double l0 = data.initial.length, psi = data.section.shear_flexibility;
  const CantileverFrame f = frame_at(data, d);
  r.alpha = f.s / f.sj;
  r.normal = f.v;
  r.deformations.resize(3 + k);
  r.deformations.head<3>() << f.sj - l0, f.vj, d[5] - d[2];
  for (int p = 0; p < k; ++p) r.deformations[3 + p] = f.v[p] - data.points[p].offset;

  // The chord frame's law (C, its floors and α-derivatives) with G for H.
  MultiPointLaw law = multi_point_law(data.section, l0, r.alpha, data.edge, data.min_compliance);
  for (int p = 0; p < k; ++p) {
    const LoadShare g = cantilever_load_share(psi, l0, r.alpha[p]);
    law.h.col(p) << g.q, g.m;
    law.dh.col(p) << g.dq, g.dm;
  }
  const Eigen::Matrix2d k_plain = cantilever_stiffness(data.section, l0);
  const MultiPointForces forces = multi_point_forces(law, k_plain, r.deformations.segment<2>(1), r.deformations.tail(k));
  Eigen::VectorXd S(3 + k);  // (N, Q, M, Y_1 … Y_k)
  S << data.k0(0, 0) * r.deformations[0], forces.moments, forces.point_forces;

  const Eigen::MatrixXd J = cantilever_equilibrium_matrix(f);
  r.nodal_forces = J * S;
  // Reported in the chord frame: N along the chord, the end moments, Y.
  const Eigen::Vector2d e(r.chord.cos, r.chord.sin);
  r.forces.resize(3 + k);
  r.forces << r.nodal_forces.segment<2>(3).dot(e), r.nodal_forces[2], r.nodal_forces[5], forces.point_forces;
  r.force_per_Y = Eigen::VectorXd::Ones(k);
  const PointForceMap map = point_force_map(law);  // K14
  r.point_u = J * map.P;
  r.point_stiffness = map.stiffness;
  r.sliding_u = Eigen::MatrixXd::Zero(size, k);
  r.sliding_v = Eigen::MatrixXd::Zero(size, k);
  if (!with_tangent) return r;

  r.tangent = J * law_tangent(map, data.k0(0, 0), k_plain) * J.transpose();  // ∂S/∂d: K14 with G
  add_frame_turning(r.tangent, f, S[0], S[1], forces.point_forces);
  r.symmetric_tangent = r.tangent;
  if (data.sliding_term) {
    for (int p = 0; p < k; ++p) {  // J (∂S/∂α_p)(∂α_p/∂x)ᵀ, α_p = s_p / s_j (§2b)
      Eigen::VectorXd dS = Eigen::VectorXd::Zero(3 + k);
      dS.segment<2>(1) = forces.dmoments.col(p);
      dS.tail(k) = forces.dpoint_forces.col(p);
      const double a = r.alpha[p];
      Eigen::VectorXd dalpha = Eigen::VectorXd::Zero(size);
      dalpha.segment<2>(0) = ((a - 1.0) / f.sj) * f.t;
      dalpha[2] = (f.v[p] - a * f.vj) / f.sj;
      dalpha.segment<2>(3) = (-a / f.sj) * f.t;
      dalpha.segment<2>(6 + 3 * p) = f.t / f.sj;
      r.sliding_u.col(p) = J * dS;
      r.sliding_v.col(p) = dalpha;
    }
    r.tangent += r.sliding_u * r.sliding_v.transpose();
  }
  return r;
}

}  // namespace tsm::contact
