// Studies: a tsmframe-study/1 document's cases run in parallel, study.json's text back — the
// same reader, parser and writer as `tsmframe study`, so the same messages and the same rows.
#include <sstream>
#include <vector>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/study/study_journal.hpp"
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

/// The rows of shard `shard_index` of `shard_count` of the study's cases (all: 0 of 1); with
/// study.keep and a `keep_directory`, the cases' results under it (cases/<case>/).
std::vector<study::CaseResult> shard_rows(const study::Study& definition, int jobs, size_t shard_index, size_t shard_count,
                                          const std::string& keep_directory = "") {
  if (shard_count < 1 || shard_index >= shard_count) throw py::value_error("shard: expected 0 <= index < count");
  std::vector<study::CaseResult> rows;
  run_interruptible([&](const solver::StopRequest* stop) {
    rows = study::run_study(definition, jobs, keep_directory, {}, stop, {}, study::StudyShard{shard_index, shard_count});
  });
  return rows;
}

std::string study_json(const std::string& text, const std::string& directory, int jobs, size_t shard_index, size_t shard_count) {
  const study::Study definition = read_study(text, directory);
  const std::vector<study::CaseResult> rows = shard_rows(definition, jobs, shard_index, shard_count);
  std::ostringstream out;  // the CLI's study.json
  study::write_study_json(out, definition, rows);
  return out.str();
}

}  // namespace

void define_study(py::module_& module) {
  module.def("study_json", &study_json, py::arg("text"), py::arg("directory") = ".", py::arg("jobs") = 0,
             py::arg("shard_index") = 0, py::arg("shard_count") = 1,
             "Run a study given as tsmframe-study/1 JSON text (model_file relative to `directory`), the cases in "
             "parallel on `jobs` threads (0: all cores) — those of shard `shard_index` of `shard_count` (case k from 0 "
             "where k mod count = index); returns the text of the CLI's study.json. "
             "Raises ValueError (JSON path: reason) for a bad study file.");
  module.def("study_rows_jsonl",
             [](const std::string& text, const std::string& directory, int jobs, size_t shard_index, size_t shard_count,
                const std::string& keep_directory) {
               return study::journal_lines(shard_rows(read_study(text, directory), jobs, shard_index, shard_count, keep_directory));
             },
             py::arg("text"), py::arg("directory") = ".", py::arg("jobs") = 1, py::arg("shard_index") = 0, py::arg("shard_count") = 1,
             py::arg("keep_directory") = "",
             "As study_json, the rows as the lines of the study's journal (study.rows.jsonl; stopped cases left out); "
             "where the study keeps cases (\"keep\": true), their results.json and steps.csv under "
             "`keep_directory`/cases/<case>/.");
  module.def("study_cases", [](const std::string& text, const std::string& directory) { return read_study(text, directory).case_count(); },
             py::arg("text"), py::arg("directory") = ".",
             "The number of cases of a study (tsmframe-study/1 JSON text); ValueError (JSON path: reason) for a bad one.");
}

}  // namespace tsm::python
