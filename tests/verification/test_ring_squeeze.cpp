// A ring squeezed between two plates (contacts on many nodes at once, two of them resting on
// plate nodes from the start) against the exact elastica of a ring under two opposite point
// loads, and against the linear ring formula for a small squeeze.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "support/models.hpp"
#include "support/rk4.hpp"

namespace test_ring_squeeze {
namespace {

using namespace tsm::test;
using tsm::solver::RunResult;
using tsm::solver::StepRecord;

using std::numbers::pi;
constexpr double E = 2e11, ring_I = 1e-7, R = 1.0, gap = 0.01;

/// A steel ring (radius 1, centre at the origin, two half-circle members of `n` elements from
/// its bottom node to its top node) between two plates 3 m long clamped at their ends, drawn
/// at the gap below and above it; the upper plate's ends move down by `squeeze` in `steps`.
/// Every ring node is a contact node on both plates (`"nodes": {"members": [0, 1]}`); the
/// bottom and top nodes rest on the plates' middle nodes from the start, held across by ux.
json squeezed_ring(int n, double squeeze, int steps) {
  json m = {{"materials", {{"steel", {{"E", E}, {"nu", 0.3}}}}},
            {"sections", {{"ring", {{"A", 1e-3}, {"I", ring_I}}}, {"plate", {{"A", 0.1}, {"I", 1e-4}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", -R}},
                                   {{"id", 2}, {"x", 0.0}, {"y", R}},
                                   {{"id", 101}, {"x", -1.5}, {"y", -R - gap}},
                                   {{"id", 102}, {"x", 1.5}, {"y", -R - gap}},
                                   {{"id", 103}, {"x", -1.5}, {"y", R + gap}},
                                   {{"id", 104}, {"x", 1.5}, {"y", R + gap}}})},
            {"supports", json::array({{{"node", 101}, {"type", "fixed"}}, {{"node", 102}, {"type", "fixed"}},
                                      {{"node", 103}, {"type", "fixed"}}, {{"node", 104}, {"type", "fixed"}},
                                      {{"node", 1}, {"fix", {"ux"}}}, {{"node", 2}, {"fix", {"ux"}}}})},
            {"prescribed", json::array({{{"node", 103}, {"uy", -squeeze}}, {{"node", 104}, {"uy", -squeeze}}})},
            {"analysis", {{"control", {{"type", "load"}, {"steps", steps}}}, {"output", "last"}}}};
  const auto half = [&](int from, int to) {
    return json{{"from", from}, {"to", to}, {"divisions", n}, {"arc", {{"center", {0.0, 0.0}}, {"sweep", pi}}},
                {"material", "steel"}, {"section", "ring"}};
  };
  const auto plate = [](int from, int to) {
    return json{{"from", from}, {"to", to}, {"divisions", 30}, {"material", "steel"}, {"section", "plate"}};
  };
  m["members"] = json::array({half(1, 2), half(2, 1), plate(101, 102), plate(103, 104)});
  // Every ring node may touch either plate: one entry for them all.
  m["contacts"] = json::array({{{"nodes", {{"members", {0, 1}}}}, {"members", {2, 3}}, {"gap", gap}}});
  return m;
}

// ---- The exact elastica: a quarter of the ring from the top point to the side ----
// Inextensible, EI θ' = M(s) − EI/R with θ(0) = 0 (tangent horizontal at the top, by symmetry),
// M(s) = M0 − (P/2) x(s) (half the load P on each half; no horizontal force at the top, by the
// top–bottom symmetry), and θ(πR/2) = −π/2 (tangent vertical at the side, by symmetry). For a
// load P, M0 follows by bisection; the squeeze is 2 (R − |y(πR/2)|) and the side's outward move
// x(πR/2) − R.
struct QuarterEnd {
  double theta, x, y;
};

QuarterEnd integrate_quarter(double P, double M0, double EI) {
  auto f = [&](const std::array<double, 3>& q) {  // q = (θ, x, y)
    return std::array<double, 3>{(M0 - 0.5 * P * q[1]) / EI - 1.0 / R, std::cos(q[0]), std::sin(q[0])};
  };
  const int steps = 1000;
  const double ds = pi * R / 2 / steps;
  std::array<double, 3> q = {0.0, 0.0, 0.0};
  for (int k = 0; k < steps; ++k) q = rk4_step(f, q, ds);
  return {q[0], q[1], q[2]};
}

QuarterEnd quarter_for_load(double P, double EI, double* M0_out = nullptr) {
  double lo = -P * R, hi = P * R;  // θ(end) rises with M0
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (integrate_quarter(P, mid, EI).theta < -pi / 2 ? lo : hi) = mid;
  }
  if (M0_out) *M0_out = 0.5 * (lo + hi);
  return integrate_quarter(P, 0.5 * (lo + hi), EI);
}

/// The load that squeezes the ring by `squeeze`, and the side's outward move there.
std::array<double, 2> elastica_squeeze(double squeeze, double EI, double* M0 = nullptr) {
  double lo = 0.0, hi = 10.0 * EI / (R * R);  // far beyond a squeeze of the diameter
  for (int it = 0; it < 55; ++it) {
    const double mid = 0.5 * (lo + hi);
    (2.0 * (R - std::abs(quarter_for_load(mid, EI).y)) < squeeze ? lo : hi) = mid;
  }
  const double P = 0.5 * (lo + hi);
  return {P, quarter_for_load(P, EI, M0).x - R};
}

int node_at(const tsm::Model& model, double x, double y) {
  for (size_t k = 0; k < model.nodes.size(); ++k)
    if ((model.nodes[k].position - Eigen::Vector2d(x, y)).norm() < 1e-9) return static_cast<int>(k);
  return -1;
}

TEST(RingSqueeze, TheElasticaReferenceTendsToTheLinearRing) {
  // Two opposite loads P on a ring: the diameter between them shortens by (π/4 − 2/π) PR³/EI
  // and the other lengthens by (2/π − 1/2) PR³/EI (Roark).
  const double EI = E * ring_I, squeeze = 1e-6;
  const auto [P, side] = elastica_squeeze(squeeze, EI);
  EXPECT_NEAR(P, squeeze * EI / ((pi / 4 - 2 / pi) * R * R * R), 1e-4 * P);
  EXPECT_NEAR(2.0 * side, (2 / pi - 0.5) * P * R * R * R / EI, 1e-3 * 2.0 * side);
}

TEST(RingSqueeze, SqueezedBy15PercentItCarriesTheElasticasLoad) {
  // 0.3 m off a 2 m diameter in 10 steps, 80 ring elements: the contact force against the
  // exact elastica's load for that squeeze (the ring's stretch and the plates' bending, 1e-4 of
  // it here, and the polygon's O(1/n²) left out of the reference: 0.5 %), the side's outward
  // move likewise; top and bottom carry the same to the rounding of their stiff contacts. The
  // other contact nodes do not touch: the ring is still convex at the top (the elastica's
  // curvature there, M0/EI − 1/R, is negative), so it touches each plate at one point.
  const double EI = E * ring_I, squeeze = 0.3;
  double M0 = 0.0;
  const auto [P, side] = elastica_squeeze(squeeze, EI, &M0);
  ASSERT_LT(M0 / EI - 1.0 / R, 0.0) << "the reference holds while the ring touches at a point";
  tsm::Model model;
  const RunResult r = run(squeezed_ring(40, squeeze, 10), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  int touching = 0;
  double bottom = 0.0, top = 0.0;
  for (size_t k = 0; k < last.contacts.size(); ++k) {
    if (last.contacts[k].element < 0) continue;
    ++touching;
    const int node = model.contacts[k].node;
    (model.nodes[node].position.y() < 0.0 ? bottom : top) += last.contacts[k].force;
  }
  EXPECT_EQ(touching, 2);
  std::printf("[figure] ring squeezed 15 %%: P = %.1f N (elastica %.1f), side out %.5f m (elastica %.5f)\n", top, P,
              node_displacement(model, last, model.nodes[node_at(model, R, 0.0)].id)[0], side);
  EXPECT_NEAR(top, P, 5e-3 * P);
  EXPECT_NEAR(bottom, top, 1e-4 * top);
  const int side_node = node_at(model, R, 0.0);
  ASSERT_GE(side_node, 0);
  EXPECT_NEAR(node_displacement(model, last, model.nodes[side_node].id)[0], side, 5e-3 * side);
}

TEST(RingSqueeze, ASmallSqueezeCarriesTheLinearRingsLoad) {
  // 1 mm: P = δ / ((π/4 − 2/π) R³/EI + 2 L³/192 EI_plate) — the ring and both plates (clamped,
  // 3 m, loaded at mid-span) in series; the polygon of 40 elements to O(1/n²), 1 %.
  const double EI = E * ring_I, squeeze = 1e-3, plate = 27.0 / (192.0 * E * 1e-4);
  const double P = squeeze / ((pi / 4 - 2 / pi) * R * R * R / EI + 2.0 * plate);
  tsm::Model model;
  const RunResult r = run(squeezed_ring(20, squeeze, 1), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  double top = 0.0;
  for (size_t k = 0; k < r.steps.back().contacts.size(); ++k)
    if (model.nodes[model.contacts[k].node].position.y() > 0.0) top += r.steps.back().contacts[k].force;
  EXPECT_NEAR(top, P, 1e-2 * P);
}

}  // namespace

namespace {

/// Two rings of radius 1 (60 and 61 elements, EI 2e3) one above the other, 2 cm apart: the lower
/// held at its bottom node, the upper hung from its top node, which a prescribed displacement
/// moves down by `push`; every node of each ring a contact node on the other ring.
json stacked_rings(double push, int steps) {
  return {{"materials", {{"steel", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"sections", {{"s", {{"A", 1e-3}, {"I", 1e-8}}}}},
          {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", -1.0}}, {{"id", 2}, {"x", 0.0}, {"y", 3.02}}})},
          {"members", json::array({{{"from", 1}, {"to", 1}, {"arc", {{"center", {0.0, 0.0}}, {"sweep", 2.0 * pi}}},
                                    {"divisions", 60}, {"material", "steel"}, {"section", "s"}},
                                   {{"from", 2}, {"to", 2}, {"arc", {{"center", {0.0, 2.02}}, {"sweep", 2.0 * pi}}},
                                    {"divisions", 61}, {"material", "steel"}, {"section", "s"}}})},
          {"supports", json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 2}, {"fix", {"ux", "rz"}}}})},
          {"prescribed", json::array({{{"node", 2}, {"uy", -push}}})},
          {"contacts", json::array({{{"nodes", {{"members", {1}}}}, {"members", {0}}},
                                    {{"nodes", {{"members", {0}}}}, {"members", {1}}}})},
          {"analysis", {{"control", {{"type", "load"}, {"steps", steps}}}}}};
}

TEST(StackedRings, PressedTogetherTheyCarryTwoLinearRingsInSeries) {
  // The lower ring's top node first meets the upper ring's lowest chord, 2.1326 cm below it
  // (2 cm + 1 − cos(π/61)); pushed 1 mm further, the force is that of two rings under diametral
  // point loads in series, δ = 2 (π/4 − 2/π) P R³/EI (Roark), to the polygons' and the 1 mm's
  // geometric effects (2e-3 measured; 5e-3 allowed). Found as a user: the upper ring moves as a
  // rigid body until they touch, its forces rounding alone, whose moments on the ring's inclined
  // chords the rounding floor did not cover (the run failed, "the loads are too small …").
  const double closing = 0.02 + 1.0 - std::cos(pi / 61.0), EI = 2e11 * 1e-8;
  tsm::Model model;
  const RunResult r = run(stacked_rings(closing + 1e-3, 2), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const StepRecord& last = r.steps.back();
  const double P = -last.reactions[3 * model.node_index(2) + 1];
  EXPECT_NEAR(P, 1e-3 / (2.0 * (pi / 4.0 - 2.0 / pi) / EI), 5e-3 * P);
  int touching = 0;
  for (const tsm::solver::ContactPoint& c : last.contacts) touching += c.element >= 0;
  EXPECT_EQ(touching, 1);
  expect_global_equilibrium(model, last, 1e-9);
  // Half a metre down in 20 steps: the rings flatten against each other (2.75 kN).
  const RunResult far = run(stacked_rings(0.5, 20), model);
  ASSERT_EQ(far.status, tsm::solver::Status::converged) << far.message;
  expect_global_equilibrium(model, far.steps.back(), 1e-8);
}

}  // namespace

}  // namespace test_ring_squeeze
