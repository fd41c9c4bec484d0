// Model reading: a model from its docs/format.md JSON text, read and meshed — what run_json runs and
// what a Result unpickled needs for its curves.
#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/model_drawing.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/solver/unloaded_mechanism.hpp"
#include "src/bindings.hpp"

namespace tsm::python {

std::shared_ptr<Model> read_model(const std::string& text) {
  try {
    return std::make_shared<Model>(io::read_model_text(text));
  } catch (const io::InputError& e) {
    throw py::value_error(e.what());  // the CLI's "JSON.path: reason"
  }
}

/// The model's drawing document (io/model_drawing.hpp): a model that is a mechanism is read and
/// drawn too, the free motion named in the document.
std::string model_drawing(const std::string& text) {
  try {
    Model model = io::read_model_text(text, io::Mechanisms::allow);
    const std::optional<solver::Mechanism> mechanism = solver::drawn_mechanism(model);
    return io::model_drawing(model, mechanism ? std::optional<std::string>(mechanism->text) : std::nullopt);
  } catch (const io::InputError& e) {
    throw py::value_error(e.what());
  }
}

void define_model(py::module_& module) {
  py::class_<Model, std::shared_ptr<Model>>(module, "MeshedModel", "A model as read and meshed (opaque): what element_curves draws");
  module.def("read_model", &read_model, py::arg("text"), "Read and mesh a model given as docs/format.md JSON text (ValueError for bad input).");
  module.def("model_drawing", &model_drawing, py::arg("text"),
             "The drawing document (tsmframe-drawing/1) of a model given as docs/format.md JSON text (ValueError for bad input).");
}

}  // namespace tsm::python
