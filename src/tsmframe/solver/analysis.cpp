#include "tsmframe/solver/analysis.hpp"

#include <algorithm>
#include <map>
#include <cmath>
#include <sstream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/assembly/global_system.hpp"
#include "tsmframe/solver/newton.hpp"
#include "tsmframe/util/first_touch.hpp"

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

constexpr double contact_at_element_end = 1e-3;  // α this close to 0 or 1: the contact point is at the element's end
constexpr double large_arc_of_size = 0.5;  // a failed arc length above this × the model's size: too long a start
constexpr double short_element_ratio = 2.0;  // an EB element shorter than this × its depth: noted when a run fails
constexpr int steps_below_failure = 3;  // converged steps just below an increment that failed before it is tried again
// An element stretched or shortened by more than this (|N| / EA) is noted: Eq. 3–5 are linear in
// the strain, a small-strain law (at 1 % engineering, Green and logarithmic strain differ by 0.5 %).
constexpr double small_strain = 0.01;
constexpr double limit_point_stiffness = 0.1;
constexpr int bisection_rounds = 30;            // a bifurcation's load factor: at most this many halvings …
constexpr double bisection_tolerance = 1e-6;    // … of its bracket, down to this fraction of λ  // a current stiffness below this × the first step's: near a maximum

std::string format_ratio(double ratio) {
  if (ratio >= 10.0 && ratio < 1e15) return std::to_string(std::llround(ratio));  // 233, not 2.3e+02
  std::ostringstream os;
  os.precision(2);
  os << ratio;
  return os.str();
}

/// A failed run's hint where Euler–Bernoulli elements are shorter than twice their section's
/// depth h = √(12 I/A) (a rectangle's): one load step then turns them far less than Timoshenko
/// elements (the paper's Fig. 3; our study: a cantilever of L/h = 20 fails a full circle in one
/// step from 17 EB elements, never with Timoshenko). Empty where there are none, and in models
/// with contacts (their failures have their own causes, told in the message: Fig. 7's EB
/// elements are as short, and fail at the contact element's edge).
std::string short_element_hint(const Model& model) {
  if (!model.contacts.empty()) return "";
  int count = 0;
  double shortest = INFINITY;
  for (const Element& e : model.elements) {
    // Bars (hinged at both ends) do not bend: their depth says nothing.
    if (e.theory != BeamTheory::euler_bernoulli || !(e.section.EA > 0.0) || (e.release_start && e.release_end)) continue;
    const double depth = std::sqrt(12.0 * e.section.EI / e.section.EA);
    const double ratio = (model.nodes[e.end].position - model.nodes[e.start].position).norm() / depth;
    if (ratio < short_element_ratio) {
      ++count;
      shortest = std::min(shortest, ratio);
    }
  }
  if (count == 0) return "";
  std::ostringstream os;
  os << "; " << count << " Euler–Bernoulli element" << (count > 1 ? "s are" : " is")
     << " shorter than twice the section's depth √(12 I/A) (shortest l/h " << format_ratio(shortest)
     << "): such elements take large rotations in a step poorly (the paper's Fig. 3) — Timoshenko elements, or "
        "smaller steps, do better";
  return os.str();
}

/// A failed first step's hint where elements bend next to nothing against their stretching
/// (EI/(EA l0²) below 1e-10: a cable drawn straight, a cable of I = 1e-16 m⁴): straight, such a
/// member has no stiffness across it until it sags, so the first iterate of any step from
/// straight moves it in proportion to the load over EI alone; its first step has to start far
/// smaller than ten halvings give (max_cutbacks 50 took a 20 m cable under its weight in 42
/// steps, 0.01 s). Empty where there are none (bars hinged at both ends do not bend).
std::string cable_hint(const Model& model) {
  constexpr double limp = 1e-10;
  int count = 0;
  double limpest = INFINITY;
  for (const Element& e : model.elements) {
    if (!(e.section.EA > 0.0) || (e.release_start && e.release_end)) continue;
    const double l0 = (model.nodes[e.end].position - model.nodes[e.start].position).norm();
    const double ratio = e.section.EI / (e.section.EA * l0 * l0);
    if (ratio < limp) ++count, limpest = std::min(limpest, ratio);
  }
  if (count == 0) return "";
  std::ostringstream os;
  os << "; " << count << " element" << (count > 1 ? "s bend" : " bends") << " next to nothing against "
     << (count > 1 ? "their" : "its") << " stretching (EI/(EA l²) down to " << limpest
     << "): drawn straight, such a cable has no stiffness across it until it sags — analysis.max_cutbacks 40–60 "
        "lets its first step start small enough, or draw it with a small sag";
  return os.str();
}

std::string failure_text(int step, double from, double to, const char* what, const NewtonOutcome& outcome,
                         int cutbacks) {
  std::ostringstream os;
  os << "step " << step << " (" << what << " " << from << " -> " << to << ") failed: " << outcome.message;
  if (cutbacks > 0) os << ", after " << cutbacks << " cutbacks in a row";
  return os.str();
}

/// The newest converged step and the one before it (null where there is none).
std::pair<StepRecord*, StepRecord*> newest_converged_two(std::vector<StepRecord>& steps) {
  StepRecord* found[2] = {nullptr, nullptr};
  int count = 0;
  for (auto s = steps.rbegin(); s != steps.rend() && count < 2; ++s)
    if (s->converged) found[count++] = &*s;
  return {found[0], found[1]};
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

/// Appends step records to a run: converged steps get their state (only the newest keeps it
/// unless the output selection wants it), every step goes to the observer.
class Recorder {
 public:
  /// With `defer_forces`, a step that the output selection drops again once a later step
  /// converges gets its element forces (a pass over the elements) only if it stays the newest:
  /// finish() adds them. Without an observer only: an observer sees every step whole.
  Recorder(const Model& model, const NewtonSolver& newton, const StepObserver& observer, RunResult& result,
           bool defer_forces = false)
      : model_(model), newton_(newton), observer_(observer), result_(result), defer_forces_(defer_forces && !observer),
        moved_dofs_(model.moved_dofs()) {}

  int next_step() const { return static_cast<int>(result_.steps.size()) + 1; }

  /// A record for the outcome of one attempt.
  StepRecord start(const NewtonOutcome& outcome, int cutbacks) const {
    StepRecord record;
    record.step = next_step();
    record.iterations = outcome.iterations;
    record.residual_norms = outcome.residual_norms;
    record.cutbacks = cutbacks;
    record.contact_iterates = outcome.contact_iterates;
    return record;
  }

  void converged(StepRecord record, const NewtonOutcome& outcome, const State& state) {
    const AnalysisSettings& settings = model_.analysis;
    record.load_factor = state.load_factor;
    record.converged = true;
    record.criterion = outcome.criterion;
    record.carried_nothing = outcome.carried_nothing;
    record.slid_off = outcome.slid_off;
    record.has_state = true;
    record.monitored.resize(dofs_per_node * static_cast<int>(settings.monitor.size()));
    for (size_t m = 0; m < settings.monitor.size(); ++m)
      record.monitored.segment<3>(dofs_per_node * m) = state.displacements.segment<3>(dofs_per_node * settings.monitor[m]);
    record.largest_move = largest_move(state.displacements, last_with_state_ >= 0 ? &result_.steps[last_with_state_].displacements : nullptr);
    // The previous step's state goes first (unless the output keeps it): the peak memory holds one state, not two.
    if (last_with_state_ >= 0 && !keeps_state(settings.output, result_.steps[last_with_state_].step)) {
      StepRecord& previous = result_.steps[last_with_state_];
      previous.has_state = false;
      previous.displacements = previous.element_forces = previous.reactions = Eigen::VectorXd();
    }
    record.displacements = state.displacements;
    forces_pending_ = defer_forces_ && !keeps_state(settings.output, record.step);
    if (!forces_pending_) {
      record.element_forces = newton_.element_forces(state);
      take_axial_strain(model_, record);
    }
    record.reactions = newton_.reactions(state.load_factor);
    record.moved_reactions.resize(static_cast<Eigen::Index>(moved_dofs_.size()));
    for (size_t k = 0; k < moved_dofs_.size(); ++k) record.moved_reactions[k] = record.reactions[moved_dofs_[k]];
    record.contacts = newton_.contact_points(state);
    last_with_state_ = static_cast<int>(result_.steps.size());
    result_.steps.push_back(std::move(record));
    if (observer_) observer_(result_.steps.back());
  }

  /// An attempt that started from the newest converged step's state factorised the tangent there
  /// first: its inertia is that step's, where it tells the stability (`tells`).
  void started_from_newest(const NewtonOutcome& outcome, bool tells) {
    if (last_with_state_ < 0 || !tells || outcome.start_negative_pivots < 0) return;
    int& negatives = result_.steps[last_with_state_].negative_eigenvalues;
    if (negatives < 0) negatives = outcome.start_negative_pivots;
  }

  /// Displacements of the newest converged step, held in its record until a later step
  /// converges (null before the first converged step).
  const Eigen::VectorXd* newest_displacements() const {
    return last_with_state_ >= 0 ? &result_.steps[last_with_state_].displacements : nullptr;
  }

  /// Replaces the newest converged step (arc-length landing exactly on its `until`).
  void replace_last(StepRecord record, const NewtonOutcome& outcome, const State& state) {
    record.step = result_.steps.back().step;
    record.cutbacks = result_.steps.back().cutbacks;
    result_.steps.pop_back();
    last_with_state_ = -1;
    for (int k = static_cast<int>(result_.steps.size()) - 1; k >= 0 && last_with_state_ < 0; --k)
      if (result_.steps[k].has_state) last_with_state_ = k;
    converged(std::move(record), outcome, state);
  }

  /// At the end of the run, with `state` the newest converged step's: its deferred element forces.
  void finish(const State& state) {
    if (!forces_pending_ || last_with_state_ < 0) return;
    result_.steps[last_with_state_].element_forces = newton_.element_forces(state);
    take_axial_strain(model_, result_.steps[last_with_state_]);
    forces_pending_ = false;
  }

  void failed(StepRecord record, const std::string& message) {
    record.converged = false;
    record.message = message;
    result_.steps.push_back(std::move(record));
    if (observer_) observer_(result_.steps.back());
  }

 private:
  const Model& model_;
  const NewtonSolver& newton_;
  const StepObserver& observer_;
  RunResult& result_;
  int last_with_state_ = -1;
  bool defer_forces_ = false;
  std::vector<int> moved_dofs_;
  bool forces_pending_ = false;  ///< the newest converged step still lacks its element forces
};

/// The start of the step being tried under load or displacement control, to go back to when it
/// fails. Its displacements are the newest converged step's, which that step's record holds
/// until a later step converges: only λ, the rotations and the contacts are copied (a vector of
/// the model's size less at 10⁵ elements and up). Before the first step converges, the
/// displacements are copied too.
class StepStart {
 public:
  void take(const State& state, const Eigen::VectorXd* recorded) {
    recorded_ = recorded;
    if (recorded) own_.displacements.resize(0);
    else own_.displacements = state.displacements;
    own_.load_factor = state.load_factor;
    own_.chord_rotations = state.chord_rotations;
    own_.contacts = state.contacts;
  }
  /// Valid until a step converges (the record may then give up its displacements).
  void restore(State& state) const {
    state.displacements = recorded_ ? *recorded_ : own_.displacements;
    state.load_factor = own_.load_factor;
    state.chord_rotations = own_.chord_rotations;
    state.contacts = own_.contacts;
  }
  double load_factor() const { return own_.load_factor; }
  /// The step converged: its start is not needed any more (its own copy goes before the step is
  /// recorded, so that the two never coexist).
  void release() { own_.displacements.resize(0); }

 private:
  State own_;
  const Eigen::VectorXd* recorded_ = nullptr;
};

/// Limit points: converged steps whose λ is a strict local extremum of the path.
std::vector<LimitPoint> limit_points(const std::vector<StepRecord>& steps) {
  std::vector<const StepRecord*> path;
  for (const StepRecord& s : steps)
    if (s.converged) path.push_back(&s);
  std::vector<LimitPoint> points;
  double before = 0.0;  // λ at the start of the path
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const double here = path[k]->load_factor, after = path[k + 1]->load_factor;
    if (here > before && here > after) points.push_back({path[k]->step, true, here});
    if (here < before && here < after) points.push_back({path[k]->step, false, here});
    before = here;
  }
  return points;
}

/// Under displacement control a path that snaps back (the controlled displacement turns back)
/// cannot be followed: a step lands on another branch, and λ leaps back in one step. Noted where
/// a converged step moves λ towards (or past) zero by more than half of its largest magnitude so
/// far and by more than three times any earlier step's change — along the path itself λ changes
/// at a rate like the earlier steps' (a smooth snap-through turns λ round gradually).
std::vector<std::string> jump_notes(const std::vector<StepRecord>& steps) {
  std::vector<std::string> notes;
  double before = 0.0, largest = 0.0, largest_change = 0.0;  // λ at the previous converged step; maxima so far
  for (const StepRecord& s : steps) {
    if (!s.converged) continue;
    const double change = s.load_factor - before;
    if (largest > 0.0 && change * before < 0.0 && std::abs(change) > 0.5 * largest &&
        std::abs(change) > 3.0 * largest_change) {
      std::ostringstream os;
      os << "step " << s.step << ": the load factor leapt from " << before << " to " << s.load_factor
         << " in one step (largest so far " << largest
         << "): the path may snap back here (the controlled displacement turning back), which "
            "displacement control jumps across onto another branch; arc-length control follows it";
      notes.push_back(os.str());
    }
    largest = std::max(largest, std::abs(s.load_factor));
    largest_change = std::max(largest_change, std::abs(change));
    before = s.load_factor;
  }
  return notes;
}

/// Under load control a step that jumps across a limit point, or off an unstable branch, lands
/// on a distant equilibrium: it moves far more per unit of λ than the steps around it (an arch
/// snapping through: 21× the step before, 230× the step after). Noted where a converged step
/// moves ≥ snap_ratio × as far per unit λ as the converged step before it and as the one after
/// it — or, at the end of the path, where it leaves an unstable state for a stable one. A steep
/// but smooth path (a pipe ring flattening at nearly constant pressure) grows its steps
/// gradually on both sides (≤ 4.3× the step after there). Steps whose contact slid off a free
/// end have their own note.
std::vector<std::string> snap_notes(const std::vector<StepRecord>& steps) {
  constexpr double snap_ratio = 5.0;
  std::vector<const StepRecord*> path;
  for (const StepRecord& s : steps)
    if (s.converged) path.push_back(&s);
  std::vector<std::string> notes;
  double before_lambda = 0.0;
  std::vector<double> rate(path.size(), 0.0);  // move per unit λ
  for (size_t k = 0; k < path.size(); ++k) {
    const double dl = std::abs(path[k]->load_factor - before_lambda);
    rate[k] = dl > 0.0 ? path[k]->largest_move / dl : 0.0;
    before_lambda = path[k]->load_factor;
  }
  for (size_t k = 1; k < path.size(); ++k) {
    const StepRecord& s = *path[k];
    if (!s.slid_off.empty() || !(rate[k - 1] > 0.0) || rate[k] < snap_ratio * rate[k - 1]) continue;
    const bool last = k + 1 == path.size();
    const bool settles = !last && rate[k] >= snap_ratio * rate[k + 1];
    const bool stabilises = path[k - 1]->negative_eigenvalues > 0 && s.negative_eigenvalues == 0;
    if (!settles && !stabilises) continue;
    std::ostringstream os;
    os << "step " << s.step << " moved " << format_ratio(rate[k] / rate[k - 1])
       << " times as far per unit of load as the step before it";
    if (settles) os << " and " << format_ratio(rate[k] / rate[k + 1]) << " times as far as the step after it";
    os << " (up to " << s.largest_move << " at a node): the structure probably snapped through there — load control "
       << "jumps across a limit point, or off an unstable branch, onto a distant equilibrium, leaving the path between out; "
          "arc-length control follows it";
    notes.push_back(os.str());
  }
  return notes;
}

/// "step 4", "steps 4 and 9", "6 steps from 4 to 12": the steps a note is about (ascending, ≥ 1).
void write_steps(std::ostream& os, const std::vector<int>& steps) {
  if (steps.size() == 1) os << "step " << steps.front();
  else if (steps.size() == 2) os << "steps " << steps.front() << " and " << steps.back();
  else os << steps.size() << " steps from " << steps.front() << " to " << steps.back();
}

/// Steps accepted on round-off because the structure carried next to nothing (a contact let go
/// and nothing else loads it, or λ is back at zero): their relative residual, up to ~1, is the
/// ratio of two rounding errors. One note for them all, so that the log's large residuals are
/// not read as a failure.
std::vector<std::string> nothing_carried_notes(const std::vector<StepRecord>& steps) {
  std::vector<int> quiet;
  for (const StepRecord& s : steps)
    if (s.converged && s.carried_nothing) quiet.push_back(s.step);
  if (quiet.empty()) return {};
  std::ostringstream os;
  write_steps(os, quiet);
  os << ": the structure carried next to nothing (its internal forces at rounding level: a contact let go and "
        "nothing else loads it, or the load is zero), so the relative residual there is rounding noise; "
     << (quiet.size() == 1 ? "it was" : "they were") << " accepted on round-off";
  return {os.str()};
}

/// Contacts that let go because their point slid off a beam's free end: one note per contact
/// node, with the steps and the element whose end it left (the path lost that support there;
/// under load control a step may so have jumped to where the beam no longer holds the node).
std::vector<std::string> slid_off_notes(const Model& model, const std::vector<StepRecord>& steps) {
  std::map<std::pair<int, int>, std::vector<int>> steps_of;  // (contact, element) → steps
  for (const StepRecord& s : steps)
    if (s.converged)
      for (const auto& [contact, element] : s.slid_off) steps_of[{contact, element}].push_back(s.step);
  std::vector<std::string> notes;
  for (const auto& [key, at] : steps_of) {
    const auto [contact, element] = key;
    std::ostringstream os;
    os << "the contact of node " << model.nodes[model.contacts[contact].node].id << " slid off the free end of member "
       << model.elements[element].member << " (past element " << model.elements[element].id << "'s end) and let go in ";
    write_steps(os, at);
    notes.push_back(os.str());
  }
  return notes;
}

/// Converged steps whose tangent has negative eigenvalues: unstable equilibria under their loads.
/// One note per run of consecutive such steps, with its cause: the limit point where the run
/// begins (a snap-through's falling branch), or, where none does, a bifurcation point passed on
/// the primary path — what a perfect structure does under any control (a straight column
/// loaded beyond its buckling load stays straight, and converges there in one iteration).
std::vector<std::string> stability_notes(const std::vector<StepRecord>& steps, const std::vector<LimitPoint>& limits,
                                         const std::vector<CriticalPoint>& critical_points) {
  struct Run {
    int first = 0, last = 0, fewest = 0, most = 0;
    const StepRecord* stable_before = nullptr;  ///< the converged step before it, known stable
    const StepRecord* first_record = nullptr;
  };
  std::vector<Run> runs;
  const StepRecord* previous = nullptr;  // the previous converged step
  for (const StepRecord& s : steps) {
    if (!s.converged) continue;
    if (s.negative_eigenvalues > 0) {
      if (!runs.empty() && runs.back().last == s.step - 1) {
        Run& r = runs.back();
        r.last = s.step;
        r.fewest = std::min(r.fewest, s.negative_eigenvalues);
        r.most = std::max(r.most, s.negative_eigenvalues);
      } else {
        const bool stable = previous && previous->negative_eigenvalues == 0;
        runs.push_back({s.step, s.step, s.negative_eigenvalues, s.negative_eigenvalues, stable ? previous : nullptr, &s});
      }
    }
    previous = &s;
  }
  std::vector<std::string> notes;
  for (const Run& r : runs) {
    std::ostringstream os;
    const bool one = r.first == r.last;
    if (one) os << "step " << r.first << " ends on an unstable equilibrium under its load";
    else os << "steps " << r.first << "–" << r.last << " end on unstable equilibria under their loads";
    os << ": the tangent stiffness there has ";
    if (r.fewest != r.most) os << r.fewest << " to ";
    os << r.most << " negative eigenvalue" << (r.most > 1 ? "s" : "");
    const auto critical = std::find_if(critical_points.begin(), critical_points.end(),
                                       [&](const CriticalPoint& c) { return c.step == r.first; });
    if (critical != critical_points.end())
      os << " (it turns indefinite at load factor " << critical->load_factor << ", within ±"
         << 0.5 * std::abs(critical->unstable - critical->stable) << ", by bisection between the steps)";
    else if (r.stable_before)  // where the tangent lost its definiteness: a bracket for the critical load
      os << " (stable at load factor " << r.stable_before->load_factor << ", step " << r.stable_before->step
         << "; unstable at " << r.first_record->load_factor << ")";
    // The limit point the run starts at: the path's step there straddles the singular tangent.
    const auto limit = std::find_if(limits.begin(), limits.end(),
                                    [&](const LimitPoint& p) { return std::abs(p.step - r.first) <= 1; });
    if (limit != limits.end())
      os << ", from the load " << (limit->maximum ? "maximum" : "minimum") << " at step " << limit->step << " on";
    else
      os << "; no limit point precedes " << (one ? "it" : "them") << ", so the path has passed a bifurcation point and keeps to its primary "
            "branch, as a perfect structure does (a straight column stays straight beyond its buckling load): an "
            "imperfection or a small disturbing load leads onto the buckled branch";

    notes.push_back(os.str());
  }
  return notes;
}

/// Converged steps where an element is stretched or shortened by more than small_strain: one note
/// for them all, with the largest strain on the path. Eq. 3–5 take N linear in the strain with the
/// rotations exact, so such results hold for that law, not for a real material (a load in the
/// wrong units shows up here).
std::vector<std::string> strain_notes(const Model& model, const std::vector<StepRecord>& steps) {
  std::vector<int> strained;
  const StepRecord* largest = nullptr;
  for (const StepRecord& s : steps) {
    if (!s.converged || s.strained_element < 0 || std::abs(s.axial_strain) <= small_strain) continue;
    strained.push_back(s.step);
    if (!largest || std::abs(s.axial_strain) > std::abs(largest->axial_strain)) largest = &s;
  }
  if (strained.empty()) return {};
  std::ostringstream os;
  write_steps(os, strained);
  os << (strained.size() == 1 ? " stretches or shortens" : " stretch or shorten") << " an element by more than "
     << 100.0 * small_strain << " %: the largest axial strain N/EA is " << 100.0 * largest->axial_strain << " % ("
     << (largest->axial_strain > 0.0 ? "tension" : "compression") << ", element "
     << model.elements[largest->strained_element].id << ", step " << largest->step
     << "). The elements' force laws (Eq. 3–5) are linear in the strain, for small strains (the rotations are exact): "
        "past a few per cent the results hold for that law, not for a real material (check the loads and their units)";
  return {os.str()};
}

/// What the result says about its path besides the steps: the limit points, and the notes.
void close_path(const Model& model, RunResult& result, ControlType control) {
  result.limit_points = limit_points(result.steps);
  result.notes = nothing_carried_notes(result.steps);
  if (control == ControlType::displacement)
    for (std::string& note : jump_notes(result.steps)) result.notes.push_back(std::move(note));
  if (control == ControlType::load)
    for (std::string& note : snap_notes(result.steps)) result.notes.push_back(std::move(note));
  for (std::string& note : stability_notes(result.steps, result.limit_points, result.critical_points))
    result.notes.push_back(std::move(note));
  for (std::string& note : slid_off_notes(model, result.steps)) result.notes.push_back(std::move(note));
  for (std::string& note : strain_notes(model, result.steps)) result.notes.push_back(std::move(note));
}

RunResult run_arc_length(const Model& model, const assembly::DofMap& dofs, NewtonSolver& newton, State& state,
                         const StepObserver& observer);
RunResult run_stepped(const Model& model, const assembly::DofMap& dofs, NewtonSolver& newton, State& state,
                      const StepObserver& observer);

/// Whether the newest converged step is unstable and the one before it stable: under load
/// control a bifurcation of the primary path (load control cannot pass a limit point).
bool turned_unstable(const StepRecord* newest, const StepRecord* previous, const RunResult& result) {
  if (!newest || !previous || newest->negative_eigenvalues <= 0 || previous->negative_eigenvalues != 0) return false;
  return result.critical_points.empty() || result.critical_points.back().step != newest->step;
}

/// The load factor where the tangent turns indefinite between `previous` (stable) and `newest`
/// (unstable), by bisection on its inertia, each trial equilibrium solved from the newest step's
/// state `from`; recorded in result.critical_points. Leaves the solver evaluated at a trial
/// state: the caller evaluates its own again.
void locate_bifurcation(const StepRecord& newest, const StepRecord& previous, const State& from, NewtonSolver& newton,
                        RunResult& result) {
  double stable = previous.load_factor, unstable = newest.load_factor;
  for (int round = 0; round < bisection_rounds; ++round) {
    if (std::abs(unstable - stable) <= bisection_tolerance * std::max(std::abs(stable), std::abs(unstable))) break;
    const double middle = 0.5 * (stable + unstable);
    State trial = from;
    newton.reset(trial);
    PathConstraint constraint;
    constraint.load_increment = middle - trial.load_factor;
    if (newton.step(constraint, trial).status != Status::converged) break;
    const int negatives = newton.negative_eigenvalues(trial, true);
    if (negatives < 0) break;
    (negatives > 0 ? unstable : stable) = middle;
  }
  result.critical_points.push_back({newest.step, 0.5 * (stable + unstable), stable, unstable});
}

/// Whether the tangent's inertia tells the stability of `state`: only where no contact is active
/// (a contact element's sliding term is not symmetric, and the inertia is its symmetric part's).
/// A non-conservative follower load is the other such case; NewtonSolver reports no inertia then.
bool inertia_tells_stability(const State& state) {
  return std::none_of(state.contacts.begin(), state.contacts.end(), [](const contact::ContactState& c) { return c.active; });
}

}  // namespace

RunResult run_analysis(const Model& model, const StepObserver& observer) {
  const AnalysisSettings& settings = model.analysis;
  const Control& control = settings.control;
  assembly::DofMap dofs(model);
  assembly::GlobalSystem system(model, dofs);
  const contact::ContactTracker contacts(model);
  NewtonSolver newton(system, {settings.tolerance, settings.max_iterations}, &contacts);
#if defined(__GLIBC__)
  // The set-up's temporaries (node graph, ordering, fill, tasks) are freed by now but scattered
  // through the heap, where the run's vectors do not fill them: hand their pages back (at 10⁵
  // elements ~3 MB of the peak resident memory, once per run).
  malloc_trim(0);
#endif

  std::vector<double> zero_rotations;
  util::assign_touched(zero_rotations, model.elements.size(), 0.0);
  State state{util::zeros_touched(model.dof_count()), 0.0, std::move(zero_rotations), contacts.initial_states()};
  newton.reset(state);
  RunResult result = control.type == ControlType::arc_length ? run_arc_length(model, dofs, newton, state, observer)
                                                             : run_stepped(model, dofs, newton, state, observer);
  // The newest converged step's inertia: each other step's came with the attempt that started
  // from it. `state` is that step's (every run ends there); the last evaluation was made there
  // unless the run ended on a failed attempt.
  const auto [newest, previous] = newest_converged_two(result.steps);
  if (newest && newest->negative_eigenvalues < 0 && inertia_tells_stability(state))
    newest->negative_eigenvalues = newton.negative_eigenvalues(state, result.steps.back().converged);
  if (control.type == ControlType::load && turned_unstable(newest, previous, result))  // the last step's, as the others'
    locate_bifurcation(*newest, *previous, state, newton, result);
  close_path(model, result, control.type);
  return result;
}

namespace {

RunResult run_stepped(const Model& model, const assembly::DofMap& dofs, NewtonSolver& newton, State& state,
                      const StepObserver& observer) {
  const AnalysisSettings& settings = model.analysis;
  const Control& control = settings.control;
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
  // After a cutback the increment doubles back step by step, but an increment that failed is
  // tried again only after steps_below_failure steps have converged just below it: where the
  // path stays hard, every step tried it first and failed (a beam rolled 60 rad in one step,
  // 60 EB elements: 133 failed attempts in 128 steps), each failure costing up to
  // max_iterations iterations.
  double failed_increment = INFINITY;
  int below_failure = 0;
  int halvings = 0, grid_index = 0;
  RunResult result;
  Recorder recorder(model, newton, observer, result, true);

  StepStart saved;  // reused: no allocation per step
  // The current stiffness parameter |Δλ| / ‖ΔD‖ of the first iterate (the tangent's) at the
  // first step's start and at the newest (Bergan): near a largest load it falls towards zero. A
  // converged step's secant would not: a deep arch's last step below its maximum still had a
  // quarter of the first step's.
  double first_stiffness = 0.0, newest_stiffness = 0.0;
  while (grid_index < grid_steps) {
    const double next_grid = static_cast<double>(grid_index + 1) / control.steps;
    double dt = std::min(increment, next_grid - t);
    if (next_grid - t - dt < 1e-9 * nominal) dt = next_grid - t;
    const bool reaches_grid = dt == next_grid - t;
    const double t_end = reaches_grid ? next_grid : t + dt;
    if (by_displacement) constraint.target = value(t_end) * control.target;
    else constraint.load_increment = value(t_end) - state.load_factor;

    saved.take(state, recorder.newest_displacements());
    const bool tells_stability = inertia_tells_stability(state);
    const NewtonOutcome outcome = newton.step(constraint, state);
    recorder.started_from_newest(outcome, tells_stability);
    if (const auto [newest, previous] = newest_converged_two(result.steps);
        !by_displacement && turned_unstable(newest, previous, result)) {
      State from;  // the newest step's state; the attempt in progress is kept and evaluated again
      saved.restore(from);
      const State attempt = state;
      locate_bifurcation(*newest, *previous, from, newton, result);
      state = attempt;
      newton.reset(state);
    }
    StepRecord record = recorder.start(outcome, halvings);
    record.increment = (value(t_end) - value(t)) * (by_displacement ? control.target : 1.0);

    if (!by_displacement && outcome.start_stiffness > 0.0) {  // each attempt starts from a converged state
      newest_stiffness = outcome.start_stiffness;
      if (first_stiffness == 0.0) first_stiffness = newest_stiffness;
    }
    if (outcome.status == Status::converged) {
      t = t_end;
      if (reaches_grid) ++grid_index;
      halvings = 0;
      const double grown = std::min(2.0 * increment, nominal);
      if (grown < failed_increment * (1.0 - 1e-12)) increment = grown;
      else if (++below_failure >= steps_below_failure) increment = grown, failed_increment = INFINITY;
      saved.release();
      recorder.converged(std::move(record), outcome, state);
      continue;
    }

    saved.restore(state);
    // The smallest increment cutback may try: max_cutbacks halvings of the nominal step. Without
    // it, steps that keep converging ever closer to a barrier would never end.
    const double smallest = std::ldexp(nominal, -settings.max_cutbacks);
    if (settings.cutback && !outcome.size_independent && halvings < settings.max_cutbacks &&
        dt / 2.0 >= smallest * (1.0 - 1e-12)) {
      ++halvings;
      increment = dt / 2.0;
      failed_increment = dt;
      below_failure = 0;
      newton.reset(state);
      continue;
    }
    record.load_factor = by_displacement ? saved.load_factor() : value(t_end);
    result.status = settings.cutback && !outcome.size_independent ? Status::cutback_limit : outcome.status;
    const double from = value(t) * (by_displacement ? control.target : 1.0);
    const double to = value(t_end) * (by_displacement ? control.target : 1.0);
    NewtonOutcome failed = outcome;
    // A largest load: cut back and still failing, the current stiffness down to a tenth of its
    // first step's, and the tangent — positive definite at the step's start — indefinite at its
    // iterates. Load control cannot pass it. Not where a contact point stands at the end of its
    // element (state is the step's start again): the edge, where the contact element's stiffness
    // changes abruptly, is then as likely the cause (Fig. 7's `paper` rows, which cannot hand over).
    const auto at_element_end = [&] {
      return std::any_of(state.contacts.begin(), state.contacts.end(), [](const contact::ContactState& c) {
        return c.active && std::min(c.alpha, 1.0 - c.alpha) < contact_at_element_end;
      });
    };
    // Cut back: halved in this attempt, or already at the smallest size since an earlier failure
    // (its halvings count restarts once a step converges).
    const bool cut_back = halvings > 0 || dt < nominal * (1.0 - 1e-9);
    const bool limit_point = !by_displacement && cut_back && failed.start_negative_pivots == 0 &&
                             failed.most_negative_pivots > 0 && first_stiffness > 0.0 &&
                             newest_stiffness < limit_point_stiffness * first_stiffness && !at_element_end();
    std::string why;
    if (limit_point)
      why = "; the load seems to have reached a maximum (a limit point: the current stiffness |Δλ|/‖ΔD‖ is down to " +
            format_ratio(newest_stiffness / first_stiffness) +
            " of the first step's, and the tangent lost its positive definiteness within the step), "
            "which load control cannot pass: use arc-length control";
    result.message = failure_text(record.step, from, to, by_displacement ? "controlled displacement" : "load factor",
                                  failed, halvings);
    // Cutback could not halve it again: the step was already the smallest max_cutbacks allows
    // since an earlier failure (the halvings count restarts once a step converges).
    if (settings.cutback && halvings == 0 && dt / 2.0 < smallest * (1.0 - 1e-12))
      result.message += ", a step already the smallest cutback allows (1/2^" + std::to_string(settings.max_cutbacks) +
                        " of a nominal step)";
    result.message += why;
    failed.message += why;
    // Cutback used all its halvings in a row (not a step already at its smallest after growing
    // again): a smaller step may pass — a straight cable's first iterate, from EI alone,
    // overshoots in proportion to the load.
    if (settings.cutback && halvings >= settings.max_cutbacks && !limit_point && !failed.loads_unresolvable) {
      result.message += "; analysis.max_cutbacks (now " + std::to_string(settings.max_cutbacks) +
                        ", at most 60) or more steps let a step start smaller";
      if (state.load_factor == 0.0) result.message += cable_hint(model);  // the path's first step
    }
    result.message += short_element_hint(model);
    recorder.finish(state);  // state is the newest converged step's again
    recorder.failed(std::move(record), failed.message);
    return result;
  }
  recorder.finish(state);
  result.status = Status::converged;
  return result;
}

/// The quantity `until` watches, and its target (FORMAT.md `until`).
double watched(const Control& control, const State& state) {
  if (control.until == Control::Until::load_factor) return state.load_factor;
  return state.displacements[dofs_per_node * control.until_node + control.until_dof];
}

RunResult run_arc_length(const Model& model, const assembly::DofMap& dofs, NewtonSolver& newton, State& state,
                         const StepObserver& observer) {
  const AnalysisSettings& settings = model.analysis;
  const Control& control = settings.control;
  // Step size: after a step of n iterations the next arc length is scaled by √(aim / n), at
  // most doubled or halved, within [min_increment, max_increment]; a failed step is retried at
  // half the arc length (cutback) until min_increment.
  constexpr double aim_iterations = 6.0;
  RunResult result;
  Recorder recorder(model, newton, observer, result);
  PathConstraint constraint;
  constraint.kind = PathConstraint::Kind::arc_length;
  double arc = control.initial_increment;
  int halvings = 0, converged_steps = 0;
  const bool watching = control.until != Control::Until::steps;

  State saved;  // the start of the step being tried (reused: no allocation per step)
  while (converged_steps < control.max_steps) {
    saved = state;
    constraint.arc_length = arc;
    const bool tells_stability = inertia_tells_stability(state);
    const NewtonOutcome outcome = newton.step(constraint, state);
    recorder.started_from_newest(outcome, tells_stability);
    StepRecord record = recorder.start(outcome, halvings);
    record.arc_length = arc;
    if (outcome.status == Status::converged) {
      record.increment = state.load_factor - saved.load_factor;
      ++converged_steps;
      // The step's increment steers the next predictor.
      constraint.previous_increment.resize(dofs.free_count());
      for (int eq = 0; eq < dofs.free_count(); ++eq)
        constraint.previous_increment[eq] = state.displacements[dofs.dof(eq)] - saved.displacements[dofs.dof(eq)];
      constraint.previous_load_increment = record.increment;
      halvings = 0;
      const double factor = std::clamp(std::sqrt(aim_iterations / std::max(1, outcome.iterations)), 0.5, 2.0);
      arc = std::clamp(arc * factor, control.min_increment, control.max_increment);
      const double before = watched(control, saved), after = watched(control, state);
      const bool reached = watching && (before - control.until_value) * (after - control.until_value) <= 0.0 && after != before;
      recorder.converged(std::move(record), outcome, state);
      if (!reached) continue;
      // Land exactly on the target: redo the step from its start under load or displacement control.
      State landed = saved;
      newton.reset(landed);
      PathConstraint land;
      if (control.until == Control::Until::load_factor) {
        land.kind = PathConstraint::Kind::load_increment;
        land.load_increment = control.until_value - saved.load_factor;
      } else {
        land.kind = PathConstraint::Kind::displacement_target;
        land.equation = dofs.equation(dofs_per_node * control.until_node + control.until_dof);
        land.target = control.until_value;
      }
      const NewtonOutcome landing = newton.step(land, landed);
      if (landing.status == Status::converged) {
        StepRecord exact = recorder.start(landing, 0);
        exact.increment = landed.load_factor - saved.load_factor;
        exact.arc_length = 0.0;  // landed under load/displacement control
        state = landed;
        recorder.replace_last(std::move(exact), landing, state);
      } else {
        newton.reset(state);  // keep the arc-length step that passed the target
      }
      result.status = Status::converged;
      return result;
    }
    state = saved;
    if (settings.cutback && halvings < settings.max_cutbacks && arc / 2.0 >= control.min_increment * (1.0 - 1e-12)) {
      ++halvings;
      arc /= 2.0;
      newton.reset(state);
      continue;
    }
    // No arc reaches the path here: it jumps (a contact slipping off a beam's end springs the
    // beam back at one load factor). Try one load-controlled step of the last Δλ across the jump.
    if (constraint.previous_load_increment != 0.0) {
      newton.reset(state);
      PathConstraint jump;
      jump.load_increment = constraint.previous_load_increment;
      const NewtonOutcome across = newton.step(jump, state);
      recorder.started_from_newest(across, inertia_tells_stability(saved));
      if (across.status == Status::converged) {
        StepRecord crossed = recorder.start(across, halvings);
        crossed.increment = state.load_factor - saved.load_factor;
        constraint.previous_increment.resize(0);  // the jump is no direction to follow
        halvings = 0;
        arc = control.initial_increment;
        ++converged_steps;
        recorder.converged(std::move(crossed), across, state);
        continue;
      }
      state = saved;
      newton.reset(state);
    }
    record.load_factor = saved.load_factor;
    result.status = settings.cutback ? Status::cutback_limit : outcome.status;
    std::ostringstream os;
    os << "step " << record.step << " (arc length " << arc << " from load factor " << saved.load_factor
       << ") failed: " << outcome.message;
    if (halvings > 0) os << ", after " << halvings << " cutbacks in a row";
    // Δs is a length (translations): a step still as long as half the structure after its
    // cutbacks was given far too long an arc to start with (the usual cause of "no real root").
    if (arc > large_arc_of_size * model.size)
      os << "; the arc length is still " << format_ratio(arc / model.size)
         << " × the structure's size (" << model.size
         << ", its bounding box's diagonal): give initial_increment and max_increment a few per cent of it";
    result.message = os.str() + short_element_hint(model);
    recorder.failed(std::move(record), outcome.message);
    return result;
  }
  if (watching) {
    result.status = Status::step_limit;
    std::ostringstream os;
    os << "max_steps (" << control.max_steps << ") used before reaching the `until` target " << control.until_value
       << " (now " << watched(control, state) << ")";
    result.message = os.str();
  } else {
    result.status = Status::converged;
  }
  return result;
}

}  // namespace

}  // namespace tsm::solver
