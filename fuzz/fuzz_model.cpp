// Fuzz target: a model file read (io/model_reader) and, where it is valid, a short analysis of it
// (harness_bounds.hpp) and its results serialised (results.json, steps.csv, with the elements'
// curves). Bad input must end as io::InputError (or io::SystemError); non-convergence as a
// status; anything else escaping — another exception, a sanitizer report, a hang — is a finding.

#include <omp.h>

#include <cstdint>
#include <sstream>
#include <string>

#include "harness_bounds.hpp"
#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/io/results_writer.hpp"
#include "tsmframe/io/system_error.hpp"
#include "tsmframe/solver/analysis.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  omp_set_num_threads(1);  // one worker per fuzzer; results do not depend on the thread count
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tsm::Model model;
  try {
    const nlohmann::json document = tsm::io::parse_json(std::string(reinterpret_cast<const char*>(data), size));
    if (!tsm::fuzz::small_model(document)) return -1;  // not added to the corpus
    model = tsm::io::read_model(document);
  } catch (const tsm::io::InputError&) {
    return 0;
  } catch (const tsm::io::SystemError&) {
    return 0;
  }
  tsm::fuzz::shorten_analysis(model);
  const tsm::solver::RunResult result = tsm::solver::run_analysis(model);
  std::ostringstream sink;
  tsm::io::write_results_json(sink, model, result, {.curves = true});
  tsm::io::write_steps_csv(sink, model, result);
  return 0;
}
