#pragma once
// The model one stage of a staged analysis runs (docs/format.md, "Stages"): its own loads and
// prescribed displacements scaled by its load factor λ from 0, what earlier stages applied held
// at the level each ended at ("dead"), the dofs earlier stages prescribed held where they stand.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/model/model.hpp"

namespace tsm {

/// Where a stage starts: the load factor each earlier stage ended at, and the displacements of
/// the last one's end (all dofs; empty before the first stage: the unloaded state).
struct StageStart {
  std::vector<double> final_load_factors;
  Eigen::VectorXd displacements;
};

/// What stage `t` applies per unit of its load factor that is fixed in direction (per dof): its
/// nodal loads, and for the first stage the members' lumped loads (the model's reference_load).
Eigen::VectorXd fixed_load(const Model& model, int t);

/// The one-stage model that runs stage `stage` of `model` (which has stages) from `start`: its
/// reference load and prescribed increments are the stage's (the first stage's with the
/// members' loads), its dead load what the earlier stages applied at their final λ, its
/// constraints the supports and every dof prescribed so far, its control and output the stage's;
/// a contact the stage leaves out touches no member.
Model stage_model(const Model& model, int stage, const StageStart& start);

}  // namespace tsm
