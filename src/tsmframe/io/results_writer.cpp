#include "tsmframe/io/results_writer.hpp"

#include <array>
#include <filesystem>

#include "tsmframe/io/element_curves.hpp"
#include "tsmframe/io/friction_names.hpp"
#include "tsmframe/io/section_diagrams.hpp"
#include "tsmframe/io/json_writer.hpp"
#include "tsmframe/io/mesh_json.hpp"
#include "tsmframe/io/model_drawing.hpp"
#include "tsmframe/io/output_file.hpp"
#include "tsmframe/model/hinges.hpp"
#include "tsmframe/version.hpp"

namespace tsm::io {
namespace {

void write_triples(JsonWriter& w, const Model& model, const Eigen::VectorXd& values, const std::vector<bool>* only) {
  w.begin_object();
  for (int k = 0; k < model.node_count(); ++k) {
    if (only && !(*only)[k]) continue;
    w.newline().key(std::to_string(model.nodes[k].id)).begin_array();
    for (int dof = 0; dof < dofs_per_node; ++dof) w.value(values[dofs_per_node * k + dof]);
    w.end_array();
  }
  w.end_object();
}

/// "curves": element id → the element's deflected curve, [x0, y0, …] (README "The output files").
void write_curves(JsonWriter& w, const Model& model, const solver::StepRecord& step) {
  std::array<Eigen::Vector2d, curve_segments + 1> points;
  w.key("curves").begin_object();
  for (size_t e = 0; e < model.elements.size(); ++e) {
    element_curve(model, model.elements[e], step.displacements, step.element_forces.segment<3>(3 * e), points);
    w.newline().key(std::to_string(model.elements[e].id)).begin_array();
    for (const Eigen::Vector2d& p : points) w.value(p.x()).value(p.y());
    w.end_array();
  }
  w.end_object();
}

/// "section_forces": element id → its N, V, M diagram's stations (io/section_diagrams), each
/// [x, N, V, M] with x from the element's start node along its chord.
void write_section_forces(JsonWriter& w, const Model& model, const solver::StepRecord& step) {
  const std::vector<std::vector<element::SectionStation>> diagrams = section_diagrams(model, step);
  w.key("section_forces").begin_object();
  for (size_t e = 0; e < model.elements.size(); ++e) {
    w.newline().key(std::to_string(model.elements[e].id)).begin_array();
    for (const element::SectionStation& s : diagrams[e])
      w.begin_array().value(s.x).value(s.N).value(s.V).value(s.M).end_array();
    w.end_array();
  }
  w.end_object();
}

/// What a run restarted from this step needs beside its displacements (restart_reader.hpp).
void write_restart_state(JsonWriter& w, const Model& model, const solver::StepRecord& step) {
  w.key("state").begin_object();
  w.key("path_parameter").value(step.path_parameter);
  w.key("chord_rotations").begin_array();
  for (const double beta : step.chord_rotations) w.value(beta);
  w.end_array();
  w.key("contacts").begin_array();
  for (const contact::ContactState& c : step.contact_states) {
    w.newline().begin_object().key("active").value(c.active);
    if (c.active) {
      w.key("element").value(model.elements[c.element].id).key("side").value(c.side).key("alpha").value(c.alpha);
      w.key("force").value(c.force).key("Y").value(c.Y).key("entering").value(c.entering);
      w.key("push").begin_array().value(c.push[0]).value(c.push[1]).end_array();
      if (c.vertex) {
        w.key("vertex").begin_object().key("element").value(model.elements[c.vertex->element].id);
        w.key("side").value(c.vertex->side).key("Y").value(c.vertex->Y).end_object();
      }
      if (const contact::FrictionState& f = c.friction; f.status != contact::FrictionStatus::none) {
        w.key("friction").begin_object().key("anchored").value(f.anchored);
        if (f.anchored) w.key("member").value(f.member).key("anchor").value(f.anchor);
        w.key("slip").value(f.slip).key("status").value(std::string(friction_name(f.step_status)));
        w.key("tangential").value(f.step_tangential).end_object();
      }
    }
    w.end_object();
  }
  w.end_array();
  if (const solver::ArcLengthMemory& arc = step.arc_memory; arc.next_arc > 0.0) {
    w.key("arc_length").begin_object().key("next_arc").value(arc.next_arc).key("steps").value(arc.converged_steps);
    w.key("previous_load_increment").value(arc.previous_load_increment);
    if (arc.previous_increment.size() > 0) {
      w.key("previous_increment");
      write_triples(w, model, arc.previous_increment, nullptr);
    }
    w.end_object();
  }
  if (!model.stages.empty()) {
    w.key("stage_load_factors").begin_array();
    for (const double lambda : step.stage_load_factors) w.value(lambda);
    w.end_array();
  }
  if (!step.stage_start.empty()) {
    w.key("stage_start").begin_array();
    for (const auto& [dof, value] : step.stage_start)
      w.begin_array().value(model.nodes[dof / dofs_per_node].id).value(dof_name(dof % dofs_per_node)).value(value).end_array();
    w.end_array();
  }
  w.end_object();
}

void write_step(JsonWriter& w, const Model& model, const solver::StepRecord& step, const std::vector<bool>& supported,
                const ResultsOptions& options) {
  w.newline().begin_object();
  w.key("step").value(step.step);
  if (!model.stages.empty()) w.key("stage").value(step.stage + 1);
  w.key("load_factor").value(step.load_factor);
  w.key("converged").value(step.converged);
  w.key("iterations").value(step.iterations);
  w.key("residual_norms").begin_array();
  for (double r : step.residual_norms) w.value(r);
  w.end_array();
  if (step.converged) w.key("criterion").value(solver::criterion_name(step.criterion));
  w.key("increment").value(step.increment);
  if (step.arc_length > 0.0) w.key("arc_length").value(step.arc_length);
  w.key("cutbacks").value(step.cutbacks);
  if (step.converged && step.negative_eigenvalues >= 0) w.key("negative_eigenvalues").value(step.negative_eigenvalues);
  if (!step.converged) w.key("message").value(step.message);
  if (step.has_state) {
    w.key("displacements");
    write_triples(w, model, step.displacements, nullptr);
    // A contact element adds Y to its element's (N, M_i, M_j).
    std::vector<const double*> contact_Y(model.elements.size(), nullptr);
    for (const solver::ContactPoint& c : step.contacts) {
      if (c.element >= 0) contact_Y[c.element] = &c.Y;
      if (c.partner >= 0) contact_Y[c.partner] = &c.partner_Y;
    }
    w.key("element_forces").begin_object();
    for (size_t e = 0; e < model.elements.size(); ++e) {
      w.newline().key(std::to_string(model.elements[e].id)).begin_array();
      for (int f = 0; f < 3; ++f) w.value(step.element_forces[3 * e + f]);
      if (contact_Y[e]) w.value(*contact_Y[e]);
      w.end_array();
    }
    w.end_object();
    write_section_forces(w, model, step);
    w.key("reactions");
    write_triples(w, model, step.reactions, &supported);
    if (options.curves) write_curves(w, model, step);
    if (step.converged) write_restart_state(w, model, step);
  }
  if (step.converged) {
    // Every active contact, on every converged step (also those without full state).
    w.key("contacts").begin_array();
    for (size_t k = 0; k < step.contacts.size(); ++k) {
      const solver::ContactPoint& c = step.contacts[k];
      if (c.element < 0) continue;
      w.newline().begin_object();
      w.key("node").value(model.nodes[model.contacts[k].node].id);
      w.key("element").value(model.elements[c.element].id);
      w.key("xi").value(c.alpha);
      w.key("force").value(c.force);
      if (c.partner >= 0) w.key("also").value(model.elements[c.partner].id);
      if (c.friction != contact::FrictionStatus::none)
        w.key("friction").value(std::string(friction_name(c.friction))).key("tangential").value(c.tangential).key("slip").value(c.slip);
      w.end_object();
    }
    w.end_array();
  }
  w.end_object();
}

}  // namespace

void write_results_json(std::ostream& out, const Model& model, const solver::RunResult& result,
                        const ResultsOptions& options) {
  // Nodes with a support or a prescribed dof (any stage's: the run reports their reactions); a
  // hinge's rotation, fixed by the reader, is neither.
  std::vector<bool> supported(model.node_count(), false);
  const std::vector<char> hinge = hinge_nodes(model);
  for (int dof = 0; dof < model.dof_count(); ++dof)
    if (model.constrained[dof] && !(dof % dofs_per_node == rz && hinge[dof / dofs_per_node])) supported[dof / dofs_per_node] = true;
  for (const int dof : model.moved_dofs()) supported[dof / dofs_per_node] = true;

  JsonWriter w(out);
  w.begin_object();
  w.key("format").value("tsmframe-results/1");
  w.key("program").value(std::string("tsmframe ") + version);
  w.key("title").value(model.title);
  w.key("units").begin_object();
  for (const auto& [name, unit] : model.units) w.key(name).value(unit);
  w.end_object();
  w.key("status").value(solver::status_name(result.status));
  w.key("message").value(result.message);
  write_mesh(w, model);
  write_model_symbols(w, model);  // what the pictures draw the model with
  w.newline().key("steps").begin_array();
  for (const solver::StepRecord& step : result.steps) write_step(w, model, step, supported, options);
  w.end_array();
  // Converged steps where λ peaks or dips along the path (limit points, with arc-length control).
  w.newline().key("limit_points").begin_array();
  for (const solver::LimitPoint& p : result.limit_points) {
    w.newline().begin_object();
    w.key("step").value(p.step).key("kind").value(p.maximum ? "maximum" : "minimum").key("load_factor").value(p.load_factor);
    if (p.refined) {  // located between the steps (solver/limit_point)
      const solver::RefinedLimit& r = *p.refined;
      w.key("located").begin_object().key("load_factor").value(r.load_factor);
      w.key("node").value(model.nodes[r.dof / dofs_per_node].id).key("dof").value(dof_name(r.dof % dofs_per_node));
      w.key("value").value(r.value).key("evaluations").value(r.evaluations).end_object();
    }
    if (p.contact_kink) w.key("contact_kink").value(true);
    w.end_object();
  }
  w.end_array();
  // Bifurcations of the primary path under load control, by bisection on the tangent's inertia.
  w.newline().key("critical_points").begin_array();
  for (const solver::CriticalPoint& c : result.critical_points) {
    w.newline().begin_object();
    w.key("step").value(c.step).key("load_factor").value(c.load_factor);
    w.key("bracket").begin_array().value(c.stable).value(c.unstable).end_array();
    w.end_object();
  }
  w.end_array();
  // Linearised buckling (analysis.buckling): each mode's λ and shape, and the converged step it
  // was estimated from where not the unloaded state.
  if (model.analysis.buckling_modes > 0) {
    if (result.buckling.step > 0)
      w.newline().key("buckling_from").begin_object().key("step").value(result.buckling.step).key("load_factor").value(result.buckling.base_load_factor).end_object();
    w.newline().key("buckling").begin_array();
    for (const solver::BucklingMode& mode : result.buckling.modes) {
      w.newline().begin_object().key("load_factor").value(mode.load_factor).key("shape");
      write_triples(w, model, mode.shape, nullptr);
      w.end_object();
    }
    w.end_array();
  }
  // Steps in neutral equilibrium: the rigid-body motion their supports leave free there.
  w.newline().key("neutral_equilibria").begin_array();
  for (const solver::NeutralStep& n : result.neutral_steps) {
    w.newline().begin_object();
    w.key("step").value(n.step).key("node").value(model.nodes[n.motion.node].id).key("part_nodes").value(n.motion.part_nodes);
    if (n.motion.kind == FreeMotion::Kind::rotation)
      w.key("motion").value("rotation").key("about").begin_array().value(n.motion.pole.x()).value(n.motion.pole.y()).end_array();
    else
      w.key("motion").value("translation").key("direction").begin_array().value(n.motion.direction.x()).value(n.motion.direction.y()).end_array();
    w.end_object();
  }
  w.end_array();
  // Steps whose stability round-off leaves unknown: the pivot whose sign is lost.
  w.newline().key("rounded_inertia").begin_array();
  for (const solver::RoundedStep& r : result.rounded_steps) {
    w.newline().begin_object().key("step").value(r.step).key("node").value(model.nodes[r.pivot.node].id);
    w.key("dof").value(dof_name(r.pivot.dof)).key("ratio").value(r.pivot.ratio).end_object();
  }
  w.end_array();
  if (!model.stages.empty()) {  // where each stage that ran ended
    w.newline().key("stages").begin_array();
    for (const solver::StageEnd& end : result.stages) {
      w.newline().begin_object();
      w.key("stage").value(end.stage + 1).key("name").value(model.stages[end.stage].name);
      w.key("status").value(solver::status_name(end.status)).key("last_step").value(end.last_step);
      w.key("load_factor").value(end.load_factor);
      w.end_object();
    }
    w.end_array();
  }
  // Remarks on the path (a jump across a snap-back under displacement control); usually none.
  w.newline().key("notes").begin_array();
  for (const std::string& note : result.notes) w.value(note);
  w.end_array();
  w.newline().end_object();
  out << '\n';
}

void write_steps_csv(std::ostream& out, const Model& model, const solver::RunResult& result) {
  const bool staged = !model.stages.empty();
  out << (staged ? "step,stage,load_factor,iterations" : "step,load_factor,iterations");
  for (int node : model.analysis.monitor) {
    const std::string id = std::to_string(model.nodes[node].id);
    out << ",ux_" << id << ",uy_" << id << ",rz_" << id;
  }
  for (const ContactSpec& c : model.contacts) {
    const std::string id = std::to_string(model.nodes[c.node].id);
    out << ",contact_element_" << id << ",contact_xi_" << id << ",contact_force_" << id;
  }
  // The reactions where a prescribed displacement moves a dof: a displacement-driven model's force.
  const std::vector<int> moved = model.moved_dofs();
  for (const int d : moved) out << ',' << (d % dofs_per_node == 0 ? "Rx_" : d % dofs_per_node == 1 ? "Ry_" : "Mz_") << model.nodes[d / dofs_per_node].id;
  out << '\n';
  for (const solver::StepRecord& step : result.steps) {
    if (!step.converged) continue;
    out << step.step << ',';
    if (staged) out << step.stage + 1 << ',';
    out << format_number(step.load_factor) << ',' << step.iterations;
    for (Eigen::Index k = 0; k < step.monitored.size(); ++k) out << ',' << format_number(step.monitored[k]);
    // Not in contact: element and xi left empty, force 0.
    for (const solver::ContactPoint& c : step.contacts) {
      if (c.element >= 0)
        out << ',' << model.elements[c.element].id << ',' << format_number(c.alpha) << ',' << format_number(c.force);
      else
        out << ",,,0";
    }
    for (Eigen::Index k = 0; k < step.moved_reactions.size(); ++k) out << ',' << format_number(step.moved_reactions[k]);
    out << '\n';
  }
}

void write_results(const std::string& directory, const Model& model, const solver::RunResult& result,
                   const ResultsOptions& options) {
  make_directories(directory);
  const std::filesystem::path dir(directory);
  write_output_file((dir / "results.json").string(), [&](std::ostream& out) { write_results_json(out, model, result, options); });
  write_output_file((dir / "steps.csv").string(), [&](std::ostream& out) { write_steps_csv(out, model, result); });
}

}  // namespace tsm::io
