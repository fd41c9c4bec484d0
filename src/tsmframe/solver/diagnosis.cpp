#include "tsmframe/solver/diagnosis.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tsm::solver {
namespace {

constexpr double large_arc_of_size = 0.5;  // a failed arc length above this × the model's size: too long a start
constexpr double short_element_ratio = 2.0;  // an EB element shorter than this × its depth: noted when a run fails

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
    const double ratio = model.drawn_length(e) / depth;
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
    const double l0 = model.drawn_length(e);
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

/// The id of a contact's node.
int contact_node_id(const Model& model, int contact) { return model.nodes[model.contacts[contact].node].id; }

/// The shortest element at a node, as drawn (∞ at a node no element holds).
double shortest_element_at(const Model& model, int node) {
  double shortest = INFINITY;
  for (const Element& e : model.elements)
    if (e.start == node || e.end == node)
      shortest = std::min(shortest, model.drawn_length(e));
  return shortest;
}

std::string hopping_text(const StepFailure& f, const Model& model) {
  std::ostringstream os;
  os << "contact points keep hopping between elements";
  if (f.hopping_contact < 0) return os.str();
  const int node = model.contacts[f.hopping_contact].node;
  os << " (node " << model.nodes[node].id << " back and forth across beam node " << model.nodes[f.hop_node].id;
  // A point drawn on a beam node where two elements meet at an angle (a symmetric push on a
  // node) is pushed along one chord's normal, then the other's (README, Contact). One drawn
  // farther away got there on the path, or in the step: a load that crushes the beam it presses
  // on (a plank under 5·10⁹ N/m) sends the points across nodes in every iterate.
  constexpr double near_node = 0.1;  // of the shortest element there: a point drawn that close may rest on it
  const double drawn = (model.nodes[node].position - model.nodes[f.hop_node].position).norm();
  if (drawn <= near_node * shortest_element_at(model, f.hop_node))
    os << ": if it rests on that node, move it off, e.g. with an odd number of divisions)";
  else
    os << ", " << drawn << " from where it was drawn: smaller steps may settle it, unless the load is too large for the structure)";
  return os.str();
}

/// Where most of the rounding that left the loads unresolvable is: one contact's force, or many
/// contacts' together, and what makes that contact so stiff. Empty where it is not in contacts.
std::string rounding_contact_text(const assembly::RoundingFloor& floor, const Model& model) {
  const bool one = 6.0 * floor.contact_force * floor.contact_force >= 0.5 * floor.force * floor.force;
  const bool together = floor.contacts > 1 && floor.contacts_force * floor.contacts_force >= 0.5 * floor.force * floor.force;
  if (floor.contact_node < 0 || !(one || together)) return "";
  std::ostringstream contact;
  if (one)
    contact << "; most of that rounding is in the force of the contact at node " << model.nodes[floor.contact_node].id
            << " (±" << floor.contact_force << ")";
  else
    contact << "; most of that rounding is in the forces of the " << floor.contacts << " contacts in touch (together ±"
            << floor.contacts_force << "; the largest ±" << floor.contact_force << ", at node "
            << model.nodes[floor.contact_node].id << ")";
  contact << ", as stiff as the element it touches is at its point (1/c = " << 1.0 / floor.compliance
          << "; a member far stiffer than what presses on it makes it so)";
  if (floor.at_cap)
    contact << ": that is the contact's cap, \"max_stiffness_ratio\" times the stiffest element holding its "
               "node (a smaller ratio softens it)";
  else if (floor.at_edge)
    contact << ": the point is at a beam node, where the contact's \"edge\" sets that compliance (a larger "
               "edge, 0.1 say, softens it)";
  else if (floor.uncapped)
    contact << ": a node no element holds (a rigid pusher) has no stiffness cap; a touched member 100× "
               "stiffer than what loads it worked in our tests";
  return contact.str();
}

std::string max_iterations_text(const StepFailure& f) {
  std::ostringstream os;
  os << "no convergence in " << f.iteration << " iterations (last relative residual " << f.relative_residual << ")";
  if (f.unsettled > 0) {  // the equilibrium was found, but never with a set of contacts that all press
    os << ": " << f.unsettled << " converged iterates had a contact pull or a node through a beam, so the set of "
       << "contacts in touch did not settle";
    // Many contacts closing together settle a few per converged iterate: a beam pressed onto
    // another along its length (165 contacts) needed 300 iterations for its first step.
    if (f.contact_nodes > 8)
      os << " (with " << f.contact_nodes << " contact nodes it may settle given more: analysis.max_iterations, now "
         << f.iteration << ", or smaller steps)";
  }
  return os.str();
}

/// A mechanism's free motion (free_mode.hpp): the nodes that move most and which way.
std::string mechanism_text(const StepFailure& f, const Model& model) {
  std::ostringstream os;
  os << "the structure is a mechanism: unloaded, it can move with no element deforming — ";
  if (f.turning_only) {
    os << "node " << model.nodes[f.moving_nodes.front()].id << " turning freely";
  } else {
    os << (f.moving_count > 1 ? "nodes " : "node ");
    for (size_t k = 0; k < f.moving_nodes.size(); ++k)
      os << (k == 0 ? "" : k + 1 == f.moving_nodes.size() && f.moving_count == static_cast<int>(f.moving_nodes.size()) ? " and " : ", ")
         << model.nodes[f.moving_nodes[k]].id;
    if (f.moving_count > static_cast<int>(f.moving_nodes.size()))
      os << " and " << f.moving_count - static_cast<int>(f.moving_nodes.size()) << " more";
    const Eigen::Vector2d& d = f.moving_direction;
    if (d.isZero()) os << " moving most";
    else if (std::abs(d.y()) < 1e-3) os << " moving along x";
    else if (std::abs(d.x()) < 1e-3) os << " moving along y";
    else os << " moving along (" << d.x() << ", " << d.y() << ")";
  }
  os << " — add a support or a joint that stops it"
     << (f.hinged ? " (member releases leave such motions: three hinges in a line, a frame with four)" : "");
  return os.str();
}

/// What went wrong at the iterate, without where ("… at iteration n" is added by the caller).
std::string iterate_failure_text(const StepFailure& f, const Model& model) {
  using Reason = StepFailure::Reason;
  std::ostringstream os;
  switch (f.reason) {
    case Reason::singular_tangent:
      // Hinges can leave a mechanism inside a part (pinned bars in a row) that the supports'
      // check, which looks at parts as rigid bodies, does not see.
      return f.hinged ? "the tangent stiffness is singular (a limit or bifurcation point, or the member releases leave "
                        "a mechanism, e.g. three hinges in a line)"
                      : "the tangent stiffness is singular (a limit or bifurcation point)";
    case Reason::arc_length_undefined: return "the load moves no translation (arc length undefined)";
    case Reason::arc_length_no_root: return "the arc-length constraint has no real root";
    case Reason::controlled_dof_immobile:
      // Where the load reaches the dof only through a contact still open (a beam pressed onto
      // another, the lower one's dof controlled), nothing moves it until that contact closes.
      return f.contacts ? "the controlled dof does not move under the load (if the load reaches it only through a "
                          "contact still open, it does not until that closes: control a dof the load moves from the "
                          "start, or use arc-length control)"
                        : "the controlled dof does not move under the load";
    case Reason::correction_not_finite: return "the Newton correction is not finite";
    case Reason::contacts_switching: return "contacts keep switching on and off";
    case Reason::contacts_hopping: return hopping_text(f, model);
    case Reason::residual_not_finite: return "the unbalanced force is not finite";
    case Reason::loads_unresolvable:
      os << "the unbalanced force stays at the rounding level of the internal forces (relative residual "
         << f.relative_residual << "): the loads are too small against what rounding leaves in this model's forces to be "
         << "resolved (a larger load, in proportion, is)";
      return os.str();
    case Reason::contact_passed_through: return "a contact node passed through a beam after its contact was released";
    case Reason::end_turned_too_far:
      os << "an element end turned " << f.end_rotation
         << " rad against its chord, beyond what an element describes (refine the mesh or take smaller steps)";
      return os.str();
    case Reason::contact_blocked:
      os << "contact node " << contact_node_id(model, f.blocked_contact) << " reached element "
         << model.elements[f.element].id << ", which contact node "
         << (f.holding_contact >= 0 ? contact_node_id(model, f.holding_contact) : -1)
         << " is on in the other frame (points on one element share its frame: give both contacts the same \"frame\")";
      return os.str();
    case Reason::mechanism: return mechanism_text(f, model);
    case Reason::blew_up: return "the unbalanced force blew up";
    case Reason::none:
    case Reason::max_iterations: break;
  }
  return "";
}

/// "; the load seems to have reached a maximum …": a limit point found where a step failed.
std::string limit_point_text(const RunFailure& failure) {
  if (!(failure.limit_point_stiffness > 0.0)) return "";
  return "; the load seems to have reached a maximum (a limit point: the current stiffness |Δλ|/‖ΔD‖ is down to " +
         format_ratio(failure.limit_point_stiffness) + " of the first step's" +
         (failure.limit_point_ahead ? " and, falling as it does, reaches nil within the step" : "") +
         ", and the tangent lost its positive definiteness within the step), "
         "which load control cannot pass: use arc-length control";
}

std::string stepped_failure_text(const RunFailure& failure, const Model& model) {
  std::ostringstream os;
  os << "step " << failure.step << " ("
     << (failure.control == RunFailure::Control::controlled_displacement ? "controlled displacement" : "load factor") << " "
     << failure.from << " -> " << failure.to << ") failed: " << step_failure_text(failure.step_failure, model);
  if (failure.cutbacks > 0) os << ", after " << failure.cutbacks << " cutbacks in a row";
  std::string text = os.str();
  // Cutback could not halve it again: the step was the smallest max_cutbacks allows, reached with
  // halvings to spare (the halvings count restarts once a step converges).
  if (failure.smallest_step)
    text += ", a step already the smallest cutback allows (1/2^" + std::to_string(failure.max_cutbacks) + " of a nominal step)";
  text += limit_point_text(failure);
  // Cutback used all its halvings in a row (not a step already at its smallest after growing
  // again): a smaller step may pass — a straight cable's first iterate, from EI alone,
  // overshoots in proportion to the load.
  if (failure.cutbacks_exhausted) {
    text += "; analysis.max_cutbacks (now " + std::to_string(failure.max_cutbacks) +
            ", at most 60) or more steps let a step start smaller";
    if (failure.first_step) text += cable_hint(model);
  }
  return text + short_element_hint(model);
}

std::string arc_length_failure_text(const RunFailure& failure, const Model& model) {
  const double arc = failure.to;
  std::ostringstream os;
  os << "step " << failure.step << " (arc length " << arc << " from load factor " << failure.from
     << ") failed: " << step_failure_text(failure.step_failure, model);
  if (failure.cutbacks > 0) os << ", after " << failure.cutbacks << " cutbacks in a row";
  // Δs is a length (translations): a step still as long as half the structure after its
  // cutbacks was given far too long an arc to start with (the usual cause of "no real root").
  if (arc > large_arc_of_size * model.size)
    os << "; the arc length is still " << format_ratio(arc / model.size) << " × the structure's size (" << model.size
       << ", its bounding box's diagonal): give initial_increment and max_increment a few per cent of it";
  return os.str() + short_element_hint(model);
}

}  // namespace

std::string format_ratio(double ratio) {
  if (ratio >= 10.0 && ratio < 1e15) return std::to_string(std::llround(ratio));  // 233, not 2.3e+02
  std::ostringstream os;
  os.precision(2);
  os << ratio;
  return os.str();
}

std::string step_failure_text(const StepFailure& f, const Model& model) {
  std::string text;
  if (f.reason == StepFailure::Reason::max_iterations) {
    text = max_iterations_text(f);
  } else {
    std::ostringstream os;
    os << iterate_failure_text(f, model) << " at iteration " << f.iteration;
    text = os.str();
    if (f.reason == StepFailure::Reason::loads_unresolvable) text += rounding_contact_text(f.floor, model);
  }
  if (f.lost_resting_contact < 0) return text;
  // The cause first: what Newton then met follows from it.
  return "the structure is held only by the contacts resting on it and the one at node " +
         std::to_string(contact_node_id(model, f.lost_resting_contact)) +
         (f.resting_contact_slid_off ? " has slid off the beam's end" : " let go") + ": nothing else supports it (then " +
         text + ")";
}

std::string failed_step_text(const RunFailure& failure, const Model& model) {
  return step_failure_text(failure.step_failure, model) + limit_point_text(failure);
}

std::string run_failure_text(const RunFailure& failure, const Model& model) {
  switch (failure.kind) {
    case RunFailure::Kind::none: return "";
    case RunFailure::Kind::step_limit: {
      std::ostringstream os;
      os << "max_steps (" << failure.max_steps << ") used before reaching the `until` target " << failure.until_value
         << " (now " << failure.until_now << ")";
      return os.str();
    }
    case RunFailure::Kind::interrupted: {
      if (failure.step <= 1) return "interrupted on request before the first step";
      std::ostringstream os;
      os << "interrupted on request before step " << failure.step << " (the last converged step at load factor "
         << failure.from << ")";
      return os.str();
    }
    case RunFailure::Kind::step_failed:
      return failure.control == RunFailure::Control::arc_length ? arc_length_failure_text(failure, model)
                                                                : stepped_failure_text(failure, model);
  }
  return "";
}

std::string in_stage_text(const std::string& text, int stage, const std::string& name) {
  std::string stage_name = "stage " + std::to_string(stage + 1);
  if (!name.empty()) stage_name += " (\"" + name + "\")";
  return "In " + stage_name + ": " + text;
}

std::string control_at_target_text(const Model& stage) {
  const Control& control = stage.analysis.control;
  std::ostringstream os;
  os << "its displacement control starts at its target (" << dof_name(control.dof) << " of node "
     << stage.nodes[control.node].id << " = " << control.target << "): nothing to drive, no step run";
  return os.str();
}

}  // namespace tsm::solver
