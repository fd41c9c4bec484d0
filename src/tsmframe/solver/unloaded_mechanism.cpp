#include "tsmframe/solver/unloaded_mechanism.hpp"

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/model/mechanism.hpp"
#include "tsmframe/solver/diagnosis.hpp"
#include "tsmframe/solver/free_mode.hpp"
#include "tsmframe/solver/tsm_problem.hpp"

namespace tsm::solver {

std::optional<std::string> unloaded_mechanism(const Model& model) {
  assembly::DofMap dofs(model);
  assembly::GlobalSystem system(model, dofs);
  const contact::ContactSet contacts(model);
  TsmProblem problem(system, &contacts);
  State state;
  state.displacements = Eigen::VectorXd::Zero(model.dof_count());
  state.chord_rotations.assign(model.elements.size(), 0.0);
  state.contacts = contacts.initial_states();
  problem.take_contact_references(state);
  problem.evaluate(state);
  // The unloaded tangent's null vector, as a run's first step that fails there names it
  // (TsmProblem::explain): within a few shifts of zero where it does not factorise, at round-off
  // level where it does.
  const bool regular = problem.factorize(state, true, nullptr, false).ok;
  StepFailure failure;
  failure.iteration = 1;
  if (!problem.name_unloaded_mechanism(state, failure, regular ? regular_within_shifts : singular_within_shifts))
    return std::nullopt;
  return step_failure_text(failure, model);
}

std::optional<Mechanism> drawn_mechanism(Model& model) {
  if (std::optional<std::string> supports = starting_mechanism(model)) return Mechanism{*supports, true};
  if (!model.stages.empty()) return std::nullopt;
  if (std::optional<std::string> hinges = unloaded_mechanism(model)) return Mechanism{*hinges, false};
  return std::nullopt;
}

}  // namespace tsm::solver
