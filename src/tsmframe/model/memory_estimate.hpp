#pragma once
// What a run holds in memory at its peak, from the model's counts, before any of it is allocated
// (README, "Memory"): the program itself, the model file's text and parsed document, the nodes and
// elements (the model, the tangent and its factor, the state), the contacts (their bookkeeping per
// candidate element, the solver they call for), the states the output selection keeps, and a
// record per step. The costs per item are measured (bench/README.md, "Memory budget"): the
// estimate is within a factor of 2 of the peak resident memory, mostly well within.

#include <string>
#include <vector>

#include "tsmframe/model/model.hpp"

namespace tsm {

/// The program itself: code, libraries, the heap's first pages (a 10-element model peaks at 5.5 MB).
inline constexpr double program_bytes = 6e6;
/// An input file's text and its parsed document (nlohmann::json: ~8.4 bytes per byte of a list of
/// nodes), both held while it is read: bytes per byte of the file.
inline constexpr double input_per_byte = 10.0;

/// The counts a run's memory follows. Doubles: products of counts must not wrap.
struct ModelCounts {
  double input_bytes = 0.0;  ///< the model file's text while it is parsed and read (0: given in memory)
  double nodes = 0.0, elements = 0.0;
  double free_dofs = 0.0;    ///< unknowns of the tangent
  double contacts = 0.0;
  double contact_candidates = 0.0;  ///< summed over the contacts: the elements each may touch
  double candidate_tables = 0.0;    ///< groups of contacts sharing their candidates (model/candidate_groups)
  double table_candidates = 0.0;    ///< summed over those groups: the elements each may touch
  double contact_spec_bytes = 0.0;  ///< the contacts' settings as read (members lists, Ψ per member)
  double max_iterations = 50.0;     ///< Newton iterates per step (each keeps every contact's point)
  double steps = 0.0;        ///< steps the control plans (arc-length: its max_steps)
  double kept_states = 1.0;  ///< converged steps whose full state the output selection keeps
  double monitored = 0.0;    ///< nodes steps.csv shows
  double moved_dofs = 0.0;   ///< dofs a prescribed displacement moves (their reactions, every step)
};

/// One part of an estimate: what it is (a few words) and its bytes.
struct MemoryPart {
  std::string name;
  double bytes = 0.0;
};

/// An estimate of a run's peak memory, in parts.
struct MemoryEstimate {
  MemoryPart program, input, elements, contacts, kept_states, steps;
  double total() const;
  /// The parts that have a size, largest first.
  std::vector<MemoryPart> parts() const;
};

/// The estimate for these counts.
MemoryEstimate estimate_memory(const ModelCounts& counts);

/// The steps a control plans: steps per leg × legs (load, displacement control), or max_steps
/// (arc-length: a bound, the most it may take).
double planned_steps(const Control& control);
/// The converged steps whose full state `output` keeps of `steps` (the newest one always).
double kept_state_count(const OutputSelection& output, double steps);

/// The counts of a read model; `input_bytes` as the caller knows it.
ModelCounts model_counts(const Model& model, double input_bytes = 0.0);
/// Elements per member (members are meshed in order: a member's elements are consecutive).
std::vector<long> member_element_counts(const Model& model);
/// The elements contact `spec` may touch: those of its members (`per_member`: member_element_counts).
double candidate_count(const ContactSpec& spec, const std::vector<long>& per_member);
/// What a contact's settings take as read (ContactSpec with its lists).
double contact_spec_bytes(const ContactSpec& spec);

}  // namespace tsm
