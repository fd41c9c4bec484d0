#pragma once
// The extension `tsmframe._core`, one part per concern, each adding its functions to the module
// through a define_*() that bindings.cpp's module body calls. Thin: JSON text in, numpy arrays
// and text out; no mechanics here (the friendly API is tsmframe/__init__.py).

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "tsmframe/model/model.hpp"

namespace tsm::python {

namespace py = pybind11;

/// MemoryError and OSError for what the system could not give a run (errors.cpp).
void define_errors(py::module_& module);
/// MeshedModel and read_model: a model from its docs/format.md JSON text (model.cpp).
void define_model(py::module_& module);
/// run_json: a model run, its results as numpy arrays and the CLI's texts (run.cpp, results.cpp).
void define_run(py::module_& module);
/// element_curves: every element's deflected curve at one state (curves.cpp).
void define_curves(py::module_& module);
/// study_json: a parameter study's cases run, study.json's text back (study.cpp).
void define_study(py::module_& module);

/// A model read and meshed from its docs/format.md JSON text; ValueError ("JSON.path: reason", the
/// CLI's words) for bad input.
std::shared_ptr<Model> read_model(const std::string& text);

}  // namespace tsm::python
