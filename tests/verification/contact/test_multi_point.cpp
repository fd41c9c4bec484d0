// Several contact points on one element (issue 27) through the whole solver: a simply supported
// beam of three elements with k rigid pushers resting on its middle element, each loaded down by
// its own force, against the closed form of a beam under k point loads — Euler–Bernoulli and
// Timoshenko. The pushers are held by nothing but their contacts (and ux, rz), so each carries
// its load into the beam at its point, and rides down with the beam there.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "support/contact_models.hpp"

namespace {

using namespace tsm::test;

constexpr double L = 10.0, E = 2e11, G = 7.7e10, I = 2e-5, A = 0.004, shear_area = 0.002, gap = 1e-3;

/// The deflection at x of a simply supported beam of span L under a unit load at ξ: bending
/// b x₁ (L² − b² − x₁²)/(6 EI L), x₁ = min(x, ξ), b = L − max(x, ξ), plus, for Timoshenko, the
/// shear part x₁ b / (L G A_s).
double influence(double x, double xi, bool timoshenko) {
  const double x1 = std::min(x, xi), b = L - std::max(x, xi);
  const double bending = b * x1 * (L * L - b * b - x1 * x1) / (6.0 * E * I * L);
  return bending + (timoshenko ? x1 * b / (L * G * shear_area) : 0.0);
}

json pushed_beam(const std::vector<double>& x, const std::vector<double>& load, const char* element) {
  json m = {{"materials", {{"steel", {{"E", E}, {"G", G}}}}},
            {"sections", {{"s", {{"A", A}, {"I", I}, {"shear_area", shear_area}}}}},
            {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", L}, {"y", 0.0}}})},
            {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 3}, {"element", element},
                                      {"material", "steel"}, {"section", "s"}}})},
            {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}}})},
            {"loads", json::array()},
            {"contacts", json::array()},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 2}}}}}};
  for (size_t p = 0; p < x.size(); ++p) {
    const int id = 10 + static_cast<int>(p);
    m["nodes"].push_back({{"id", id}, {"x", x[p]}, {"y", gap}});
    m["supports"].push_back({{"node", id}, {"fix", {"ux", "rz"}}});
    m["loads"].push_back({{"node", id}, {"fy", -load[p]}});
    m["contacts"].push_back({{"node", id}, {"members", "all"}, {"gap", gap}});
  }
  return m;
}

struct Case {
  std::vector<double> x;  ///< the pushers, all over the middle element (10/3 … 20/3)
  const char* element;
};

class MultiPointPush : public ::testing::TestWithParam<Case> {};

TEST_P(MultiPointPush, EqualsTheBeamUnderPointLoads) {
  const Case& c = GetParam();
  const int k = static_cast<int>(c.x.size());
  std::vector<double> load;
  for (int p = 0; p < k; ++p) load.push_back(100.0 * (1.0 + 0.3 * p));  // unequal: no symmetry to hide behind
  tsm::Model model;
  const tsm::solver::RunResult r = run(pushed_beam(c.x, load, c.element), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const bool timoshenko = std::string(c.element) == "timoshenko";
  double largest = 0.0;
  std::vector<double> exact(k, 0.0);
  for (int p = 0; p < k; ++p) {
    for (int q = 0; q < k; ++q) exact[p] -= influence(c.x[p], c.x[q], timoshenko) * load[q];
    largest = std::max(largest, std::abs(exact[p]));
  }
  ASSERT_GT(largest, 2e-4);  // a millimetre or so: rotations below 1e-3, so geometry adds ~1e-6
  for (int p = 0; p < k; ++p) {
    SCOPED_TRACE(testing::Message() << c.element << ", k = " << k << ", point " << p);
    const tsm::solver::ContactPoint& point = contact_of(r.steps.back(), p);
    EXPECT_EQ(point.element, 1);  // all on the middle element
    EXPECT_NEAR(point.force, load[p], 1e-5 * load[p]);
    EXPECT_NEAR(node_displacement(model, r.steps.back(), 10 + p)[1], exact[p], 1e-5 * largest);
  }
  expect_equilibrium(model, r.steps.back());
}

TEST(MultiPointContact, ANodeReachingAnElementACantileverFrameContactHoldsFailsTheStepNamingBoth) {
  // The cantilever frame has one point per element: pusher 10 rests there in that frame, pusher
  // 11 is pushed onto the same element from 1 cm above.
  json m = pushed_beam({4.0, 6.0}, {100.0, 0.0}, "euler-bernoulli");
  m["contacts"][0]["frame"] = "cantilever";
  m["nodes"][3]["y"] = 0.01;
  m["loads"].erase(1);
  m["prescribed"] = json::array({{{"node", 11}, {"uy", -0.02}}});
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_NE(r.status, tsm::solver::Status::converged);
  EXPECT_NE(r.message.find("contact node 11 reached element"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("which contact node 10 has to itself"), std::string::npos) << r.message;
  // In the chord frame both points share the element.
  m["contacts"][0].erase("frame");
  const tsm::solver::RunResult chord = run(m, model);
  ASSERT_EQ(chord.status, tsm::solver::Status::converged) << chord.message;
  EXPECT_EQ(contact_of(chord.steps.back(), 0).element, 1);
  EXPECT_EQ(contact_of(chord.steps.back(), 1).element, 1);
}

INSTANTIATE_TEST_SUITE_P(
    KPoints, MultiPointPush,
    ::testing::Values(Case{{5.0}, "euler-bernoulli"}, Case{{4.0, 6.0}, "euler-bernoulli"},
                      Case{{4.0, 5.0, 6.2}, "euler-bernoulli"}, Case{{3.6, 4.3, 5.0, 5.5, 6.4}, "euler-bernoulli"},
                      Case{{5.0}, "timoshenko"}, Case{{4.0, 6.0}, "timoshenko"}, Case{{4.0, 5.0, 6.2}, "timoshenko"},
                      Case{{3.6, 4.3, 5.0, 5.5, 6.4}, "timoshenko"}),
    [](const testing::TestParamInfo<Case>& info) {
      return std::string(info.param.element[0] == 't' ? "Timoshenko" : "EulerBernoulli") + std::to_string(info.param.x.size());
    });

}  // namespace
