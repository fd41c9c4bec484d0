// Results are bit-identical with 1 and 2 threads: the element loop runs in colour groups, so
// every sum reaches each entry in the same order (global_system.hpp), and the factorisation runs
// subtrees of the elimination tree concurrently with each row's arithmetic unchanged (block_ldlt.hpp).
#include <gtest/gtest.h>
#include <omp.h>

#include "support/models.hpp"

namespace {

using namespace tsm::test;

TEST(Threads, OneAndTwoThreadsGiveBitIdenticalResults) {
  // Big enough for the parallel paths (colour groups of ≥ 4096 elements; subtrees of 64 … n/16
  // blocks, here one per chain): 3 cantilevers of 3000.
  json m = beam_model({.L = 10.0, .E = 2e11, .G = 8e10, .A = 1e-2, .I = 1e-5, .shear_area = 8e-3, .divisions = 3000,
                       .element = "timoshenko"});
  m["nodes"].push_back({{"id", 3}, {"x", 0.0}, {"y", 5.0}});
  m["nodes"].push_back({{"id", 4}, {"x", 10.0}, {"y", 5.0}});
  m["nodes"].push_back({{"id", 5}, {"x", 0.0}, {"y", 10.0}});
  m["nodes"].push_back({{"id", 6}, {"x", 10.0}, {"y", 10.0}});
  m["members"].push_back({{"from", 3}, {"to", 4}, {"divisions", 3000}, {"element", "timoshenko"}, {"material", "m"}, {"section", "s"}});
  m["members"].push_back({{"from", 5}, {"to", 6}, {"divisions", 3000}, {"element", "timoshenko"}, {"material", "m"}, {"section", "s"}});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 3}, {"type", "fixed"}}, {{"node", 5}, {"type", "fixed"}}});
  const double M = 1.0 * 2e11 * 1e-5 / 10.0;
  m["loads"] = json::array({{{"node", 2}, {"mz", M}}, {{"node", 4}, {"fy", M / 10.0}}, {{"node", 6}, {"mz", -M}, {"fx", -M / 20.0}}});
  m["analysis"]["control"]["steps"] = 2;
  const tsm::Model model = tsm::io::read_model(m);

  omp_set_num_threads(1);
  const auto one = tsm::solver::run_analysis(model);
  omp_set_num_threads(2);
  const auto two = tsm::solver::run_analysis(model);
  ASSERT_EQ(one.status, tsm::solver::Status::converged) << one.message;
  ASSERT_EQ(one.steps.size(), two.steps.size());
  for (size_t s = 0; s < one.steps.size(); ++s) {
    EXPECT_EQ(one.steps[s].iterations, two.steps[s].iterations);
    EXPECT_EQ(one.steps[s].residual_norms, two.steps[s].residual_norms);
    EXPECT_TRUE((one.steps[s].displacements.array() == two.steps[s].displacements.array()).all()) << "step " << s;
    EXPECT_TRUE((one.steps[s].element_forces.array() == two.steps[s].element_forces.array()).all()) << "step " << s;
  }
  // And the answer is the right one: the first cantilever is bent by M to the arc of angle M L/EI.
  const Eigen::Vector3d tip = node_displacement(model, one.steps.back(), 2);
  EXPECT_NEAR(tip[2], M * 10.0 / (2e11 * 1e-5), 1e-8);
}

}  // namespace
