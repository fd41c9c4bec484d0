// The parts of a run that happen once or every iteration, timed apart (issue 5): the set-up
// (dof map with its ordering, the assembly with its pattern and fill, the solver's analysis), then
// evaluations of the internal forces and tangent at one bent state and the factorisation of that
// tangent with a solve, each part with the pages it touched first or had mapped in (minor
// faults; util::touch_pages counts its pages there too). The 10⁵-element models of bench/targets.sh: `tsmframe_phases chains` (100 × 1,000) or
// `tsmframe_phases lattice` (70 × 70 bays × 10); `tsmframe_phases chains C` for C chains of
// 1,000 (1000: the 10⁶ of the spread). Run it in a fresh process: the set-up's page faults are
// its first touches of the heap.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <memory>
#include <vector>

#include "chains_model.hpp"
#include "lattice_model.hpp"
#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/solver/linear_solver.hpp"
#include "tsmframe/solver/tsm_problem.hpp"

namespace {

long page_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

/// Times `part`, printing its milliseconds and page faults.
template <class Part>
void timed(const char* name, Part&& part) {
  const long faults = page_faults();
  const auto t0 = std::chrono::steady_clock::now();
  part();
  const double ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("  %-28s %8.1f ms %7ld pages first touched or mapped in\n", name, ms, page_faults() - faults);
}

}  // namespace

int main(int argc, char** argv) {
  const bool lattice = argc > 1 && std::strcmp(argv[1], "lattice") == 0;
  const int chains = !lattice && argc > 2 ? std::atoi(argv[2]) : 100;  // chains C: C chains of 1000
  const tsm::Model model = lattice ? tsm::bench::lattice(70, 10, 1e6) : tsm::bench::rolled_cantilevers(chains, 1000, 0.25, 10);
  std::printf("%s: %zu elements\n", lattice ? "lattice 70 x 70 x 10" : (std::to_string(chains) + " chains x 1000").c_str(), model.elements.size());
  std::unique_ptr<tsm::assembly::DofMap> dofs;
  std::unique_ptr<tsm::assembly::GlobalSystem> system;
  std::unique_ptr<tsm::contact::ContactSet> contacts;
  std::unique_ptr<tsm::solver::TsmProblem> problem;
  timed("set-up: dof map, ordering", [&] { dofs = std::make_unique<tsm::assembly::DofMap>(model); });
  timed("set-up: assembly, pattern", [&] { system = std::make_unique<tsm::assembly::GlobalSystem>(model, *dofs); });
  timed("set-up: solver's analysis", [&] {
    contacts = std::make_unique<tsm::contact::ContactSet>(model);
    problem = std::make_unique<tsm::solver::TsmProblem>(*system, contacts.get());
  });
  // A bent state: every node turned and moved as on a circle's arc of its distance from x = 0.
  Eigen::VectorXd D = Eigen::VectorXd::Zero(model.dof_count());
  for (int k = 0; k < model.node_count(); ++k) {
    const Eigen::Vector2d x = model.nodes[k].position;
    D.segment<3>(3 * k) << -0.002 * x.x() * x.x(), 0.01 * x.x() * x.x() + 0.001 * x.y(), 0.02 * x.x();
  }
  std::vector<double> rotations(model.elements.size(), 0.0);
  tsm::assembly::Evaluation e;
  timed("first evaluation", [&] { system->evaluate(D, rotations, true, e); });
  // Evaluation, then factorisation with the solve riding along, 60 times: the fastest and the median.
  tsm::solver::LinearSolver solver;
  solver.analyze(*dofs, system->tangent());
  Eigen::VectorXd x(dofs->free_count());
  std::vector<double> evaluation, factorisation;
  const long faults = page_faults();
  for (int r = 0; r < 60; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    system->evaluate(D, rotations, true, e);
    auto t1 = std::chrono::steady_clock::now();
    x.setOnes();
    if (!solver.factorize_and_solve(system->tangent_for_factorisation(), {}, x)) std::printf("  (a pivot failed)\n");
    auto t2 = std::chrono::steady_clock::now();
    evaluation.push_back(1e3 * std::chrono::duration<double>(t1 - t0).count());
    factorisation.push_back(1e3 * std::chrono::duration<double>(t2 - t1).count());
  }
  for (auto* times : {&evaluation, &factorisation}) std::sort(times->begin(), times->end());
  std::printf("  %-28s %8.2f ms (median %.2f)\n", "evaluation (fastest of 60)", evaluation.front(), evaluation[30]);
  std::printf("  %-28s %8.2f ms (median %.2f)\n", "factorisation and solve", factorisation.front(), factorisation[30]);
  std::printf("  %-28s %8ld pages first touched in the 60\n", "", page_faults() - faults);
}
