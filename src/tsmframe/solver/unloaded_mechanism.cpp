#include "tsmframe/solver/unloaded_mechanism.hpp"

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/contact/contact_set.hpp"
#include "tsmframe/model/mechanism.hpp"
#include "tsmframe/solver/diagnosis.hpp"
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
  // As the first step's failure at a singular tangent is explained (TsmProblem::explain): the
  // null vector of the unloaded tangent, where it has one, named.
  StepFailure failure;
  failure.reason = StepFailure::Reason::singular_tangent;
  failure.iteration = 1;
  problem.explain(state, failure);
  if (failure.reason != StepFailure::Reason::mechanism) return std::nullopt;
  return step_failure_text(failure, model);
}

std::optional<Mechanism> drawn_mechanism(Model& model) {
  if (std::optional<std::string> supports = starting_mechanism(model)) return Mechanism{*supports, true};
  if (!model.stages.empty()) return std::nullopt;
  if (std::optional<std::string> hinges = unloaded_mechanism(model)) return Mechanism{*hinges, false};
  return std::nullopt;
}

}  // namespace tsm::solver
