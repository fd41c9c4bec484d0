// What the system could not give a run, as Python's own exceptions: the memory the machine lacks
// (io::MemoryShortage, the CLI's exit 3) is a MemoryError, any other io::SystemError (a file that
// cannot be written, with the OS's reason) an OSError. Bad input stays a ValueError (model.cpp).
#include "tsmframe/io/system_error.hpp"
#include "src/bindings.hpp"

namespace tsm::python {

void define_errors(py::module_&) {
  py::register_exception_translator([](std::exception_ptr raised) {
    try {
      if (raised) std::rethrow_exception(raised);
    } catch (const io::MemoryShortage& e) {
      PyErr_SetString(PyExc_MemoryError, e.what());
    } catch (const io::SystemError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
}

}  // namespace tsm::python
