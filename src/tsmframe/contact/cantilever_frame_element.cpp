#include "tsmframe/contact/cantilever_frame_element.hpp"

#include <algorithm>
#include <cmath>

namespace tsm::contact {

LoadShare cantilever_load_share(double psi, double l0, double alpha) {
  const double s = std::clamp(alpha, 0.0, 1.0), a = s * l0, b = (1.0 - s) * l0, span = l0 * l0 + 12.0 * psi;
  LoadShare g;
  g.q = -(a * a * a + 3.0 * a * a * b + 12.0 * psi * a) / (l0 * span);
  g.m = (a * a * b * l0 + 6.0 * psi * a * b) / (l0 * span);
  if (alpha >= 0.0 && alpha <= 1.0) {
    g.dq = -(6.0 * a * b + 12.0 * psi) / span;
    g.dm = (l0 * a * (2.0 * b - a) + 6.0 * psi * (b - a)) / span;
  }
  return g;
}

element::Matrix3 cantilever_bending_stiffness(const element::SectionStiffness& section, double l0, double alpha) {
  const double a = alpha * l0, b = (1.0 - alpha) * l0, psi = section.shear_flexibility;
  const double omega = a * b * a * b + 3.0 * psi * (l0 * l0 + a * b) + 36.0 * psi * psi;  // Eq. 9
  const double f = section.EI / omega;
  element::Matrix3 k;  // rows Q, M, Y; columns v_j, θ_j, v_c (FORMULATION §2b)
  k(0, 0) = f * 3.0 * (a * a * a + 4.0 * a * a * b + 12.0 * psi * l0) / (b * l0);
  k(0, 1) = k(1, 0) = -f * 3.0 * (a * a * a + 2.0 * a * a * b + 12.0 * psi * a + 6.0 * psi * b) / l0;
  k(1, 1) = f * (omega + 3.0 * a * a * b * l0 + 9.0 * psi * (l0 * l0 + a * b)) / l0;
  k(2, 0) = k(0, 2) = -f * 3.0 * (a * (a + 3.0 * b) + 12.0 * psi) / b;
  k(2, 1) = k(1, 2) = f * 3.0 * (a * l0 + 6.0 * psi);
  k(2, 2) = f * 3.0 * l0 * (l0 * l0 + 12.0 * psi) / (a * b);
  return k;
}

Eigen::Matrix2d cantilever_stiffness(const element::SectionStiffness& section, double l0) {
  // Timoshenko cantilever (q = 12Ψ/l0²; Ψ = 0: 12EI/l0³, −6EI/l0², 4EI/l0).
  const double q = 12.0 * section.shear_flexibility / (l0 * l0), f = section.EI / (1.0 + q);
  Eigen::Matrix2d k;
  k << 12.0 * f / (l0 * l0 * l0), -6.0 * f / (l0 * l0), -6.0 * f / (l0 * l0), (4.0 + q) * f / l0;
  return k;
}

ContactResponse cantilever_frame_response(const ContactElementData& data, const Vector9& d, double previous_rotation,
                                          bool with_tangent) {
  ContactResponse r;
  r.chord = element::current_chord(data.initial, d.head<6>(), previous_rotation);
  const double l0 = data.initial.length, psi = data.section.shear_flexibility;
  const double angle = data.initial.angle + d[2];  // ψ = φ0 + Θ_i
  const Eigen::Vector2d t(std::cos(angle), std::sin(angle)), m(-t.y(), t.x());
  const Eigen::Vector2d rj = (data.initial.end - data.initial.start) + Eigen::Vector2d(d[3] - d[0], d[4] - d[1]);
  const Eigen::Vector2d rc = (data.contact_start - data.initial.start) + Eigen::Vector2d(d[6] - d[0], d[7] - d[1]);
  const double sj = rj.dot(t), vj = rj.dot(m), sc = rc.dot(t), vc = rc.dot(m);
  r.alpha = sc / sj;
  r.normal = vc;
  const Vector4 dd(sj - l0, vj, d[5] - d[2], vc - data.offset);
  r.deformations = dd;

  const LoadShare g = cantilever_load_share(psi, l0, r.alpha);
  const PointLoadLaw law = point_load_law(data.section, l0, r.alpha, data.edge, data.min_compliance);  // c: as the chord element's
  const Eigen::Matrix2d kp = cantilever_stiffness(data.section, l0);
  const Eigen::Vector2d gv(g.q, g.m), bend(dd[1], dd[2]);
  const double Y = (dd[3] + gv.dot(bend)) / law.compliance;
  const Eigen::Vector2d qm = kp * bend + gv * Y;
  const Vector4 S(data.k0(0, 0) * dd[0], qm[0], qm[1], Y);  // (N, Q, M, Y)

  ContactEquilibriumMatrix J = ContactEquilibriumMatrix::Zero();  // rows i, j, c × (u, v, θ)
  J.block<2, 1>(0, 0) = -t, J(2, 0) = vj, J.block<2, 1>(3, 0) = t;
  J.block<2, 1>(0, 1) = -m, J(2, 1) = -sj, J.block<2, 1>(3, 1) = m;
  J(2, 2) = -1.0, J(5, 2) = 1.0;
  J.block<2, 1>(0, 3) = -m, J(2, 3) = -sc, J.block<2, 1>(6, 3) = m;
  r.nodal_forces = J * S;
  // Reported in the chord frame: N along the chord, the end moments, Y.
  const Eigen::Vector2d e(r.chord.cos, r.chord.sin);
  r.forces << r.nodal_forces.segment<2>(3).dot(e), r.nodal_forces[2], r.nodal_forces[5], Y;
  r.point_u = J * Vector4(0.0, g.q, g.m, 1.0);
  r.point_stiffness = 1.0 / law.compliance;
  if (!with_tangent) return r;

  Eigen::Matrix4d D = Eigen::Matrix4d::Zero();
  D(0, 0) = data.k0(0, 0);
  const Eigen::Vector4d point(0.0, g.q, g.m, 1.0);
  D += point * point.transpose() / law.compliance;
  D.block<2, 2>(1, 1) += kp;
  r.tangent = J * D * J.transpose();
  // K_G, only in the Θ_i row and column (FORMULATION §2b).
  const double N = S[0], Q = S[1];
  Vector9 row = Vector9::Zero();
  row.segment<2>(0) = -(N * m - Q * t - Y * t);
  row[2] = -(N * sj + Q * vj + Y * vc);
  row.segment<2>(3) = N * m - Q * t;
  row.segment<2>(6) = -Y * t;
  r.tangent.row(2) += row.transpose();
  r.tangent.col(2) += row;
  r.tangent(2, 2) -= row[2];  // the diagonal entry once
  if (data.sliding_term) {
    const double dY = (g.dq * dd[1] + g.dm * dd[2]) / law.compliance - Y * law.dcompliance / law.compliance;
    const Vector4 dS(0.0, g.dq * Y + g.q * dY, g.dm * Y + g.m * dY, dY);
    Vector9 dalpha = Vector9::Zero();
    dalpha.segment<2>(0) = ((r.alpha - 1.0) / sj) * t;
    dalpha[2] = (vc - r.alpha * vj) / sj;
    dalpha.segment<2>(3) = (-r.alpha / sj) * t;
    dalpha.segment<2>(6) = t / sj;
    r.sliding_u = J * dS;
    r.sliding_v = dalpha;
  }
  r.symmetric_tangent = r.tangent;
  r.tangent += r.sliding_u * r.sliding_v.transpose();
  return r;
}

}  // namespace tsm::contact
