// Studies: a tsmframe-study/1 document's cases run in parallel, study.json's text back — the
// same reader, parser and writer as `tsmframe study`, so the same messages and the same rows.
#include <sstream>
#include <vector>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/study/study_runner.hpp"
#include "tsmframe/study/study_writer.hpp"
#include "src/bindings.hpp"
#include "src/interruptible.hpp"

namespace tsm::python {
namespace {

/// The study in `text` (model_file relative to `directory`); ValueError (JSON path: reason).
study::Study read_study(const std::string& text, const std::string& directory) {
  study::Study definition;
  try {
    definition = study::read_study(io::parse_json(text), directory);
  } catch (const io::InputError& e) {
    throw py::value_error(e.what());  // the CLI's "JSON.path: reason"
  }
  if (const std::optional<std::string> invalid = study::invalid_in_every_case(definition)) throw py::value_error(*invalid);
  return definition;
}

std::string study_json(const std::string& text, const std::string& directory, int jobs) {
  const study::Study definition = read_study(text, directory);
  std::vector<study::CaseResult> rows;
  run_interruptible([&](const solver::StopRequest* stop) { rows = study::run_study(definition, jobs, "", {}, stop); });
  std::ostringstream out;  // the CLI's study.json
  study::write_study_json(out, definition, rows);
  return out.str();
}

}  // namespace

void define_study(py::module_& module) {
  module.def("study_json", &study_json, py::arg("text"), py::arg("directory") = ".", py::arg("jobs") = 0,
             "Run a study given as tsmframe-study/1 JSON text (model_file relative to `directory`), the cases in "
             "parallel on `jobs` threads (0: all cores); returns the text of the CLI's study.json. "
             "Raises ValueError (JSON path: reason) for a bad study file.");
}

}  // namespace tsm::python
