// Self-weight ("gravity": [gx, gy] and materials' "density"; issue 29): a member weighs
// density × A × g per unit length, a member load like any other. A cantilever under its own
// weight against the textbook tip deflection q L⁴/8EI and root reactions; gravity in any
// direction carried to the supports whole; added to a member's own load; the reader's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/models.hpp"

namespace test_self_weight {
namespace {

using namespace tsm::test;

constexpr double L = 2.0, E = 2e11, A = 1e-3, I = 1e-7, density = 7850.0, g = 9.81;

/// A cantilever from (0, 0) along `direction` (unit), clamped at node 1, of `divisions` EB elements.
json weighing_cantilever(int divisions, double gx, double gy, Eigen::Vector2d direction = {1.0, 0.0}) {
  return {{"materials", {{"steel", {{"E", E}, {"density", density}}}}},
          {"sections", {{"s", {{"A", A}, {"I", I}}}}},
          {"gravity", {gx, gy}},
          {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", L * direction.x()}, {"y", L * direction.y()}}})},
          {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", divisions}, {"material", "steel"}, {"section", "s"}}})},
          {"supports", json::array({{{"node", 1}, {"type", "fixed"}}})},
          {"analysis", {{"control", {{"type", "load"}, {"steps", 1}}}}}};
}

TEST(SelfWeight, ACantileverSagsAsTheTextbookSaysAndItsRootCarriesItsWeight) {
  // q = ρ A g = 77.0 N/m; tip deflection q L⁴/8EI = 7.7 mm (L/260: the geometry's share ~1e-5).
  // Measured: 3.3e-3, 8.2e-4, 2.0e-4 off with 10, 20, 40 elements.
  const double q = density * A * g, exact = q * L * L * L * L / (8.0 * E * I);
  double previous = 0.0;
  for (const int divisions : {10, 20, 40}) {
    tsm::Model model;
    const tsm::solver::RunResult r = run(weighing_cantilever(divisions, 0.0, -g), model);
    ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
    const tsm::solver::StepRecord& last = r.steps.back();
    const double tip = -node_displacement(model, last, 2)[1];
    const double error = std::abs(tip / exact - 1.0);
    std::printf("[figure] %d elements: tip deflection %.6e, %.2e off q L^4/8EI\n", divisions, tip, error);
    // A member load is lumped half to each element end: the error falls as h² (0.33 (h/L)²).
    EXPECT_LT(error, 0.4 / (divisions * divisions)) << divisions << " elements";
    if (previous > 0.0) EXPECT_NEAR(previous / error, 4.0, 0.5) << "h² with the mesh";
    previous = error;
    // The root carries the whole weight and its moment (about the root, in the bent geometry: within 1e-4).
    EXPECT_NEAR(last.reactions[1], q * L, 1e-10 * q * L);
    EXPECT_NEAR(last.reactions[0], 0.0, 1e-10 * q * L);
    EXPECT_NEAR(last.reactions[2], q * L * L / 2.0, 1e-4 * q * L * L / 2.0);
    expect_global_equilibrium(model, last);
  }
}

TEST(SelfWeight, GravityInAnyDirectionReachesTheSupportWhole) {
  // A column 30° off vertical under gravity (3, −4) m/s²: the reaction is −ρ A L g, both parts.
  const double gx = 3.0, gy = -4.0;
  tsm::Model model;
  const tsm::solver::RunResult r =
      run(weighing_cantilever(8, gx, gy, {std::sin(0.5), std::cos(0.5)}), model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  const double weight = density * A * L;
  EXPECT_NEAR(r.steps.back().reactions[0], -weight * gx, 1e-10 * weight * 5.0);
  EXPECT_NEAR(r.steps.back().reactions[1], -weight * gy, 1e-10 * weight * 5.0);
}

TEST(SelfWeight, ItAddsToAMembersOwnLoad) {
  json m = weighing_cantilever(10, 0.0, -g);
  m["members"][0]["load"] = {{"fy", -100.0}};
  tsm::Model model;
  const tsm::solver::RunResult r = run(m, model);
  ASSERT_EQ(r.status, tsm::solver::Status::converged) << r.message;
  EXPECT_NEAR(r.steps.back().reactions[1], (100.0 + density * A * g) * L, 1e-10 * 300.0);
}

TEST(SelfWeight, TheReaderRefusesWhatCannotWeigh) {
  json m = weighing_cantilever(4, 0.0, -g);
  m["materials"]["steel"].erase("density");
  EXPECT_NE(refusal(m).find("gravity: no material has a density"), std::string::npos) << refusal(m);
  m["materials"]["steel"]["density"] = -1.0;
  EXPECT_NE(refusal(m).find("materials.steel.density"), std::string::npos) << refusal(m);
  m["materials"]["steel"]["density"] = density;
  m["gravity"] = {0.0};
  EXPECT_NE(refusal(m).find("gravity: expected [gx, gy]"), std::string::npos) << refusal(m);
  m["gravity"] = {0.0, "down"};
  EXPECT_NE(refusal(m).find("gravity[1]"), std::string::npos) << refusal(m);
  m.erase("gravity");  // a density alone weighs nothing: no load at all
  EXPECT_EQ(refusal(m), "");
}

}  // namespace

}  // namespace test_self_weight
