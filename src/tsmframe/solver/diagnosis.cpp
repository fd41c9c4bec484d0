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

/// "; the load seems to have reached a maximum …": a limit point found where a step failed.
std::string limit_point_text(const RunFailure& failure) {
  if (!(failure.limit_point_stiffness > 0.0)) return "";
  return "; the load seems to have reached a maximum (a limit point: the current stiffness |Δλ|/‖ΔD‖ is down to " +
         format_ratio(failure.limit_point_stiffness) +
         " of the first step's, and the tangent lost its positive definiteness within the step), "
         "which load control cannot pass: use arc-length control";
}

std::string stepped_failure_text(const RunFailure& failure, const Model& model) {
  std::ostringstream os;
  os << "step " << failure.step << " ("
     << (failure.control == RunFailure::Control::controlled_displacement ? "controlled displacement" : "load factor") << " "
     << failure.from << " -> " << failure.to << ") failed: " << failure.step_message;
  if (failure.cutbacks > 0) os << ", after " << failure.cutbacks << " cutbacks in a row";
  std::string text = os.str();
  // Cutback could not halve it again: the step was already the smallest max_cutbacks allows
  // since an earlier failure (the halvings count restarts once a step converges).
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
     << ") failed: " << failure.step_message;
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

std::string step_failure_text(const RunFailure& failure) { return failure.step_message + limit_point_text(failure); }

std::string run_failure_text(const RunFailure& failure, const Model& model) {
  switch (failure.kind) {
    case RunFailure::Kind::none: return "";
    case RunFailure::Kind::step_limit: {
      std::ostringstream os;
      os << "max_steps (" << failure.max_steps << ") used before reaching the `until` target " << failure.until_value
         << " (now " << failure.until_now << ")";
      return os.str();
    }
    case RunFailure::Kind::step_failed:
      return failure.control == RunFailure::Control::arc_length ? arc_length_failure_text(failure, model)
                                                                : stepped_failure_text(failure, model);
  }
  return "";
}

}  // namespace tsm::solver
