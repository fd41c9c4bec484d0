// The N, V, M diagrams of a solved model (io/section_diagrams) against statics: a cantilever bent
// far by a tip load, where the moment at every node is the load times its lever in the deformed
// geometry and the chord's N and V are the load's components; and a load riding on a simply
// supported beam stopped inside an element, where V jumps by the load under it and M peaks at
// P a b / L.
#include <gtest/gtest.h>

#include <cmath>

#include "support/models.hpp"
#include "tsmframe/io/section_diagrams.hpp"

namespace {

using namespace tsm::test;

TEST(SectionDiagrams, ACantileverBentFarByATipLoadCarriesItsLoadsLeverAtEverySection) {
  // L = 4, EI = 1e4, P = 2,000 down at the tip: the tip drops ~0.6 L. Dead load, exact statics in
  // the deformed geometry: at a section at x, M = −P (x_tip − x) (hogging), and on an element
  // whose chord makes φ with x, N = −P sin φ, V = dM/dx along the chord = P cos φ.
  const double P = 2000.0, L = 4.0;
  json m = beam_model({.L = L, .E = 1e4, .G = 1e4, .A = 1e4, .I = 1.0, .shear_area = 1e4, .divisions = 16});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"fy", -P}}});
  m["analysis"]["control"] = {{"type", "load"}, {"steps", 8}};
  tsm::Model model;
  const auto r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const tsm::solver::StepRecord& last = r.steps.back();
  const Eigen::Vector2d tip = node_position(model, last, 2);
  ASSERT_LT(tip.x(), 0.9 * L);  // bent far: statics in the drawn geometry would be off by > 10 %
  const auto diagrams = tsm::io::section_diagrams(model, last);
  for (size_t e = 0; e < model.elements.size(); ++e) {
    const tsm::Element& element = model.elements[e];
    const Eigen::Vector2d a = node_position(model, last, model.nodes[element.start].id);
    const Eigen::Vector2d b = node_position(model, last, model.nodes[element.end].id);
    const Eigen::Vector2d chord = (b - a).normalized();
    ASSERT_EQ(diagrams[e].size(), 2u);
    const auto& start = diagrams[e].front();
    const auto& end = diagrams[e].back();
    EXPECT_NEAR(start.M, -P * (tip.x() - a.x()), 1e-8 * P * L) << "element " << element.id;
    EXPECT_NEAR(end.M, -P * (tip.x() - b.x()), 1e-8 * P * L) << "element " << element.id;
    EXPECT_NEAR(start.N, -P * chord.y(), 1e-8 * P) << "element " << element.id;
    EXPECT_NEAR(start.V, P * chord.x(), 1e-8 * P) << "element " << element.id;
    EXPECT_NEAR(end.x, (b - a).norm(), 1e-12);
  }
}

TEST(SectionDiagrams, ALoadRidingOnASimplySupportedBeamMakesTheShearJumpUnderIt) {
  // The riding load of test_resting (a node drawn 5 cm above a 10-m beam of 20 elements, pressed
  // down by 10 kN, its ux prescribed) stopped at x = 3.3, 0.6 along the element 3.0–3.5. Linear
  // statics: M = P a b / L = 23.1 kN m under it (sagging), V = P b / L before it and −P a / L after
  // it — to the geometric effects (the gap's lever, the surface's slope): 1e-3 here.
  const json m = riding_load(2.3, 4);
  tsm::Model model;
  const auto r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const tsm::solver::StepRecord& last = r.steps.back();
  const double P = 1e4, L = 10.0, a = 3.3, b = L - a;
  const auto diagrams = tsm::io::section_diagrams(model, last);
  const int loaded = last.contacts[0].element;
  ASSERT_EQ(model.elements[loaded].id, 7);
  const auto& s = diagrams[loaded];
  ASSERT_EQ(s.size(), 4u);
  EXPECT_NEAR(s[1].x, 0.3, 1e-3);
  EXPECT_NEAR(s[1].M, P * a * b / L, 1e-3 * P * a * b / L);
  EXPECT_NEAR(s[1].M, s[2].M, 1.0);  // the push's share along the chord (~2 N) at the gap's height (5 cm)
  EXPECT_NEAR(s[1].V, P * b / L, 1e-3 * P);
  EXPECT_NEAR(s[2].V, -P * a / L, 1e-3 * P);
  EXPECT_NEAR(s[2].V - s[1].V, -P, 1e-3 * P);
  // Elsewhere each element's stations join its neighbours', and exactly (to Newton's tolerance)
  // each element carries the force its supports' reactions send through it, in its chord's frame:
  // left of the load the pin's R₁ (N = −R₁·e, V = R₁·n), right of it the roller's R₂ (N = R₂·e,
  // V = −R₂·n). The beam's slope tilts the chords, so N is V's share along them (~40 N), and the
  // push along the bent beam's normal has such a share too.
  const Eigen::Vector2d R1 = last.reactions.segment<2>(0), R2 = last.reactions.segment<2>(3);
  for (size_t e = 0; e < diagrams.size(); ++e) {
    if (e + 1 < diagrams.size())
      EXPECT_NEAR(diagrams[e].back().M, diagrams[e + 1].front().M, 1e-6 * P * a * b / L) << "element " << e + 1;
    const tsm::Element& element = model.elements[e];
    const Eigen::Vector2d chord = (node_position(model, last, model.nodes[element.end].id) -
                                   node_position(model, last, model.nodes[element.start].id)).normalized();
    const Eigen::Vector2d normal(-chord.y(), chord.x());
    for (const auto& station : diagrams[e]) {  // the loaded element: R₁ up to the load, R₂ past it
      const bool before = static_cast<int>(e) < loaded || (static_cast<int>(e) == loaded && &station < &diagrams[e][2]);
      const Eigen::Vector2d R = before ? R1 : Eigen::Vector2d(-R2);
      EXPECT_NEAR(station.N, -R.dot(chord), 1e-6 * P) << "element " << element.id << " at " << station.x;
      EXPECT_NEAR(station.V, R.dot(normal), 1e-6 * P) << "element " << element.id << " at " << station.x;
    }
  }
}

}  // namespace
