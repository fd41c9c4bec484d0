#include "tsmframe/solver/recorder.hpp"

#include "tsmframe/solver/stability.hpp"

#include <cmath>

namespace tsm::solver {
namespace {

/// Whether a converged step keeps its full state in the results.
bool keeps_state(const AnalysisSettings& settings, int step) {
  if (settings.buckling_modes > 0 && settings.buckling_at == AnalysisSettings::BucklingAt::step && step == settings.buckling_step)
    return true;  // buckling is estimated from it after the run
  const OutputSelection& output = settings.output;
  switch (output.kind) {
    case OutputSelection::Kind::all: return true;
    case OutputSelection::Kind::last: return false;
    case OutputSelection::Kind::every: return step % output.every == 0;
  }
  return true;
}

/// Sets the step's largest axial strain N / EA from its element forces (N first of each three).
void take_axial_strain(const Model& model, StepRecord& record) {
  const Eigen::VectorXd& forces = record.element_forces;
  if (forces.size() != 3 * static_cast<Eigen::Index>(model.elements.size())) return;
  double largest = 0.0;
  int element = -1;
  for (size_t e = 0; e < model.elements.size(); ++e) {
    const double strain = forces[3 * e] / model.elements[e].section.EA;
    if (element < 0 || std::abs(strain) > std::abs(largest)) largest = strain, element = static_cast<int>(e);
  }
  record.axial_strain = largest;
  record.strained_element = element;
}

/// The farthest a node's (u, v) moved from `before` (null: from zero) to `now`.
double largest_move(const Eigen::VectorXd& now, const Eigen::VectorXd* before) {
  double largest = 0.0;
  for (Eigen::Index k = 0; k + 1 < now.size(); k += dofs_per_node) {
    const double du = now[k] - (before ? (*before)[k] : 0.0), dv = now[k + 1] - (before ? (*before)[k + 1] : 0.0);
    largest = std::max(largest, du * du + dv * dv);
  }
  return std::sqrt(largest);
}

/// The contacts as a restart needs them: what each touches, without the references detection
/// compares with (per candidate element; restored from the state) or the step's memory (cleared
/// at every converged step).
std::vector<contact::ContactState> kept_contacts(const std::vector<contact::ContactState>& contacts) {
  std::vector<contact::ContactState> kept(contacts.size());
  for (size_t k = 0; k < contacts.size(); ++k) {
    const contact::ContactState& c = contacts[k];
    kept[k].active = c.active;
    kept[k].element = c.element;
    kept[k].side = c.side;
    kept[k].alpha = c.alpha;
    kept[k].force = c.force;
    kept[k].Y = c.Y;
    kept[k].push[0] = c.push[0];
    kept[k].push[1] = c.push[1];
    kept[k].vertex = c.vertex;
    kept[k].entering = c.entering;
    kept[k].friction = c.friction;
  }
  return kept;
}

}  // namespace

void Recorder::start_from(const State& state) {
  if (state.displacements.size() > 0 && state.displacements.any()) start_ = problem_.physical(state);
}

Recorder::Recorder(const Model& model, const TsmProblem& problem, const StepObserver& observer, RunResult& result,
                   bool defer_forces)
    : model_(model), problem_(problem), observer_(observer), result_(result), defer_forces_(defer_forces && !observer),
      moved_dofs_(model.moved_dofs()), supported_(model) {}

StepRecord Recorder::start(const NewtonOutcome& outcome, int cutbacks) const {
  StepRecord record;
  record.step = next_step();
  record.stage = model_.analysis.stage;
  record.iterations = outcome.iterations;
  record.residual_norms = outcome.residual_norms;
  record.cutbacks = cutbacks;
  record.contact_iterates = outcome.contact_iterates;
  return record;
}

void Recorder::converged(StepRecord record, const NewtonOutcome& outcome, const State& state) {
  const AnalysisSettings& settings = model_.analysis;
  record.load_factor = state.load_factor;
  record.converged = true;
  record.criterion = outcome.criterion;
  record.slid_off = outcome.slid_off;
  record.has_state = true;
  const Eigen::VectorXd& displacements = problem_.physical(state);  // global: what a record holds
  record.monitored.resize(dofs_per_node * static_cast<int>(settings.monitor.size()));
  for (size_t m = 0; m < settings.monitor.size(); ++m)
    record.monitored.segment<3>(dofs_per_node * m) = displacements.segment<3>(dofs_per_node * settings.monitor[m]);
  // From the step before, or from where the run started (an earlier stage's end; else nil).
  const Eigen::VectorXd* before = last_with_state_ >= 0 ? &result_.steps[last_with_state_].displacements
                                  : start_.size() > 0   ? &start_
                                                        : nullptr;
  record.largest_move = largest_move(displacements, before);
  // The previous step's state goes first (unless the output keeps it): the peak memory holds one state, not two.
  if (last_with_state_ >= 0 && !keeps_state(settings, result_.steps[last_with_state_].step)) {
    StepRecord& previous = result_.steps[last_with_state_];
    previous.has_state = false;
    previous.displacements = previous.element_forces = previous.reactions = Eigen::VectorXd();
    previous.chord_rotations = {};
    previous.arc_memory = {};
    previous.contact_states = {};
  }
  record.displacements = displacements;
  record.chord_rotations = state.chord_rotations;
  record.arc_memory = state.arc_length;
  record.contact_states = kept_contacts(state.contacts);
  forces_pending_ = defer_forces_ && !keeps_state(settings, record.step);
  if (!forces_pending_) {
    record.element_forces = problem_.element_forces(state);
    take_axial_strain(model_, record);
  }
  record.reactions = problem_.reactions(state.load_factor);
  take_neutral(record, state);
  record.moved_reactions.resize(static_cast<Eigen::Index>(moved_dofs_.size()));
  for (size_t k = 0; k < moved_dofs_.size(); ++k) record.moved_reactions[k] = record.reactions[moved_dofs_[k]];
  record.contacts = problem_.contact_points(state);
  last_with_state_ = static_cast<int>(result_.steps.size());
  result_.steps.push_back(std::move(record));
  observe(result_.steps.back());
}

void Recorder::take_neutral(StepRecord& record, const State& state) {
  std::erase_if(result_.neutral_steps, [&](const NeutralStep& n) { return n.step == record.step; });  // replace_last's
  // Where the tangent's inertia would tell the stability (stability.hpp), and its evaluation is
  // this state's (reactions, above).
  if (!inertia_tells_stability(state.contacts) || !problem_.loads_conservative()) return;
  if (const auto motion = supported_.neutral_motion(record.displacements, problem_.global_internal_force())) {
    record.neutral = true;
    result_.neutral_steps.push_back({record.step, *motion});
  }
}

void Recorder::started_from_newest(const NewtonOutcome& outcome, bool tells) {
  if (last_with_state_ < 0 || !tells) return;
  StepRecord& newest = result_.steps[last_with_state_];
  if (newest.negative_eigenvalues >= 0 || newest.neutral) return;
  newest.negative_eigenvalues = outcome.start_negative_pivots;
  const bool listed = !result_.rounded_steps.empty() && result_.rounded_steps.back().step == newest.step;
  if (outcome.start_rounded && !listed) result_.rounded_steps.push_back({newest.step, *outcome.start_rounded});
}

void Recorder::replace_last(StepRecord record, const NewtonOutcome& outcome, const State& state) {
  record.step = result_.steps.back().step;
  record.cutbacks = result_.steps.back().cutbacks;
  result_.steps.pop_back();
  std::erase_if(result_.rounded_steps, [&](const RoundedStep& r) { return r.step == record.step; });
  last_with_state_ = -1;
  for (int k = static_cast<int>(result_.steps.size()) - 1; k >= 0 && last_with_state_ < 0; --k)
    if (result_.steps[k].has_state) last_with_state_ = k;
  converged(std::move(record), outcome, state);
}

void Recorder::observe(StepRecord& record) const {
  if (observer_) observer_(record);
  // How α moved per iterate is for the observer only (the command line's --log-iterations): kept
  // in every record it grew with contacts × iterations × steps (213 MB of a 5,001-contact run).
  std::vector<std::vector<ContactPoint>>().swap(record.contact_iterates);
}

void Recorder::finish(const State& state) {
  if (!forces_pending_ || last_with_state_ < 0) return;
  result_.steps[last_with_state_].element_forces = problem_.element_forces(state);
  take_axial_strain(model_, result_.steps[last_with_state_]);
  forces_pending_ = false;
}

void Recorder::cut_back(StepRecord record, const std::string& message) const {
  if (!observer_) return;
  record.converged = false;
  record.cut_back = true;
  record.message = message;
  observer_(record);
}

void Recorder::failed(StepRecord record, const std::string& message) {
  record.converged = false;
  record.message = message;
  result_.steps.push_back(std::move(record));
  observe(result_.steps.back());
}

}  // namespace tsm::solver
