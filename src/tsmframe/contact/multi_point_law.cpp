#include "tsmframe/contact/multi_point_law.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "tsmframe/contact/contact_force_law.hpp"

namespace tsm::contact {
namespace {

/// K5's numerator A(u, v, m) and its partial derivatives at l0 held (K9), for the lengths u (node
/// i to the left point), v (the right point to node j) and m (between the points).
struct InfluenceTerms {
  double value = 0.0, du = 0.0, dv = 0.0, dm = 0.0;
};
InfluenceTerms influence_terms(double psi, double l0, double u, double v, double m) {
  const double uv = u * v;
  const double q = u * u + v * v + 3.0 * uv + 3.0 * m * (u + v);
  const double p = uv * (3.0 * l0 * m + 2.0 * uv) + 6.0 * psi * q + 72.0 * psi * psi;  // K5
  InfluenceTerms t;
  t.value = uv * p;
  t.du = v * p + uv * (v * (3.0 * l0 * m + 4.0 * uv) + 6.0 * psi * (2.0 * u + 3.0 * v + 3.0 * m));  // K9
  t.dv = u * p + uv * (u * (3.0 * l0 * m + 4.0 * uv) + 6.0 * psi * (2.0 * v + 3.0 * u + 3.0 * m));
  t.dm = uv * (3.0 * l0 * uv + 18.0 * psi * (u + v));
  return t;
}

/// A's second partial derivatives (A is linear in m: ∂²A/∂m² = 0), N17.
struct InfluenceSecondTerms {
  double uu = 0.0, vv = 0.0, uv = 0.0, um = 0.0, vm = 0.0;
};
InfluenceSecondTerms influence_second_terms(double psi, double l0, double u, double v, double m) {
  InfluenceSecondTerms t;
  t.uu = 6.0 * l0 * m * v * v + 12.0 * u * v * v * v + 36.0 * psi * v * (u + v + m);  // N17
  t.vv = 6.0 * l0 * m * u * u + 12.0 * u * u * u * v + 36.0 * psi * u * (u + v + m);
  t.uv = 12.0 * l0 * m * u * v + 18.0 * u * u * v * v +
         6.0 * psi * (3.0 * u * u + 3.0 * v * v + 12.0 * u * v + 6.0 * m * (u + v)) + 72.0 * psi * psi;
  t.um = 6.0 * l0 * u * v * v + 18.0 * psi * v * (2.0 * u + v);
  t.vm = 6.0 * l0 * u * u * v + 18.0 * psi * u * (2.0 * v + u);
  return t;
}

double influence_denominator(const element::SectionStiffness& section, double l0) {
  return 6.0 * section.EI * l0 * (l0 * l0 + 12.0 * section.shear_flexibility);  // K5
}

bool inside(double alpha) { return alpha >= 0.0 && alpha <= 1.0; }

/// The pair floor (K11) on C̃ (the diagonal floor applied): every pair whose difference-mode
/// compliance d_pq is below the floor gets ε_pq (e_p − e_q)(e_p − e_q)ᵀ, ε_pq = (floor − d_pq)/4,
/// and its α-derivatives. d_pq and its derivatives are all taken from C̃ before any pair is added.
void apply_pair_floor(MultiPointLaw& law, double floor) {
  const int k = law.size();
  struct Binding {
    int p, q;
    double epsilon, depsilon_p, depsilon_q;
  };
  std::vector<Binding> bindings;
  const Eigen::MatrixXd& C = law.compliance;
  for (int p = 0; p < k; ++p)
    for (int q = p + 1; q < k; ++q) {
      const double d = C(p, p) + C(q, q) - 2.0 * C(p, q);
      if (!(d < floor)) continue;
      const double dd_p = law.dcompliance.rows(p, p) - 2.0 * law.dcompliance.rows(p, q);
      const double dd_q = law.dcompliance.rows(q, q) - 2.0 * law.dcompliance.rows(q, p);
      bindings.push_back({p, q, 0.25 * (floor - d), -0.25 * dd_p, -0.25 * dd_q});
    }
  auto add_pair = [](Eigen::MatrixXd& m, int p, int q, double value) {
    m(p, p) += value;
    m(q, q) += value;
    m(p, q) -= value;
    m(q, p) -= value;
  };
  // ∂C/∂α_p gains the pair's (e_p − e_q)(e_p − e_q)ᵀ ∂ε/∂α_p: in row p, and at C_qq.
  auto add_rate = [&law](int p, int q, double value) {
    law.dcompliance.rows(p, p) += value;
    law.dcompliance.rows(p, q) -= value;
    law.dcompliance.diagonals.push_back({p, q, value});
  };
  for (const Binding& b : bindings) {
    add_pair(law.compliance, b.p, b.q, b.epsilon);
    add_rate(b.p, b.q, b.depsilon_p);
    add_rate(b.q, b.p, b.depsilon_q);
  }
}

}  // namespace

Eigen::VectorXd ComplianceRates::times(int p, const Eigen::VectorXd& Y) const {
  Eigen::VectorXd out = rows.row(p).transpose() * Y[p];  // column p
  out[p] += rows.row(p).dot(Y) - rows(p, p) * Y[p];      // row p, its diagonal once
  for (const Diagonal& d : diagonals)
    if (d.p == p) out[d.q] += d.value * Y[d.q];
  return out;
}

Eigen::MatrixXd ComplianceRates::dense(int p) const {
  const Eigen::Index k = rows.rows();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(k, k);
  m.row(p) = rows.row(p);
  m.col(p) = rows.row(p).transpose();
  for (const Diagonal& d : diagonals)
    if (d.p == p) m(d.q, d.q) += d.value;
  return m;
}

double clamped_influence(const element::SectionStiffness& section, double l0, double x, double xi) {
  const double left = std::clamp(std::min(x, xi), 0.0, l0), right = std::clamp(std::max(x, xi), 0.0, l0);
  const InfluenceTerms t = influence_terms(section.shear_flexibility, l0, left, l0 - right, right - left);
  return t.value / influence_denominator(section, l0);  // K5
}

double clamped_influence_slope(const element::SectionStiffness& section, double l0, double x, double xi) {
  if (!(x >= 0.0 && x <= l0)) return 0.0;
  const double other = std::clamp(xi, 0.0, l0);
  const double left = std::min(x, other), right = std::max(x, other);
  const InfluenceTerms t = influence_terms(section.shear_flexibility, l0, left, l0 - right, right - left);
  // x the left point: u = x, m = ξ − x; the right point: v = l0 − x, m = x − ξ (K9). Where the
  // points meet (a jump for Timoshenko) the mean of the two one-sided slopes.
  const double as_left = t.du - t.dm, as_right = t.dm - t.dv;
  const double slope = x < other ? as_left : x > other ? as_right : 0.5 * (as_left + as_right);
  return slope / influence_denominator(section, l0);
}

double clamped_influence_curvature(const element::SectionStiffness& section, double l0, double x, double xi) {
  if (!(x >= 0.0 && x <= l0)) return 0.0;
  const double other = std::clamp(xi, 0.0, l0);
  const double left = std::min(x, other), right = std::max(x, other);
  const InfluenceSecondTerms t = influence_second_terms(section.shear_flexibility, l0, left, l0 - right, right - left);
  // N17: x the left point (u = x, m = ξ − x): A_uu − 2A_um; the right point (v = l0 − x,
  // m = x − ξ): A_vv − 2A_vm (A_mm = 0). Equal where the points meet.
  const double second = x <= other ? t.uu - 2.0 * t.um : t.vv - 2.0 * t.vm;
  return second / influence_denominator(section, l0);
}

double clamped_influence_cross_slope(const element::SectionStiffness& section, double l0, double x, double xi) {
  if (!(x >= 0.0 && x <= l0) || !(xi >= 0.0 && xi <= l0)) return 0.0;
  const double left = std::min(x, xi), right = std::max(x, xi);
  const InfluenceSecondTerms t = influence_second_terms(section.shear_flexibility, l0, left, l0 - right, right - left);
  // N17: ∂/∂ξ of ∂C/∂x. x left (ξ moves m and v): A_um − A_uv + A_vm; x right (ξ moves u and m):
  // A_um − A_uv + A_vm as well (A_mm = 0) — one expression, symmetric in x and ξ.
  return (t.um - t.uv + t.vm) / influence_denominator(section, l0);
}

double compliance_floor(const element::SectionStiffness& section, double l0, double edge, double min_compliance) {
  // K10: an Euler–Bernoulli point at edge·l0 from a node, or the stiffness cap (point_load_law's floor).
  return std::max(std::pow(edge * (1.0 - edge) * l0, 3) / (3.0 * section.EI), min_compliance);
}

MultiPointLaw multi_point_law(const element::SectionStiffness& section, double l0, const Eigen::VectorXd& alpha,
                              double edge, double min_compliance) {
  const int k = static_cast<int>(alpha.size());
  MultiPointLaw law;
  law.h.setZero(2, k);
  law.dh.setZero(2, k);
  law.compliance.setZero(k, k);
  law.dcompliance.rows.setZero(k, k);
  for (int p = 0; p < k; ++p) {  // each point alone: point_load_law, its floor included (K4, K10)
    const PointLoadLaw point = point_load_law(section, l0, alpha[p], edge, min_compliance);
    law.h.col(p) << point.h_i, point.h_j;
    law.dh.col(p) << point.dh_i, point.dh_j;
    law.compliance(p, p) = point.compliance;
    law.dcompliance.rows(p, p) = point.dcompliance;
  }
  for (int p = 0; p < k; ++p)  // the points' coupling through the clamped beam (K5, K9)
    for (int q = p + 1; q < k; ++q) {
      const double x = std::clamp(alpha[p], 0.0, 1.0) * l0, xi = std::clamp(alpha[q], 0.0, 1.0) * l0;
      law.compliance(p, q) = law.compliance(q, p) = clamped_influence(section, l0, x, xi);
      const double dp = inside(alpha[p]) ? l0 * clamped_influence_slope(section, l0, x, xi) : 0.0;
      const double dq = inside(alpha[q]) ? l0 * clamped_influence_slope(section, l0, xi, x) : 0.0;
      law.dcompliance.rows(p, q) = dp;
      law.dcompliance.rows(q, p) = dq;
    }
  apply_pair_floor(law, compliance_floor(section, l0, edge, min_compliance));  // K11
  return law;
}

ConnectedMultiPointLaw connected_multi_point_law(const MultiPointLaw& law, const Eigen::Matrix2d& k_plain,
                                                 double flexibility_i, double flexibility_j) {
  const double flexibility[2] = {flexibility_i, flexibility_j};
  const int k = law.size();
  ConnectedMultiPointLaw out{law, k_plain};
  Eigen::Matrix2Xd& H = out.law.h;
  Eigen::Matrix2Xd& dH = out.law.dh;
  Eigen::MatrixXd& C = out.law.compliance;
  Eigen::Matrix2d& K = out.k_plain;
  // Hinges, one end at a time (K12a): M_r = 0 condenses θ_e,r out; row and column r of K and row
  // r of H become zero, C gains H_rᵀ H_r / K_rr.
  for (int r = 0; r < 2; ++r) {
    if (!std::isinf(flexibility[r]) || !(K(r, r) > 0.0)) continue;
    const Eigen::Vector2d column = K.col(r);
    const double krr = K(r, r);
    const Eigen::RowVectorXd Hr = H.row(r), dHr = dH.row(r);
    C += Hr.transpose() * Hr / krr;
    for (int p = 0; p < k; ++p) {  // row p and column p: twice on the diagonal
      out.law.dcompliance.rows.row(p) += dHr[p] * Hr / krr;
      out.law.dcompliance.rows(p, p) += dHr[p] * Hr[p] / krr;
    }
    H -= column * Hr / krr;
    dH -= column * dHr / krr;
    K -= column * column.transpose() / krr;
    H.row(r).setZero();  // exactly, not by cancellation
    dH.row(r).setZero();
  }
  // Springs on the other ends (K12b): A = (I + K F)⁻¹, K' = A K, H' = A H, C' = C + Hᵀ F A H.
  Eigen::Matrix2d F = Eigen::Matrix2d::Zero();
  for (int r = 0; r < 2; ++r)
    if (!std::isinf(flexibility[r])) F(r, r) = flexibility[r];
  const Eigen::Matrix2d A = (Eigen::Matrix2d::Identity() + K * F).inverse();
  const Eigen::Matrix2Xd G = A * H, FG = F * G;
  for (int p = 0; p < k; ++p) {
    const Eigen::VectorXd w = FG.transpose() * dH.col(p);  // ∂(Hᵀ F A H)/∂α_p = e_p wᵀ + w e_pᵀ
    out.law.dcompliance.rows.row(p) += w.transpose();
    out.law.dcompliance.rows(p, p) += w[p];
  }
  Eigen::MatrixXd added = H.transpose() * FG;
  C += 0.5 * (added + added.transpose());  // symmetric up to rounding
  dH = A * dH;
  H = G;
  K = A * K;
  K(0, 1) = K(1, 0) = 0.5 * (K(0, 1) + K(1, 0));
  return out;
}

PointForceMap point_force_map(const MultiPointLaw& law) {
  const int k = law.size();
  PointForceMap map;
  map.P = Eigen::MatrixXd::Zero(3 + k, k);
  map.P.middleRows(1, 2) = law.h;
  map.P.bottomRows(k).setIdentity();
  map.stiffness = k > 0 ? Eigen::MatrixXd(law.compliance.llt().solve(Eigen::MatrixXd::Identity(k, k))) : Eigen::MatrixXd(0, 0);
  map.stiffness = 0.5 * (map.stiffness + map.stiffness.transpose()).eval();
  return map;
}

Eigen::MatrixXd law_tangent(const PointForceMap& map, double axial, const Eigen::Matrix2d& k_plain) {
  Eigen::MatrixXd D = map.P * map.stiffness * map.P.transpose();  // K14
  D(0, 0) += axial;
  D.block<2, 2>(1, 1) += k_plain;
  return D;
}

MultiPointForces multi_point_forces(const MultiPointLaw& law, const Eigen::Matrix2d& k_plain,
                                    const Eigen::Vector2d& theta, const Eigen::VectorXd& deflections) {
  const int k = law.size();
  MultiPointForces f;
  f.point_forces.setZero(k);
  f.dmoments.setZero(2, k);
  f.dpoint_forces.setZero(k, k);
  if (k > 0) {
    const Eigen::LLT<Eigen::MatrixXd> C(law.compliance);
    f.point_forces = C.solve(deflections + law.h.transpose() * theta);  // K2
    Eigen::MatrixXd rhs(k, k);  // K13: column p, −∂C/∂α_p Y + e_p ∂h_pᵀθ
    for (int p = 0; p < k; ++p) {
      rhs.col(p) = -law.dcompliance.times(p, f.point_forces);
      rhs(p, p) += law.dh.col(p).dot(theta);
    }
    f.dpoint_forces = C.solve(rhs);
    f.dmoments = law.dh * f.point_forces.asDiagonal();
    f.dmoments += law.h * f.dpoint_forces;
  }
  f.moments = k_plain * theta + law.h * f.point_forces;  // K2
  return f;
}

}  // namespace tsm::contact
