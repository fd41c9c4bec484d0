#pragma once
// Where a restarted run goes on from (`tsmframe run MODEL --from DIR/results.json#STEP`): a
// converged step an earlier run of the same model kept with its state (io/restart_reader.hpp).

#include <utility>
#include <vector>

#include "tsmframe/solver/state.hpp"

namespace tsm::solver {

struct RestartPoint {
  int step = 0;   ///< the kept step's number: the restarted run's steps are numbered on from it
  int stage = 0;  ///< its stage (index; 0 without stages)
  /// The state there: displacements, the stage's λ and path parameter, chord rotations and the
  /// contacts (their references restored by ContactSet::restore).
  State state;
  /// The λ each earlier stage ended at, and where the dofs the stage prescribes or controls
  /// stood at its start (dof, value): what its model (stage_model) is built from.
  std::vector<double> final_load_factors;
  std::vector<std::pair<int, double>> stage_start;
};

}  // namespace tsm::solver
