#include "tsmframe/contact/contact_element.hpp"

namespace tsm::contact {
namespace {

using element::Vector6;

}  // namespace

ContactEquilibriumMatrix contact_equilibrium_matrix(const element::Chord& chord, double alpha) {
  ContactEquilibriumMatrix J = ContactEquilibriumMatrix::Zero();
  J.topLeftCorner<6, 3>() = element::equilibrium_matrix(chord);
  const Eigen::Vector2d n(-chord.sin, chord.cos);
  J.col(3) = spread(-(1.0 - alpha) * n, -alpha * n, n);
  return J;
}

ChordFrameLaw chord_frame_law(const ContactElementData& data, double alpha) {
  ChordFrameLaw law;
  law.raw = point_load_law(data.section, data.initial.length, alpha, data.edge, data.min_compliance);  // Eq. 6–9, split
  law.connected = law.raw;
  law.k_plain = data.k0.bottomRightCorner<2, 2>();
  if (data.connected()) {  // a hinge or a spring between an end and its node: condensed out
    const ConnectedLaw c = connected_law(law.raw, law.k_plain, data.flexibility_i, data.flexibility_j);
    law.connected = c.law;
    law.k_plain = c.k_plain;
  }
  return law;
}

ContactResponse chord_frame_response(const ContactElementData& data, const Vector9& d, double previous_rotation,
                                     bool with_tangent) {
  ContactResponse r = chord_frame_parts(data, d, previous_rotation, with_tangent);
  if (data.friction.mu != 0.0) add_friction(data, 0.0, Vector9::Zero(), with_tangent, r);
  if (!with_tangent) return r;
  r.tangent = r.symmetric_tangent + r.sliding_u * r.sliding_v.transpose();
  if (data.friction.mu != 0.0) r.tangent.noalias() += r.friction_u * r.friction_v.transpose();
  return r;
}

ContactResponse chord_frame_parts(const ContactElementData& data, const Vector9& d, double previous_rotation,
                                  bool with_tangent) {
  ContactResponse r;
  const Vector6 beam = d.head<6>();
  r.chord = element::current_chord(data.initial, beam, previous_rotation);
  const double l = r.chord.length;
  const Eigen::Vector2d e(r.chord.cos, r.chord.sin), n(-r.chord.sin, r.chord.cos);
  // r = x_c − x_i formed as (X_c − X_i) + (u_c − u_i): no large coordinates cancel.
  const Eigen::Vector2d rel = (data.contact_start - data.initial.start) + Eigen::Vector2d(d[6] - d[0], d[7] - d[1]);
  r.alpha = rel.dot(e) / l;
  r.normal = rel.dot(n);
  const double theta_i = d[2] - r.chord.rotation, theta_j = d[5] - r.chord.rotation;
  r.deformations << r.chord.elongation, theta_i, theta_j, r.normal - data.offset;

  r.law = chord_frame_law(data, r.alpha);
  const PointLoadLaw& law = r.law.connected;
  const Eigen::Matrix2d& k_plain = r.law.k_plain;
  const Eigen::Vector2d h(law.h_i, law.h_j), theta(theta_i, theta_j);
  const double Y = (r.deformations[3] + h.dot(theta)) / law.compliance;
  const Eigen::Vector2d moments = k_plain * theta + h * Y;
  r.forces << data.k0(0, 0) * r.chord.elongation, moments, Y;

  const ContactEquilibriumMatrix J = contact_equilibrium_matrix(r.chord, r.alpha);
  r.nodal_forces = J * r.forces;
  r.point_u = J * Vector4(0.0, law.h_i, law.h_j, 1.0);
  r.point_stiffness = 1.0 / law.compliance;
  if (!with_tangent) return r;

  // ∂S/∂d: the plain element's k0 plus the point load's rank-one part (h, 1)(h, 1)ᵀ / c.
  Eigen::Matrix4d D = Eigen::Matrix4d::Zero();
  D(0, 0) = data.k0(0, 0);
  Eigen::Vector4d point(0.0, law.h_i, law.h_j, 1.0);
  D += point * point.transpose() / law.compliance;
  D.block<2, 2>(1, 1) += k_plain;
  Matrix9& K = r.symmetric_tangent;
  const ContactEquilibriumMatrix JD = J * D;
  K.noalias() = JD.lazyProduct(J.transpose());  // a 9×4×9 product: coefficient by coefficient

  // K_G: N ∂²l + (M_i + M_j) ∂²(−β) on i, j, and Y ∂²δy_c on the translations of i, j, c.
  K.topLeftCorner<6, 6>() += element::geometric_stiffness(r.chord, r.forces.head<3>());
  const double rho = r.normal;
  const Vector9 a1 = spread(-n, n, Eigen::Vector2d::Zero());  // n · dΔ
  const Vector9 a2 = spread(-e, Eigen::Vector2d::Zero(), e);  // e · dr
  const Vector9 a3 = spread(-e, e, Eigen::Vector2d::Zero());  // e · dΔ
  // Y ∂²δy_c = −(Y/l) [a1 a2ᵀ + a2 a1ᵀ + (ρ/l) a1 a1ᵀ − α (a1 a3ᵀ + a3 a1ᵀ)] = −(Y/l) (a1 bᵀ + b a1ᵀ).
  const Vector9 b = a2 + (0.5 * rho / l) * a1 - r.alpha * a3;
  add_symmetric(K, (-Y / l) * a1, b);

  if (data.sliding_term) {
    // a, b follow the geometry: J (∂S/∂α)(∂α/∂x)ᵀ (FORMULATION §2).
    const double dY = (law.dh_i * theta_i + law.dh_j * theta_j) / law.compliance - Y * law.dcompliance / law.compliance;
    const Vector4 dS(0.0, law.dh_i * Y + law.h_i * dY, law.dh_j * Y + law.h_j * dY, dY);
    const Vector9 dalpha = spread(((r.alpha - 1.0) / l) * e - (rho / (l * l)) * n,
                                  (rho / (l * l)) * n - (r.alpha / l) * e, e / l);
    r.sliding_u = J * dS;
    r.sliding_v = dalpha;
  }
  return r;
}

double alpha_on_element(const element::InitialChord& initial, const element::Vector6& d,
                        const Eigen::Vector2d& node_position) {
  return element::chord_frame(initial, d).alpha(node_position);
}

NodeOnElement node_on_element(const element::InitialChord& initial, const element::SectionStiffness& section,
                              const element::Vector6& d, double chord_rotation, const Eigen::Vector2d& node_position,
                              double flexibility_i, double flexibility_j) {
  const element::Chord chord = element::current_chord(initial, d, chord_rotation);
  const Eigen::Vector2d n(-chord.sin, chord.cos);
  const Eigen::Vector2d rel = node_position - (initial.start + d.head<2>());
  NodeOnElement out;
  out.alpha = alpha_on_element(initial, d, node_position);
  std::array<double, 2> h = point_load_moments(section, initial.length, out.alpha);
  if (flexibility_i != 0.0 || flexibility_j != 0.0) {  // w from the nodes' rotations through the connections
    const PointLoadLaw law = connected_law(point_load_law(section, initial.length, out.alpha, 0.25),
                                           element::basic_stiffness(section, initial.length).bottomRightCorner<2, 2>(),
                                           flexibility_i, flexibility_j).law;
    h = {law.h_i, law.h_j};
  }
  const double w = -(h[0] * (d[2] - chord.rotation) + h[1] * (d[5] - chord.rotation));
  out.gap = rel.dot(n) - w;
  return out;
}

}  // namespace tsm::contact
