// Results are bit-identical with 1 and 2 threads: the element loop runs in chunks whose colour
// groups run concurrently, so every sum reaches each entry in the same order (global_system.hpp);
// the factorisation and the solves run subtrees of the elimination tree, and the rows above them
// level by level, concurrently, with each row's arithmetic unchanged (block_ldlt.hpp). Chains
// exercise the subtrees; a grid frame exercises the rows above them.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <utility>

#include "support/models.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/linalg/block_ldlt.hpp"
#include "tsmframe/study/study_runner.hpp"
#include "tsmframe/element/beam_element.hpp"
#include "tsmframe/util/parallel_for.hpp"

namespace {

using namespace tsm::test;

void expect_bit_identical(const tsm::solver::RunResult& one, const tsm::solver::RunResult& two) {
  ASSERT_EQ(one.steps.size(), two.steps.size());
  for (size_t s = 0; s < one.steps.size(); ++s) {
    EXPECT_EQ(one.steps[s].iterations, two.steps[s].iterations);
    EXPECT_EQ(one.steps[s].residual_norms, two.steps[s].residual_norms);
    EXPECT_TRUE((one.steps[s].displacements.array() == two.steps[s].displacements.array()).all()) << "step " << s;
    EXPECT_TRUE((one.steps[s].element_forces.array() == two.steps[s].element_forces.array()).all()) << "step " << s;
  }
}

/// The model run with one thread, then with two (the default number restored after).
std::pair<tsm::solver::RunResult, tsm::solver::RunResult> run_with_one_and_two_threads(const tsm::Model& model) {
  omp_set_num_threads(1);
  tsm::solver::RunResult one = tsm::solver::run_analysis(model);
  omp_set_num_threads(2);
  tsm::solver::RunResult two = tsm::solver::run_analysis(model);
  omp_set_num_threads(omp_get_num_procs());
  return {std::move(one), std::move(two)};
}

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

  const auto [one, two] = run_with_one_and_two_threads(model);
  ASSERT_EQ(one.status, tsm::solver::Status::converged) << one.message;
  expect_bit_identical(one, two);
  // And the answer is the right one: the first cantilever is bent by M to the arc of angle M L/EI.
  const Eigen::Vector3d tip = node_displacement(model, one.steps.back(), 2);
  EXPECT_NEAR(tip[2], M * 10.0 / (2e11 * 1e-5), 1e-8);
}

// A grid frame of bays × bays members, `divisions` Timoshenko elements each, the bottom row
// clamped and the top row pushed sideways and down.
tsm::Model grid_frame(int bays, int divisions) {
  const int n = bays + 1;
  json m = {{"materials", {{"steel", {{"E", 2.05e11}, {"G", 7.9e10}}}}},
            {"sections", {{"sq", {{"A", 1e-2}, {"I", 8.333e-6}, {"shear_area", 8.33e-3}}}}},
            {"nodes", json::array()}, {"members", json::array()}, {"supports", json::array()}, {"loads", json::array()},
            {"analysis", {{"control", {{"type", "load"}, {"steps", 2}}}, {"output", "all"}}}};
  auto id = [n](int x, int y) { return y * n + x + 1; };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) m["nodes"].push_back({{"id", id(x, y)}, {"x", double(x)}, {"y", double(y)}});
  auto member = [&](int a, int b) {
    m["members"].push_back(
        {{"from", a}, {"to", b}, {"divisions", divisions}, {"element", "timoshenko"}, {"material", "steel"}, {"section", "sq"}});
  };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < bays; ++x) member(id(x, y), id(x + 1, y));
  for (int y = 0; y < bays; ++y)
    for (int x = 0; x < n; ++x) member(id(x, y), id(x, y + 1));
  for (int x = 0; x < n; ++x) {
    m["supports"].push_back({{"node", id(x, 0)}, {"type", "fixed"}});
    m["loads"].push_back({{"node", id(x, bays)}, {"fx", 2e5}, {"fy", -2e5}});
  }
  return tsm::io::read_model(m);
}

TEST(Threads, AGridFrameGivesBitIdenticalResults) {
  // 16 × 16 bays, 5 elements per member (2,720 elements, past util::smallest_shared_model): its
  // elimination tree leaves hundreds of rows above the subtree tasks, run level by level in
  // parallel.
  const int bays = 16;
  const tsm::Model model = grid_frame(bays, 5);
  ASSERT_GE(static_cast<int>(model.elements.size()), tsm::util::smallest_shared_model) << "else every loop runs on one thread";

  const auto [one, two] = run_with_one_and_two_threads(model);
  ASSERT_EQ(one.status, tsm::solver::Status::converged) << one.message;
  expect_bit_identical(one, two);
  for (const auto& step : one.steps) expect_global_equilibrium(model, step);
  EXPECT_GT(node_displacement(model, one.steps.back(), (bays + 1) * (bays + 1))[0], 0.1);  // it sways far
}

TEST(Threads, AGridFrameWhoseLastSeparatorIsDenseGivesBitIdenticalResults) {
  // 40 × 40 bays of one element each: the last separator (58 rows) is factorised as one dense
  // block, its prefix passes and the block shared out over the threads.
  const tsm::Model model = grid_frame(40, 1);
  const tsm::assembly::DofMap dofs(model);
  const tsm::assembly::GlobalSystem system(model, dofs);
  tsm::linalg::BlockLDLT ldlt;
  ldlt.analyze(system.tangent());
  ASSERT_GE(ldlt.rows_in_dense_paths(), 32) << "else the dense block is not exercised";

  const auto [one, two] = run_with_one_and_two_threads(model);
  ASSERT_EQ(one.status, tsm::solver::Status::converged) << one.message;
  expect_bit_identical(one, two);
  // To the run's own tolerance (1e-8): 41 loaded joints sum their residuals into the balance.
  for (const auto& step : one.steps) expect_global_equilibrium(model, step, 1e-8);
}

TEST(Threads, AContactSlidingThroughElementEndsGivesBitIdenticalResults) {
  // A 9 m cantilever of 6,000 elements pushed 0.6 m up by a rigid node from x = 4.05 m: the
  // contact point slides through many element ends, each hand-over re-forming only what the
  // contact touches (GlobalSystem::evaluate_contact_change) between parallel element loops.
  json m = beam_model({.L = 9.0, .E = 2.05e11, .G = 7.9e10, .A = 1e-2, .I = 1e-4, .shear_area = 8.3e-3, .divisions = 6000,
                       .element = "timoshenko"});
  m["nodes"].push_back({{"id", 100}, {"x", 4.05}, {"y", 0.0}});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}, {{"node", 100}, {"fix", {"ux", "rz"}}}});
  m["prescribed"] = json::array({{{"node", 100}, {"uy", 0.6}}});
  m["contacts"] = json::array({{{"node", 100}, {"members", "all"}}});
  m["analysis"] = {{"control", {{"type", "load"}, {"steps", 4}}}, {"output", "all"}};
  const tsm::Model model = tsm::io::read_model(m);

  const auto [one, two] = run_with_one_and_two_threads(model);
  ASSERT_EQ(one.status, tsm::solver::Status::converged) << one.message;
  expect_bit_identical(one, two);
  ASSERT_EQ(one.steps.back().contacts.size(), 1u);
  EXPECT_GT(one.steps.back().contacts[0].element, 2700 + 10) << "the point has slid on past element 2700 (x = 4.05 m)";
  EXPECT_EQ(one.steps.back().contacts[0].element, two.steps.back().contacts[0].element);
  EXPECT_EQ(one.steps.back().contacts[0].force, two.steps.back().contacts[0].force);
}

TEST(Threads, ContactsClosingAlongABeamGiveBitIdenticalResults) {
  // examples/beam-pressed-onto-beam.json at 1,000 elements (250 contact nodes, 175 in touch at the
  // end) under 1 kN/m in 2 steps: contacts close by the dozen, the release looks ahead (one
  // factorisation and a solve per contact that lets go, on the shared solver) and the step is cut
  // back on the way.
  json m = pressed_beams(-1000.0, 2, 750, 250);
  m["analysis"]["output"] = "all";
  const tsm::Model model = tsm::io::read_model(m);
  const auto [one, two] = run_with_one_and_two_threads(model);
  ASSERT_EQ(one.status, tsm::solver::Status::converged) << one.message;
  expect_bit_identical(one, two);
  int touching = 0;
  for (const tsm::solver::ContactPoint& c : one.steps.back().contacts) touching += c.element >= 0;
  EXPECT_GT(touching, 100);
}

TEST(Threads, TheRoundingFloorIsTheSameOnOneAndTwoThreads) {
  // The floor Newton's round-off criterion compares with (GlobalSystem::rounding_floor) sums its
  // elements chunk by chunk on both threads: the same bits on one, and the sum of every element's
  // own floor (element::round_off_floor, summed here one by one in the model's order).
  json m = beam_model({.L = 10.0, .E = 2e11, .G = 8e10, .A = 1e-2, .I = 1e-5, .shear_area = 8e-3, .divisions = 9000, .element = "timoshenko"});
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  const tsm::Model model = tsm::io::read_model(m);
  const tsm::assembly::DofMap dofs(model);
  const tsm::assembly::GlobalSystem system(model, dofs);
  Eigen::VectorXd D(model.dof_count());
  std::vector<double> rotations(model.elements.size());
  for (int k = 0; k < model.node_count(); ++k) {  // bent into an arc of 1.5 rad, stretched a little
    const double x = model.nodes[k].position.x(), turn = 0.15 * x;
    D.segment<3>(3 * k) << (x > 0 ? std::sin(turn) / 0.15 * 1.001 - x : 0.0), (1.0 - std::cos(turn)) / 0.15, turn;
  }
  for (size_t e = 0; e < rotations.size(); ++e) rotations[e] = 0.15 * model.nodes[model.elements[e].start].position.x();
  omp_set_num_threads(1);
  const tsm::assembly::RoundingFloor one = system.rounding_floor(D, rotations, {});
  omp_set_num_threads(2);
  const tsm::assembly::RoundingFloor two = system.rounding_floor(D, rotations, {});
  omp_set_num_threads(omp_get_num_procs());
  EXPECT_EQ(one.force, two.force);
  EXPECT_EQ(one.moment, two.moment);
  double force = 0.0, moment = 0.0;
  for (size_t e = 0; e < model.elements.size(); ++e) {
    const tsm::Element& el = model.elements[e];
    const tsm::element::InitialChord chord =
        tsm::element::initial_chord(model.nodes[el.start].position, model.nodes[el.end].position);
    const tsm::element::Matrix3 k0 = tsm::element::basic_stiffness(el.section, chord.length);
    tsm::element::Vector6 d;
    d << D.segment<3>(3 * el.start), D.segment<3>(3 * el.end);
    const tsm::element::RoundOffFloor f =
        tsm::element::round_off_floor(chord, k0, d, tsm::element::beam_response(chord, k0, d, rotations[e], false));
    force += 4.0 * f.force * f.force;
    moment += 2.0 * f.moment * f.moment;
  }
  EXPECT_NEAR(two.force, std::sqrt(force), 1e-12 * std::sqrt(force));
  EXPECT_NEAR(two.moment, std::sqrt(moment), 1e-12 * std::sqrt(moment));
  EXPECT_GT(two.force, 0.0);
}

TEST(Threads, AStudyRunsEachCaseOnOneThreadAndLeavesTheCallersSettingAlone) {
  // Every worker of a study, the calling thread among them, runs its cases on one thread (the
  // cases share the cores); afterwards the calling thread's setting is its own again (Python's
  // tf.study: a later tf.run used one thread).
  BeamSpec b;
  b.divisions = 4;
  json m = beam_model(b);
  m["supports"] = json::array({{{"node", 1}, {"type", "fixed"}}});
  m["loads"] = json::array({{{"node", 2}, {"fy", 1e-3}}});
  json s = {{"model", m}, {"sweep", json::array({{{"name", "n"}, {"path", "/members/0/divisions"}, {"values", {2, 3, 4, 5}}}})},
            {"record", json::array({{{"name", "tip"}, {"quantity", "displacement"}, {"node", 2}, {"dof", "uy"}}})}};
  const tsm::study::Study study = tsm::study::read_study(s, ".");
  const int before = omp_get_max_threads();
  omp_set_num_threads(2);
  const std::vector<tsm::study::CaseResult> rows = tsm::study::run_study(study, 2, "");
  EXPECT_EQ(omp_get_max_threads(), 2);
  ASSERT_EQ(rows.size(), 4u);
  for (const tsm::study::CaseResult& r : rows) EXPECT_TRUE(r.converged) << r.message;
  omp_set_num_threads(before);
}

}  // namespace
