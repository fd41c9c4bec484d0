// Lattice frame benchmark (issue 5): a rectangular grid of B × B bays (1 m), every member
// divided into D Timoshenko elements (steel, 100 mm square), the bottom row clamped, each top
// node pushed sideways and down by F in 10 load steps until the frame sways far. Prints the same
// row as tsmframe_scaling. Usage: tsmframe_lattice [B=70] [D=10] [F=2e4].
#include <cstdio>
#include <cstdlib>

#include "lattice_model.hpp"
#include "measure.hpp"

int main(int argc, char** argv) {
  const int bays = argc > 1 ? std::atoi(argv[1]) : 70;
  const int divisions = argc > 2 ? std::atoi(argv[2]) : 10;
  const double force = argc > 3 ? std::atof(argv[3]) : 2e4;
  return tsm::bench::measure([&] { return tsm::bench::lattice(bays, divisions, force); },
                             [&](const tsm::Model&, const tsm::solver::RunResult& result) {
                               const auto& last = result.steps.back();
                               if (!last.has_state) return std::string("(no state)");
                               const int corner = 3 * (bays * (bays + 1) + bays);
                               char text[96];
                               std::snprintf(text, sizeof text, "sway=%.4f drop=%.4f", last.displacements[corner],
                                             last.displacements[corner + 1]);
                               return std::string(text);
                             });
}
