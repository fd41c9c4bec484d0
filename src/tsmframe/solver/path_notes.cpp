#include "tsmframe/solver/path_notes.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>

#include "tsmframe/linalg/inertia.hpp"
#include "tsmframe/solver/diagnosis.hpp"

namespace tsm::solver {
namespace {

// An element stretched or shortened by more than this (|N| / EA) is noted: Eq. 3–5 are linear in
// the strain, a small-strain law (at 1 % engineering, Green and logarithmic strain differ by 0.5 %).
constexpr double small_strain = 0.01;

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
    if (s.converged && s.criterion == Criterion::nothing_carried) quiet.push_back(s.step);
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
         << 0.5 * std::abs(critical->unstable - critical->stable) << ", by bisection between the steps"
         << (critical->rounded ? "; nearer it, round-off leaves the eigenvalue count in doubt" : "") << ")";
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

/// One note per run of consecutive steps in `listed` (each with a `step`), from its first entry:
/// `write(os, first, plural)` after "step N ends" or "steps N–M end".
template <class Listed, class Write>
std::vector<std::string> notes_per_run(const std::vector<Listed>& listed, Write write) {
  std::vector<std::string> notes;
  for (size_t k = 0; k < listed.size();) {
    size_t last = k;
    while (last + 1 < listed.size() && listed[last + 1].step == listed[last].step + 1) ++last;
    std::ostringstream os;
    if (last == k) os << "step " << listed[k].step << " ends";
    else os << "steps " << listed[k].step << "–" << listed[last].step << " end";
    write(os, listed[k], last > k);
    notes.push_back(os.str());
    k = last + 1;
  }
  return notes;
}

/// Converged steps in neutral equilibrium (Recorder: the supports let a part move as a rigid
/// body there, its loads doing no work along the motion): one note per run of consecutive such
/// steps, naming the first one's motion. Their tangent is singular, so that no eigenvalue count
/// is given for them.
std::vector<std::string> neutral_notes(const Model& model, const std::vector<NeutralStep>& neutral) {
  return notes_per_run(neutral, [&](std::ostringstream& os, const NeutralStep& first, bool) {
    const FreeMotion& motion = first.motion;
    os << " in neutral equilibrium: there the supports let " << part_text(model, motion) << " "
       << motion_text(motion) << " as a rigid body"
       << (motion.kind == FreeMotion::Kind::rotation ? " (their lines of action pass through that point)"
                                                     : " (none acts along it)")
       << " and its loads do no work along that motion, so the tangent stiffness is singular and its eigenvalues tell "
          "nothing of the stability";
  });
}

/// Converged steps whose stability round-off leaves unknown (Recorder, stability: a pivot of the
/// tangent's factorisation within round-off of zero, linalg/inertia.hpp): one note per run of
/// consecutive such steps, naming its first step's pivot.
std::vector<std::string> rounded_notes(const Model& model, const std::vector<RoundedStep>& rounded) {
  return notes_per_run(rounded, [&](std::ostringstream& os, const RoundedStep& first, bool plural) {
    const RoundedInertia& pivot = first.pivot;
    os << " with " << (plural ? "their" : "its") << " stability unknown (no negative_eigenvalues): round-off "
       << "leaves the tangent stiffness's eigenvalue count in doubt — its pivot at node " << model.nodes[pivot.node].id
       << " along " << dof_name(pivot.dof) << " is " << std::setprecision(2) << pivot.ratio
       << " of that node's own stiffness there, below " << linalg::doubtful_pivot
       << ", within the factorisation's rounding, so that no double-precision count has its sign. A structure far "
       << "softer as a whole than its stiffest element does this (a member very much longer than deep, in many short "
       << "elements): fewer, longer elements resolve it";
  });
}

}  // namespace

namespace {

/// Whether a contact point changed elements between two converged steps (passed an element end,
/// or touched or let go: the contact's path has a kink there either way).
bool contact_changed_element(const StepRecord& a, const StepRecord& b) {
  for (size_t c = 0; c < std::min(a.contacts.size(), b.contacts.size()); ++c)
    if (a.contacts[c].element != b.contacts[c].element || a.contacts[c].partner != b.contacts[c].partner) return true;
  return false;
}

}  // namespace

std::vector<LimitPoint> limit_points(const std::vector<StepRecord>& steps, const std::vector<RefinedLimit>& refined) {
  std::vector<const StepRecord*> path;
  for (const StepRecord& s : steps)
    if (s.converged) path.push_back(&s);
  std::vector<LimitPoint> points;
  double before = 0.0;  // λ at the start of the path
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const double here = path[k]->load_factor, after = path[k + 1]->load_factor;
    const bool maximum = here > before && here > after, minimum = here < before && here < after;
    before = here;
    if (!maximum && !minimum) continue;
    LimitPoint point;
    point.step = path[k]->step, point.maximum = maximum, point.load_factor = here;
    for (const RefinedLimit& r : refined)
      if (r.step == point.step) point.refined = r;
    point.contact_kink = (k > 0 && contact_changed_element(*path[k - 1], *path[k])) ||
                             contact_changed_element(*path[k], *path[k + 1]);
    points.push_back(point);
  }
  return points;
}

namespace {

/// Limit points where a contact point changed elements between the steps around them.
std::vector<std::string> contact_kink_notes(const std::vector<LimitPoint>& limits) {
  std::vector<std::string> notes;
  for (const LimitPoint& p : limits) {
    if (!p.contact_kink) continue;
    std::ostringstream os;
    os << "the load " << (p.maximum ? "maximum" : "minimum") << " at step " << p.step << " (load factor " << p.load_factor
       << ") comes where a contact point changes elements (passes an element end, touches or lets go): the contact's "
       << "path kinks there, so that on a coarse mesh the extremum may be the mesh's rather than the structure's — a "
       << "finer mesh of the touched members tells";
    notes.push_back(os.str());
  }
  return notes;
}

}  // namespace

std::string unresolved_buckling_note(int asked, size_t found) {
  std::ostringstream os;
  os << "linearised buckling resolved " << found << " of the " << asked << " modes asked for: the next lies below the "
     << "round-off of the stiffness's factorisation (its stiffness under 1e-16 of the stiffest element's — members "
     << "very much longer than deep in short elements), so that no double-precision solve gives it; fewer, longer "
     << "elements give it, or the path's own stability (negative_eigenvalues) under that load";
  return os.str();
}

std::string unreached_buckling_note(int step) {
  if (step == 0) return "linearised buckling was asked at the run's last converged state, and no step converged";
  return "linearised buckling was asked at step " + std::to_string(step) + ", which the run did not reach converged";
}

/// What the result says about its path besides the steps: the limit points, and the notes.
void close_path(const Model& model, RunResult& result, ControlType control) {
  result.limit_points = limit_points(result.steps, result.refined_limits);
  if (control == ControlType::load)  // λ's extrema are the path's legs: the user's, not the structure's
    for (LimitPoint& p : result.limit_points) p.contact_kink = false;
  result.notes = nothing_carried_notes(result.steps);
  if (control == ControlType::displacement)
    for (std::string& note : jump_notes(result.steps)) result.notes.push_back(std::move(note));
  if (control == ControlType::load)
    for (std::string& note : snap_notes(result.steps)) result.notes.push_back(std::move(note));
  for (std::string& note : stability_notes(result.steps, result.limit_points, result.critical_points))
    result.notes.push_back(std::move(note));
  for (std::string& note : contact_kink_notes(result.limit_points)) result.notes.push_back(std::move(note));
  for (std::string& note : neutral_notes(model, result.neutral_steps)) result.notes.push_back(std::move(note));
  for (std::string& note : rounded_notes(model, result.rounded_steps)) result.notes.push_back(std::move(note));
  for (std::string& note : slid_off_notes(model, result.steps)) result.notes.push_back(std::move(note));
  for (std::string& note : strain_notes(model, result.steps)) result.notes.push_back(std::move(note));
}

}  // namespace tsm::solver
