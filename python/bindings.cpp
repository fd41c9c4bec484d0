// The Python extension `tsmframe._core`: its module body. Each concern's functions are defined
// in src/ (src/bindings.hpp).
#include "src/bindings.hpp"
#include "tsmframe/version.hpp"

PYBIND11_MODULE(_core, module) {
  module.doc() = "tsmframe's solver (thin bindings; use the tsmframe package)";
  module.attr("__version__") = tsm::version;
  tsm::python::define_errors(module);
  tsm::python::define_model(module);
  tsm::python::define_curves(module);
  tsm::python::define_run(module);
  tsm::python::define_study(module);
}
