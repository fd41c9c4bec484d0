#include "tsmframe/model/memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tsmframe/model/candidate_groups.hpp"

namespace tsm {
namespace {

// Per element and per node, beside the state kept (below): the model, the tangent's blocks and
// their LDLᵀ factor, the chord rotations, the step's start, the solver's vectors. With one state,
// 350 per element and 200 per node: chains of 10⁴ to 3·10⁵ elements peak at 548 bytes per element
// and node, lattices of 10⁵ and 4·10⁵ elements at 680 and 730 (more fill in the factor).
constexpr double per_element = 326.0, per_node = 152.0;
// A converged state with its results: displacements and reactions (3 doubles per node), element
// forces (3 per element) and the chord rotation a restart goes on from (1 per element).
constexpr double state_per_node = 48.0, state_per_element = 32.0;
// A step's record (solver::StepRecord: 304 bytes of fields, the residual norms, the allocations'
// headers), and what it shows in steps.csv: the monitored nodes' displacements, the reactions at
// the moved dofs, every contact's point.
constexpr double per_step = 400.0, step_per_monitored = 24.0, step_per_moved = 8.0, step_per_contact = 48.0;
// A contact: its state, its geometry's settings and its step's points, and its reference at the
// step's start — the candidates near its node and its side of each (~64 of them, 4¼ bytes each):
// ~900 bytes; its element's response as the assembly adds it, kept for the next contact change
// (assembly::KeptPointResponse, 784 bytes); its point at every Newton iterate of a step (48
// bytes). Per candidate a side, two bits, where an iterate moves the node beyond the broad
// phase's reach or the node lets go (contact/sides.hpp; counted for every contact at once), and
// for a node let go off a free end its place in each candidate chord's frame (16 bytes; counted
// for `released_places` contacts at once).
// Per group of contacts that may touch the same elements (model/candidate_groups) one table: the
// candidates' places (an int per element of the model), and per candidate its index and Ψ (12 bytes).
constexpr double contact_fixed = 900.0 + 784.0, contact_per_candidate = 0.25, contact_per_iterate = 48.0;
constexpr double place_per_candidate = 16.0, released_places = 64.0;
constexpr double table_per_element = 4.0, table_per_candidate = 12.0;
// Once per model with contacts: each element's initial chord and the elements at each node; the
// displacements and chord rotations the references were taken at (solver::State's, and the
// copy the step's start keeps): 48 bytes per node, 16 per element.
constexpr double contacts_per_element = 64.0, contacts_per_node = 48.0;
// The solver once contacts touch: beyond 32 of them the sliding terms join the node-block LU (a
// second triangle of the tangent's size), but a sparse LU of the whole tangent stays the
// fallback where an unpivoted pivot block is singular and is counted (Eigen's SparseLU: ~5 KB
// per unknown, measured on beams pressed onto beams); up to 32 a dense column per contact
// (Woodbury); from 4 on, the release look-ahead's G over the contacts in touch (at most 2,000).
constexpr double sparse_lu_per_dof = 5000.0;
constexpr double woodbury_most = 32.0, forecast_fewest = 4.0, forecast_most = 2000.0;

/// A count as text, its thousands apart: "400,020,000" (three digits past 10¹⁵: "1.23e+18").
std::string count_text(double n) {
  char text[32];
  if (n >= 1e15) {
    std::snprintf(text, sizeof text, "%.2e", n);
    return text;
  }
  const int length = std::snprintf(text, sizeof text, "%.0f", n);
  std::string out;
  for (int k = 0; k < length; ++k) {
    if (k > 0 && (length - k) % 3 == 0) out.push_back(',');
    out.push_back(text[k]);
  }
  return out;
}

double contact_solver_bytes(const ModelCounts& c) {
  if (c.contacts == 0.0) return 0.0;
  double bytes = c.contacts > woodbury_most ? sparse_lu_per_dof * c.free_dofs : 8.0 * c.contacts * c.free_dofs;
  if (c.contacts >= forecast_fewest) bytes += 8.0 * std::pow(std::min(c.contacts, forecast_most), 2);
  return bytes;
}

}  // namespace

double MemoryEstimate::total() const {
  return program.bytes + input.bytes + elements.bytes + contacts.bytes + kept_states.bytes + steps.bytes;
}

std::vector<MemoryPart> MemoryEstimate::parts() const {
  std::vector<MemoryPart> out;
  for (const MemoryPart* p : {&program, &input, &elements, &contacts, &kept_states, &steps})
    if (p->bytes > 0.0) out.push_back(*p);
  std::stable_sort(out.begin(), out.end(), [](const MemoryPart& a, const MemoryPart& b) { return a.bytes > b.bytes; });
  return out;
}

MemoryEstimate estimate_memory(const ModelCounts& c) {
  MemoryEstimate e;
  e.program = {"the program", program_bytes};
  e.input = {"the model file", input_per_byte * c.input_bytes};
  e.elements = {count_text(c.elements) + " elements and " + count_text(c.nodes) + " nodes",
                per_element * c.elements + per_node * c.nodes};
  const double places = c.contacts > 0.0 ? std::min(c.contacts, released_places) * c.contact_candidates / c.contacts : 0.0;
  e.contacts = {count_text(c.contacts) + " contacts with " + count_text(c.contact_candidates) + " candidate elements",
                c.contacts * (contact_fixed + contact_per_iterate * (c.max_iterations + 1.0)) +
                    contact_per_candidate * c.contact_candidates + place_per_candidate * places +
                    c.candidate_tables * table_per_element * c.elements + table_per_candidate * c.table_candidates +
                    c.contact_spec_bytes + contact_solver_bytes(c) +
                    (c.contacts > 0.0 ? contacts_per_element * c.elements + contacts_per_node * c.nodes : 0.0)};
  e.kept_states = {"the state of " + count_text(c.kept_states) + (c.kept_states == 1.0 ? " step" : " steps"),
                   c.kept_states * (state_per_node * c.nodes + state_per_element * c.elements)};
  e.steps = {count_text(c.steps) + " steps' records",
             c.steps * (per_step + step_per_monitored * c.monitored + step_per_moved * c.moved_dofs + step_per_contact * c.contacts)};
  return e;
}

double planned_steps(const Control& control) {
  if (control.type == ControlType::arc_length) return control.max_steps;
  const double legs = control.path.empty() ? 1.0 : static_cast<double>(control.path.size());
  return static_cast<double>(control.steps) * legs;
}

double kept_state_count(const OutputSelection& output, double steps) {
  switch (output.kind) {
    case OutputSelection::Kind::last: return 1.0;
    case OutputSelection::Kind::every: return std::min(steps, std::ceil(steps / output.every) + 1.0);
    case OutputSelection::Kind::all: return std::max(steps, 1.0);
  }
  return steps;
}

std::vector<long> member_element_counts(const Model& model) {
  std::vector<long> counts(model.member_count, 0);
  for (const Element& e : model.elements) ++counts[e.member];
  return counts;
}

double candidate_count(const ContactSpec& spec, const std::vector<long>& per_member) {
  double n = 0.0;
  for (const int m : spec.members) n += static_cast<double>(per_member[m]);
  return n;
}

double contact_spec_bytes(const ContactSpec& spec) {
  return sizeof(ContactSpec) + 4.0 * static_cast<double>(spec.members.capacity()) +
         8.0 * static_cast<double>(spec.member_shear_flexibility.capacity());
}

ModelCounts model_counts(const Model& model, double input_bytes) {
  ModelCounts c;
  c.input_bytes = input_bytes;
  c.nodes = model.node_count();
  c.elements = static_cast<double>(model.elements.size());
  c.free_dofs = static_cast<double>(std::count(model.constrained.begin(), model.constrained.end(), false));
  c.contacts = static_cast<double>(model.contacts.size());
  const std::vector<long> per_member = member_element_counts(model);
  for (const ContactSpec& spec : model.contacts) {
    c.contact_candidates += candidate_count(spec, per_member);
    c.contact_spec_bytes += contact_spec_bytes(spec);
  }
  const CandidateGroups groups = candidate_groups(model.contacts);
  c.candidate_tables = static_cast<double>(groups.first.size());
  for (const int first : groups.first) c.table_candidates += candidate_count(model.contacts[first], per_member);
  c.max_iterations = model.analysis.max_iterations;
  c.steps = planned_steps(model.analysis.control);
  c.kept_states = kept_state_count(model.analysis.output, c.steps);
  if (!model.stages.empty()) c.steps = c.kept_states = 0.0;  // every stage's, and a copy of the model per stage
  for (const Stage& stage : model.stages) {
    const double steps = planned_steps(stage.control);
    c.steps += steps;
    c.kept_states += kept_state_count(stage.output, steps);
  }
  c.monitored = static_cast<double>(model.analysis.monitor.size());
  c.moved_dofs = static_cast<double>(model.moved_dofs().size());
  return c;
}

}  // namespace tsm
