// Curves: every element's deflected curve (io/element_curves) at one state, for plots.
#include <pybind11/numpy.h>

#include <Eigen/Core>
#include <vector>

#include "tsmframe/io/element_curves.hpp"
#include "src/bindings.hpp"

namespace tsm::python {
namespace {

using Values = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// (elements, segments + 1, 2): the current coordinates along each element's curve.
py::array_t<double> element_curves(const Model& model, Values displacements, Values element_forces, int segments) {
  const py::ssize_t n = model.node_count(), m = static_cast<py::ssize_t>(model.elements.size());
  if (displacements.size() != 3 * n || element_forces.size() != 3 * m)
    throw py::value_error("element_curves: displacements must hold (nodes, 3) values and element_forces (elements, 3)");
  if (segments < 1) throw py::value_error("element_curves: segments must be at least 1");
  const Eigen::VectorXd state = Eigen::Map<const Eigen::VectorXd>(displacements.data(), 3 * n);
  const Eigen::Map<const Eigen::VectorXd> forces(element_forces.data(), 3 * m);
  py::array_t<double> out({m, static_cast<py::ssize_t>(segments + 1), py::ssize_t{2}});
  std::vector<Eigen::Vector2d> points(segments + 1);
  double* data = out.mutable_data();
  for (py::ssize_t e = 0; e < m; ++e) {
    io::element_curve(model, model.elements[e], state, forces.segment<3>(3 * e), points);
    for (const Eigen::Vector2d& p : points) {
      *data++ = p.x();
      *data++ = p.y();
    }
  }
  return out;
}

}  // namespace

void define_curves(py::module_& module) {
  module.def("element_curves", &element_curves, py::arg("model"), py::arg("displacements"), py::arg("element_forces"),
             py::arg("segments") = io::curve_segments,
             "Every element's deflected curve at one state (a step's displacements (n, 3) and element_forces (m, 3)), "
             "hinges and end springs included: an array (m, segments + 1, 2) of current coordinates.");
}

}  // namespace tsm::python
