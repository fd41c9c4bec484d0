// The Python extension `tsmframe._core`: thin — read a model (FORMAT.md JSON text), run it, and
// hand the results over as numpy arrays plus the same results.json text the CLI writes. No
// mechanics here; the friendly API lives in tsmframe/__init__.py.
#include <omp.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tsmframe/io/element_curves.hpp"
#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/io/results_writer.hpp"
#include "tsmframe/solver/analysis.hpp"
#include "tsmframe/study/study_runner.hpp"
#include "tsmframe/study/study_writer.hpp"
#include "tsmframe/version.hpp"

namespace py = pybind11;

namespace {

template <typename T>
py::array_t<T> array(std::vector<py::ssize_t> shape, const std::vector<T>& data) {
  py::array_t<T> a(shape);
  std::copy(data.begin(), data.end(), a.mutable_data());
  return a;
}

py::dict run_json(const std::string& text, int threads) {
  auto meshed = std::make_shared<tsm::Model>();  // kept by the Result for its curves
  tsm::Model& model = *meshed;
  try {
    model = tsm::io::read_model_text(text);
  } catch (const tsm::io::InputError& e) {
    throw py::value_error(e.what());  // the CLI's "JSON.path: reason"
  }
  tsm::solver::RunResult result;
  {
    py::gil_scoped_release release;
    const int callers = omp_get_max_threads();  // `threads` for this run only, not for the next
    if (threads > 0) omp_set_num_threads(threads);
    result = tsm::solver::run_analysis(model);
    omp_set_num_threads(callers);
  }
  const py::ssize_t n = model.node_count(), m = static_cast<py::ssize_t>(model.elements.size());
  const py::ssize_t c = static_cast<py::ssize_t>(model.contacts.size());
  py::dict out;
  out["model"] = meshed;
  out["status"] = tsm::solver::status_name(result.status);
  out["message"] = result.message;
  out["notes"] = result.notes;
  py::list critical;  // bifurcations under load control: {step, load_factor, bracket}
  for (const tsm::solver::CriticalPoint& c : result.critical_points) {
    py::dict point;
    point["step"] = c.step;
    point["load_factor"] = c.load_factor;
    point["bracket"] = py::make_tuple(c.stable, c.unstable);
    critical.append(point);
  }
  out["critical_points"] = critical;
  std::vector<int> node_ids, element_ids, element_nodes, element_members;
  std::vector<double> node_xy;
  std::vector<std::string> element_kinds;
  for (const tsm::Node& node : model.nodes) {
    node_ids.push_back(node.id);
    node_xy.push_back(node.position.x());
    node_xy.push_back(node.position.y());
  }
  for (const tsm::Element& e : model.elements) {
    element_ids.push_back(e.id);
    element_nodes.push_back(model.nodes[e.start].id);
    element_nodes.push_back(model.nodes[e.end].id);
    element_members.push_back(e.member);
    element_kinds.push_back(tsm::theory_name(e.theory));
  }
  out["node_ids"] = array<int>({n}, node_ids);
  out["node_xy"] = array<double>({n, 2}, node_xy);
  out["element_ids"] = array<int>({m}, element_ids);
  out["element_nodes"] = array<int>({m, 2}, element_nodes);
  out["element_members"] = array<int>({m}, element_members);
  out["element_kinds"] = element_kinds;
  std::vector<int> contact_nodes;
  for (const tsm::ContactSpec& spec : model.contacts) contact_nodes.push_back(model.nodes[spec.node].id);
  out["contact_nodes"] = array<int>({c}, contact_nodes);

  // Every step (converged or the failed last attempt): step number, λ, iterations, residuals.
  std::vector<int> step_numbers, iterations, converged, negative_eigenvalues;
  std::vector<double> load_factors;
  py::list residuals, criteria;
  // Converged steps: contacts; steps with state: displacements, element forces, reactions.
  std::vector<int> state_steps, contact_element, contact_also;
  std::vector<double> displacements, forces, reactions, contact_alpha, contact_force;
  for (const tsm::solver::StepRecord& s : result.steps) {
    step_numbers.push_back(s.step);
    load_factors.push_back(s.load_factor);
    iterations.push_back(s.iterations);
    converged.push_back(s.converged ? 1 : 0);
    negative_eigenvalues.push_back(s.converged ? s.negative_eigenvalues : -1);
    residuals.append(array<double>({static_cast<py::ssize_t>(s.residual_norms.size())}, s.residual_norms));
    criteria.append(tsm::solver::criterion_name(s.criterion));
    if (s.converged)
      for (py::ssize_t k = 0; k < c; ++k) {
        const tsm::solver::ContactPoint& p = s.contacts[k];
        contact_element.push_back(p.element >= 0 ? model.elements[p.element].id : 0);
        contact_also.push_back(p.partner >= 0 ? model.elements[p.partner].id : 0);
        contact_alpha.push_back(p.element >= 0 ? p.alpha : 0.0);
        contact_force.push_back(p.element >= 0 ? p.force : 0.0);
      }
    if (!s.has_state) continue;
    state_steps.push_back(s.step);
    displacements.insert(displacements.end(), s.displacements.data(), s.displacements.data() + 3 * n);
    forces.insert(forces.end(), s.element_forces.data(), s.element_forces.data() + 3 * m);
    reactions.insert(reactions.end(), s.reactions.data(), s.reactions.data() + 3 * n);
  }
  const py::ssize_t steps = static_cast<py::ssize_t>(result.steps.size());
  const py::ssize_t with_state = static_cast<py::ssize_t>(state_steps.size());
  const py::ssize_t converged_steps = static_cast<py::ssize_t>(contact_element.size() / std::max<py::ssize_t>(c, 1));
  out["step"] = array<int>({steps}, step_numbers);
  out["load_factor"] = array<double>({steps}, load_factors);
  out["iterations"] = array<int>({steps}, iterations);
  out["converged"] = array<int>({steps}, converged);
  out["negative_eigenvalues"] = array<int>({steps}, negative_eigenvalues);
  out["residual_norms"] = residuals;
  out["criterion"] = criteria;
  out["state_steps"] = array<int>({with_state}, state_steps);
  out["displacements"] = array<double>({with_state, n, 3}, displacements);
  out["element_forces"] = array<double>({with_state, m, 3}, forces);
  out["reactions"] = array<double>({with_state, n, 3}, reactions);
  out["contact_element"] = array<int>({c > 0 ? converged_steps : 0, c}, contact_element);
  out["contact_also"] = array<int>({c > 0 ? converged_steps : 0, c}, contact_also);
  out["contact_alpha"] = array<double>({c > 0 ? converged_steps : 0, c}, contact_alpha);
  out["contact_force"] = array<double>({c > 0 ? converged_steps : 0, c}, contact_force);
  std::ostringstream json, csv;
  tsm::io::write_results_json(json, model, result);
  tsm::io::write_steps_csv(csv, model, result);
  out["results_json"] = json.str();
  out["steps_csv"] = csv.str();
  return out;
}

/// A model from its FORMAT.md JSON text, read and meshed: what a Result unpickled needs for its curves.
std::shared_ptr<tsm::Model> read_model(const std::string& text) {
  try {
    return std::make_shared<tsm::Model>(tsm::io::read_model_text(text));
  } catch (const tsm::io::InputError& e) {
    throw py::value_error(e.what());
  }
}

/// Every element's deflected curve (io/element_curves) at one state: (elements, segments + 1, 2).
py::array_t<double> element_curves(const tsm::Model& model, py::array_t<double, py::array::c_style | py::array::forcecast> displacements,
                                   py::array_t<double, py::array::c_style | py::array::forcecast> element_forces, int segments) {
  const py::ssize_t n = model.node_count(), m = static_cast<py::ssize_t>(model.elements.size());
  if (displacements.size() != 3 * n || element_forces.size() != 3 * m)
    throw py::value_error("element_curves: displacements must hold (nodes, 3) values and element_forces (elements, 3)");
  if (segments < 1) throw py::value_error("element_curves: segments must be at least 1");
  const Eigen::Map<const Eigen::VectorXd> D(displacements.data(), 3 * n), forces(element_forces.data(), 3 * m);
  const Eigen::VectorXd state = D;
  py::array_t<double> out({m, static_cast<py::ssize_t>(segments + 1), py::ssize_t{2}});
  std::vector<Eigen::Vector2d> points(segments + 1);
  double* data = out.mutable_data();
  for (py::ssize_t e = 0; e < m; ++e) {
    tsm::io::element_curve(model, model.elements[e], state, forces.segment<3>(3 * e), points);
    for (const Eigen::Vector2d& p : points) {
      *data++ = p.x();
      *data++ = p.y();
    }
  }
  return out;
}

std::string study_json(const std::string& text, const std::string& directory, int jobs) {
  tsm::study::Study study;
  try {
    nlohmann::json document;
    try {
      document = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
      throw tsm::io::InputError("", std::string("invalid JSON: ") + e.what());
    }
    study = tsm::study::read_study(document, directory);
  } catch (const tsm::io::InputError& e) {
    throw py::value_error(e.what());  // the CLI's "JSON.path: reason"
  }
  std::vector<tsm::study::CaseResult> rows;
  {
    py::gil_scoped_release release;
    rows = tsm::study::run_study(study, jobs, "");
  }
  std::ostringstream out;  // the CLI's study.json
  tsm::study::write_study_json(out, study, rows);
  return out.str();
}

}  // namespace

PYBIND11_MODULE(_core, module) {
  module.doc() = "tsmframe's solver (thin bindings; use the tsmframe package)";
  module.attr("__version__") = tsm::version;
  py::class_<tsm::Model, std::shared_ptr<tsm::Model>>(module, "MeshedModel",
                                                      "A model as read and meshed (opaque): what element_curves draws");
  module.def("read_model", &read_model, py::arg("text"), "Read and mesh a model given as FORMAT.md JSON text (ValueError for bad input).");
  module.def("element_curves", &element_curves, py::arg("model"), py::arg("displacements"), py::arg("element_forces"),
             py::arg("segments") = tsm::io::curve_segments,
             "Every element's deflected curve at one state (a step's displacements (n, 3) and element_forces (m, 3)), "
             "hinges and end springs included: an array (m, segments + 1, 2) of current coordinates.");
  module.def("run_json", &run_json, py::arg("text"), py::arg("threads") = 0,
             "Run a model given as FORMAT.md JSON text; returns a dict of numpy arrays and the results.json text. "
             "Raises ValueError (JSON path: reason) for bad input.");
  module.def("study_json", &study_json, py::arg("text"), py::arg("directory") = ".", py::arg("jobs") = 0,
             "Run a study given as tsmframe-study/1 JSON text (model_file relative to `directory`), the cases in "
             "parallel on `jobs` threads (0: all cores); returns the text of the CLI's study.json. "
             "Raises ValueError (JSON path: reason) for a bad study file.");
}
