#include "src/results.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <sstream>
#include <string>
#include <vector>

#include "tsmframe/io/friction_names.hpp"
#include "tsmframe/io/results_writer.hpp"
#include "tsmframe/io/section_diagrams.hpp"
#include "src/bindings.hpp"

namespace tsm::python {
namespace {

template <typename T>
py::array_t<T> array(std::vector<py::ssize_t> shape, const std::vector<T>& data) {
  py::array_t<T> a(shape);
  std::copy(data.begin(), data.end(), a.mutable_data());
  return a;
}

py::ssize_t count(size_t n) { return static_cast<py::ssize_t>(n); }

/// status, message, notes, the bifurcations found under load control ({step, load_factor, bracket})
/// and the steps in neutral equilibrium ({step, node, part_nodes, motion, about or direction}).
void add_outcome(py::dict& out, const Model& model, const solver::RunResult& result) {
  out["status"] = solver::status_name(result.status);
  out["message"] = result.message;
  out["notes"] = result.notes;
  py::list critical;
  for (const solver::CriticalPoint& c : result.critical_points) {
    py::dict point;
    point["step"] = c.step;
    point["load_factor"] = c.load_factor;
    point["bracket"] = py::make_tuple(c.stable, c.unstable);
    critical.append(point);
  }
  out["critical_points"] = critical;
  py::list limits;  // λ's extrema along the path, located where the stepping could
  for (const solver::LimitPoint& p : result.limit_points) {
    py::dict point;
    point["step"] = p.step;
    point["kind"] = p.maximum ? "maximum" : "minimum";
    point["load_factor"] = p.load_factor;
    if (p.refined) {
      py::dict located;
      located["load_factor"] = p.refined->load_factor;
      located["node"] = model.nodes[p.refined->dof / dofs_per_node].id;
      located["dof"] = dof_name(p.refined->dof % dofs_per_node);
      located["value"] = p.refined->value;
      located["evaluations"] = p.refined->evaluations;
      point["located"] = located;
    }
    if (p.contact_kink) point["contact_kink"] = true;
    limits.append(point);
  }
  out["limit_points"] = limits;
  py::list neutral;  // steps in neutral equilibrium: the motion the supports leave free there
  for (const solver::NeutralStep& n : result.neutral_steps) {
    py::dict step;
    step["step"] = n.step;
    step["node"] = model.nodes[n.motion.node].id;
    step["part_nodes"] = n.motion.part_nodes;
    if (n.motion.kind == FreeMotion::Kind::rotation) {
      step["motion"] = "rotation";
      step["about"] = py::make_tuple(n.motion.pole.x(), n.motion.pole.y());
    } else {
      step["motion"] = "translation";
      step["direction"] = py::make_tuple(n.motion.direction.x(), n.motion.direction.y());
    }
    neutral.append(step);
  }
  out["neutral_equilibria"] = neutral;
  py::list rounded;  // steps whose stability round-off leaves unknown: the pivot whose sign is lost
  for (const solver::RoundedStep& r : result.rounded_steps)
    rounded.append(py::dict(py::arg("step") = r.step, py::arg("node") = model.nodes[r.pivot.node].id,
                            py::arg("dof") = dof_name(r.pivot.dof), py::arg("ratio") = r.pivot.ratio));
  out["rounded_inertia"] = rounded;
  std::vector<double> factors, shapes;  // linearised buckling at the unloaded state (analysis.buckling)
  for (const solver::BucklingMode& mode : result.buckling.modes) {
    factors.push_back(mode.load_factor);
    shapes.insert(shapes.end(), mode.shape.data(), mode.shape.data() + mode.shape.size());
  }
  out["buckling_load_factors"] = array<double>({count(factors.size())}, factors);
  out["buckling_modes"] = array<double>({count(factors.size()), model.node_count(), 3}, shapes);
  out["buckling_step"] = result.buckling.step;  // 0: at the unloaded state
  py::list stages;  // a staged run's stages that ran: where each ended
  for (const solver::StageEnd& end : result.stages) {
    py::dict stage;
    stage["stage"] = end.stage + 1;
    stage["name"] = model.stages[end.stage].name;
    stage["status"] = solver::status_name(end.status);
    stage["last_step"] = end.last_step;
    stage["load_factor"] = end.load_factor;
    stages.append(stage);
  }
  out["stages"] = stages;
}

/// The meshed model: node ids and coordinates, element ids, end node ids, members and kinds, contact node ids.
void add_model(py::dict& out, const Model& model) {
  std::vector<int> node_ids, element_ids, element_nodes, element_members, contact_nodes;
  std::vector<double> node_xy;
  std::vector<std::string> element_kinds;
  for (const Node& node : model.nodes) {
    node_ids.push_back(node.id);
    node_xy.insert(node_xy.end(), {node.position.x(), node.position.y()});
  }
  for (const Element& e : model.elements) {
    element_ids.push_back(e.id);
    element_nodes.insert(element_nodes.end(), {model.nodes[e.start].id, model.nodes[e.end].id});
    element_members.push_back(e.member);
    element_kinds.push_back(theory_name(e.theory));
  }
  for (const ContactSpec& spec : model.contacts) contact_nodes.push_back(model.nodes[spec.node].id);
  const py::ssize_t n = model.node_count(), m = count(model.elements.size());
  out["node_ids"] = array<int>({n}, node_ids);
  out["node_xy"] = array<double>({n, 2}, node_xy);
  out["element_ids"] = array<int>({m}, element_ids);
  out["element_nodes"] = array<int>({m, 2}, element_nodes);
  out["element_members"] = array<int>({m}, element_members);
  out["element_kinds"] = element_kinds;
  out["contact_nodes"] = array<int>({count(contact_nodes.size())}, contact_nodes);
}

/// Every step (converged or the failed last attempt): step number, λ, iterations, whether it
/// converged, negative eigenvalues (−1 unknown), residuals per iterate, criterion.
void add_steps(py::dict& out, const solver::RunResult& result) {
  std::vector<int> steps, stages, iterations, converged, negative_eigenvalues;
  std::vector<double> load_factors;
  py::list residuals, criteria;
  for (const solver::StepRecord& s : result.steps) {
    steps.push_back(s.step);
    stages.push_back(s.stage + 1);
    load_factors.push_back(s.load_factor);
    iterations.push_back(s.iterations);
    converged.push_back(s.converged ? 1 : 0);
    negative_eigenvalues.push_back(s.converged ? s.negative_eigenvalues : -1);
    residuals.append(array<double>({count(s.residual_norms.size())}, s.residual_norms));
    criteria.append(solver::criterion_name(s.criterion));
  }
  const py::ssize_t S = count(result.steps.size());
  out["step"] = array<int>({S}, steps);
  out["stage"] = array<int>({S}, stages);
  out["load_factor"] = array<double>({S}, load_factors);
  out["iterations"] = array<int>({S}, iterations);
  out["converged"] = array<int>({S}, converged);
  out["negative_eigenvalues"] = array<int>({S}, negative_eigenvalues);
  out["residual_norms"] = residuals;
  out["criterion"] = criteria;
}

/// The steps with state: their numbers, displacements, element forces, N/V/M stations and reactions.
void add_states(py::dict& out, const Model& model, const solver::RunResult& result) {
  const py::ssize_t n = model.node_count(), m = count(model.elements.size());
  std::vector<int> state_steps;
  std::vector<double> displacements, forces, reactions;
  for (const solver::StepRecord& s : result.steps) {
    if (!s.has_state) continue;
    state_steps.push_back(s.step);
    displacements.insert(displacements.end(), s.displacements.data(), s.displacements.data() + 3 * n);
    forces.insert(forces.end(), s.element_forces.data(), s.element_forces.data() + 3 * m);
    reactions.insert(reactions.end(), s.reactions.data(), s.reactions.data() + 3 * n);
  }
  const py::ssize_t K = count(state_steps.size());
  py::list sections;  // per state: the N, V, M stations (io/section_diagrams), rows (element id, x, N, V, M)
  for (const solver::StepRecord& s : result.steps) {
    if (!s.has_state) continue;
    std::vector<double> rows;
    const auto diagrams = io::section_diagrams(model, s);
    for (size_t e = 0; e < diagrams.size(); ++e)
      for (const element::SectionStation& station : diagrams[e])
        rows.insert(rows.end(), {static_cast<double>(model.elements[e].id), station.x, station.N, station.V, station.M});
    sections.append(array<double>({count(rows.size() / 5), 5}, rows));
  }
  out["section_forces"] = sections;
  out["state_steps"] = array<int>({K}, state_steps);
  out["displacements"] = array<double>({K, n, 3}, displacements);
  out["element_forces"] = array<double>({K, m, 3}, forces);
  out["reactions"] = array<double>({K, n, 3}, reactions);
}

/// Per converged step and contact: element id (0: none), the vertex's other element id, α, force,
/// and friction's force along the beam, slip so far and status ("" without friction).
void add_contacts(py::dict& out, const Model& model, const solver::RunResult& result) {
  const py::ssize_t c = count(model.contacts.size());
  std::vector<int> element, also;
  std::vector<double> alpha, force, tangential, slip;
  py::list status;
  py::ssize_t C = 0;  // converged steps, where the model has contacts (else no rows)
  for (const solver::StepRecord& s : result.steps) {
    if (!s.converged || c == 0) continue;
    ++C;
    for (py::ssize_t k = 0; k < c; ++k) {
      const solver::ContactPoint& p = s.contacts[k];
      element.push_back(p.element >= 0 ? model.elements[p.element].id : 0);
      also.push_back(p.partner >= 0 ? model.elements[p.partner].id : 0);
      alpha.push_back(p.element >= 0 ? p.alpha : 0.0);
      force.push_back(p.element >= 0 ? p.force : 0.0);
      const bool frictional = p.element >= 0 && p.friction != contact::FrictionStatus::none;
      tangential.push_back(frictional ? p.tangential : 0.0);
      slip.push_back(frictional ? p.slip : 0.0);
      status.append(frictional ? std::string(io::friction_name(p.friction)) : std::string());
    }
  }
  out["contact_element"] = array<int>({C, c}, element);
  out["contact_also"] = array<int>({C, c}, also);
  out["contact_alpha"] = array<double>({C, c}, alpha);
  out["contact_force"] = array<double>({C, c}, force);
  out["contact_tangential"] = array<double>({C, c}, tangential);
  out["contact_slip"] = array<double>({C, c}, slip);
  out["contact_friction"] = py::module_::import("numpy").attr("array")(status, "U5").attr("reshape")(C, c);
}

/// What `tsmframe run` writes: results.json and steps.csv.
void add_texts(py::dict& out, const Model& model, const solver::RunResult& result) {
  std::ostringstream json, csv;
  io::write_results_json(json, model, result);
  io::write_steps_csv(csv, model, result);
  out["results_json"] = json.str();
  out["steps_csv"] = csv.str();
}

}  // namespace

py::dict results_dict(const std::shared_ptr<Model>& model, const solver::RunResult& result) {
  py::dict out;
  out["model"] = model;
  add_outcome(out, *model, result);
  add_model(out, *model);
  add_steps(out, result);
  add_states(out, *model, result);
  add_contacts(out, *model, result);
  add_texts(out, *model, result);
  return out;
}

}  // namespace tsm::python
