#include "tsmframe/solver/analysis.hpp"

#include <cmath>
#include <sstream>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/solver/newton.hpp"

namespace tsm::solver {
namespace {

/// Whether a converged step keeps its full state in the results.
bool keeps_state(const OutputSelection& output, int step) {
  switch (output.kind) {
    case OutputSelection::Kind::all: return true;
    case OutputSelection::Kind::last: return false;
    case OutputSelection::Kind::every: return step % output.every == 0;
  }
  return true;
}

std::string failure_text(int step, double from, double to, const char* what, const NewtonOutcome& outcome,
                         int cutbacks) {
  std::ostringstream os;
  os << "step " << step << " (" << what << " " << from << " -> " << to << ") failed: " << outcome.message;
  if (cutbacks > 0) os << ", after " << cutbacks << " cutbacks in a row";
  return os.str();
}

}  // namespace

RunResult run_analysis(const Model& model, const StepObserver& observer) {
  const AnalysisSettings& settings = model.analysis;
  const Control& control = settings.control;
  assembly::DofMap dofs(model);
  assembly::GlobalSystem system(model, dofs);
  const contact::ContactTracker contacts(model);
  NewtonSolver newton(system, {settings.tolerance, settings.max_iterations}, &contacts);

  State state{Eigen::VectorXd::Zero(model.dof_count()), 0.0,
              std::vector<double>(model.elements.size(), 0.0), contacts.initial_states()};
  newton.reset(state);

  const bool by_displacement = control.type == ControlType::displacement;
  PathConstraint constraint;
  if (by_displacement) {
    constraint.kind = PathConstraint::Kind::displacement_target;
    constraint.equation = dofs.equation(dofs_per_node * control.node + control.dof);
  }
  // The path parameter t runs from 0 to the number of legs (1 unless a load path is given): λ
  // under load control, the fraction of the target under displacement control, piecewise
  // linear between the path's points. Steps end on the grid k/N of each leg; cutback halves
  // within a grid cell.
  std::vector<double> points{0.0};
  if (control.path.empty()) points.push_back(1.0);
  else points.insert(points.end(), control.path.begin(), control.path.end());
  const int legs = static_cast<int>(points.size()) - 1;
  const auto value = [&](double t) {
    const int leg = std::min(static_cast<int>(t), legs - 1);
    return points[leg] + (t - leg) * (points[leg + 1] - points[leg]);
  };
  const int grid_steps = control.steps * legs;
  const double nominal = 1.0 / control.steps;
  double t = 0.0, increment = nominal;
  int halvings = 0, grid_index = 0;
  RunResult result;
  int last_with_state = -1;

  while (grid_index < grid_steps) {
    const double next_grid = static_cast<double>(grid_index + 1) / control.steps;
    double dt = std::min(increment, next_grid - t);
    if (next_grid - t - dt < 1e-9 * nominal) dt = next_grid - t;
    const bool reaches_grid = dt == next_grid - t;
    const double t_end = reaches_grid ? next_grid : t + dt;
    if (by_displacement) constraint.target = value(t_end) * control.target;
    else constraint.load_increment = value(t_end) - state.load_factor;

    const State saved = state;
    const NewtonOutcome outcome = newton.step(constraint, state);
    StepRecord record;
    record.step = static_cast<int>(result.steps.size()) + 1;
    record.iterations = outcome.iterations;
    record.residual_norms = outcome.residual_norms;
    record.cutbacks = halvings;
    record.increment = (value(t_end) - value(t)) * (by_displacement ? control.target : 1.0);
    record.contact_iterates = outcome.contact_iterates;

    if (outcome.status == Status::converged) {
      t = t_end;
      if (reaches_grid) ++grid_index;
      halvings = 0;
      increment = std::min(2.0 * increment, nominal);
      record.load_factor = state.load_factor;
      record.converged = true;
      record.criterion = outcome.criterion;
      record.has_state = true;
      record.monitored.resize(dofs_per_node * static_cast<int>(settings.monitor.size()));
      for (size_t m = 0; m < settings.monitor.size(); ++m)
        record.monitored.segment<3>(dofs_per_node * m) = state.displacements.segment<3>(dofs_per_node * settings.monitor[m]);
      record.displacements = state.displacements;
      record.element_forces = newton.element_forces();
      record.reactions = newton.reactions(state.load_factor);
      record.contacts = newton.contact_points(state);
      // Only the newest step keeps its state unless the output selection wants it.
      if (last_with_state >= 0 && !keeps_state(settings.output, result.steps[last_with_state].step)) {
        StepRecord& previous = result.steps[last_with_state];
        previous.has_state = false;
        previous.displacements = previous.element_forces = previous.reactions = Eigen::VectorXd();
      }
      last_with_state = static_cast<int>(result.steps.size());
      result.steps.push_back(std::move(record));
      if (observer) observer(result.steps.back());
      continue;
    }

    state = saved;
    // The smallest increment cutback may try: max_cutbacks halvings of the nominal step. Without
    // it, steps that keep converging ever closer to a barrier would never end.
    const double smallest = std::ldexp(nominal, -settings.max_cutbacks);
    if (settings.cutback && halvings < settings.max_cutbacks && dt / 2.0 >= smallest * (1.0 - 1e-12)) {
      ++halvings;
      increment = dt / 2.0;
      newton.reset(state);
      continue;
    }
    record.load_factor = by_displacement ? saved.load_factor : value(t_end);
    record.converged = false;
    record.message = outcome.message;
    result.status = settings.cutback ? Status::cutback_limit : outcome.status;
    const double from = value(t) * (by_displacement ? control.target : 1.0);
    const double to = value(t_end) * (by_displacement ? control.target : 1.0);
    result.message = failure_text(record.step, from, to, by_displacement ? "controlled displacement" : "load factor",
                                  outcome, halvings);
    result.steps.push_back(std::move(record));
    if (observer) observer(result.steps.back());
    return result;
  }
  result.status = Status::converged;
  return result;
}

}  // namespace tsm::solver
