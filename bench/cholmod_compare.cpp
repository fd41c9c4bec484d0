// Our node-block LDLᵀ against SuiteSparse's CHOLMOD (issue 5 asks to measure it) on the tangent
// of the lattice frame at its undeformed state: the same matrix, factorised five times each
// (best time shown), one solve each, and how far apart the two solutions are. Built only when
// CHOLMOD is installed (libsuitesparse-dev); not a dependency of tsmframe.
// Usage: tsmframe_cholmod_compare [B=70] [D=10]
#include <cholmod.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "lattice_model.hpp"
#include "tsmframe/assembly/global_system.hpp"

namespace {

double seconds() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

int main(int argc, char** argv) {
  const int bays = argc > 1 ? std::atoi(argv[1]) : 70, divisions = argc > 2 ? std::atoi(argv[2]) : 10;
  const tsm::Model model = tsm::bench::lattice(bays, divisions, 0.0);
  tsm::assembly::DofMap dofs(model);
  tsm::assembly::GlobalSystem system(model, dofs);
  tsm::assembly::Evaluation evaluation;
  system.evaluate(Eigen::VectorXd::Zero(model.dof_count()), std::vector<double>(model.elements.size(), 0.0), true, evaluation);
  const tsm::linalg::BlockMatrix tangent = system.tangent();
  if (3 * tangent.size != dofs.free_count()) {
    std::fprintf(stderr, "a node with some dofs fixed: this comparison expects whole free nodes\n");
    return 1;
  }

  tsm::linalg::BlockLDLT ours;
  tsm::linalg::BlockMatrix factor = tangent;
  double t0 = seconds();
  ours.analyze(factor);
  const double ours_analysis = seconds() - t0;
  double ours_factorisation = 1e30;
  for (int r = 0; r < 5; ++r) {
    factor = tangent;
    t0 = seconds();
    if (!ours.factorize(factor)) return 1;
    ours_factorisation = std::min(ours_factorisation, seconds() - t0);
  }
  Eigen::VectorXd x = Eigen::VectorXd::Ones(3 * tangent.size);
  t0 = seconds();
  ours.solve_in_place(x);
  const double ours_solve = seconds() - t0;

  // The same matrix as scalar lower-triangle CSC (blocks in the same order), exact zeros dropped.
  const long n = 3L * tangent.size;
  std::vector<long> column(n + 1, 0), row;
  std::vector<double> value;
  for (int c = 0; c < tangent.size; ++c)
    for (int dc = 0; dc < 3; ++dc) {
      for (int p = tangent.column[c]; p < tangent.column[c + 1]; ++p)
        for (int dr = 0; dr < 3; ++dr) {
          const long r = 3L * tangent.row[p] + dr, col = 3L * c + dc;
          const double v = tangent.is_fill(p) ? 0.0 : tangent.value[p](dr, dc);
          if (r < col || (v == 0.0 && r != col)) continue;
          row.push_back(r);
          value.push_back(v);
        }
      column[3L * c + dc + 1] = static_cast<long>(row.size());
    }
  std::printf("%d elements, %ld equations; times in ms (best of 5 factorisations)\n", static_cast<int>(model.elements.size()), n);
  std::printf("%-34s %9s %11s %8s %12s\n", "solver", "analysis", "factorise", "solve", "rel. diff");
  std::printf("%-34s %9.1f %11.1f %8.2f %12s\n", "tsmframe node-block LDLT", 1e3 * ours_analysis, 1e3 * ours_factorisation,
              1e3 * ours_solve, "—");
  for (const int supernodal : {CHOLMOD_SIMPLICIAL, CHOLMOD_SUPERNODAL}) {
    cholmod_common common;
    cholmod_l_start(&common);
    common.supernodal = supernodal;
    cholmod_sparse* A = cholmod_l_allocate_sparse(n, n, row.size(), 1, 1, -1, CHOLMOD_REAL, &common);
    std::copy(column.begin(), column.end(), static_cast<long*>(A->p));
    std::copy(row.begin(), row.end(), static_cast<long*>(A->i));
    std::copy(value.begin(), value.end(), static_cast<double*>(A->x));
    t0 = seconds();
    cholmod_factor* L = cholmod_l_analyze(A, &common);
    const double analysis = seconds() - t0;
    double factorisation = 1e30;
    for (int r = 0; r < 5; ++r) {
      t0 = seconds();
      cholmod_l_factorize(A, L, &common);
      factorisation = std::min(factorisation, seconds() - t0);
    }
    cholmod_dense* B = cholmod_l_ones(n, 1, CHOLMOD_REAL, &common);
    t0 = seconds();
    cholmod_dense* X = cholmod_l_solve(CHOLMOD_A, L, B, &common);
    const double solve = seconds() - t0;
    double difference = 0.0;
    for (long i = 0; i < n; ++i) difference += std::pow(static_cast<double*>(X->x)[i] - x[i], 2);
    char name[64];
    std::snprintf(name, sizeof name, "CHOLMOD %s LL^T", L->is_super ? "supernodal" : "simplicial");
    std::printf("%-34s %9.1f %11.1f %8.2f %12.1e\n", name, 1e3 * analysis, 1e3 * factorisation, 1e3 * solve,
                std::sqrt(difference) / x.norm());
    cholmod_l_free_dense(&X, &common);
    cholmod_l_free_dense(&B, &common);
    cholmod_l_free_factor(&L, &common);
    cholmod_l_free_sparse(&A, &common);
    cholmod_l_finish(&common);
  }
}
