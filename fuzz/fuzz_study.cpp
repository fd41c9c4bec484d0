// Fuzz target: a study file read (study/study_reader) and its cases expanded — the first, the
// middle and the last case's model built by the sweep's assignments and read as a model — without
// running them. Bad input must end as io::InputError (or io::SystemError); anything else
// escaping — another exception, a sanitizer report, a hang — is a finding. A "model_file" is
// read from examples/ and only as a plain file name (no input may read /dev/zero or a path of
// its choosing).

#include <omp.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>
#include <vector>

#include "harness_bounds.hpp"
#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/io/system_error.hpp"
#include "tsmframe/study/study_runner.hpp"

namespace {

/// A file name of examples/: letters, digits, '-', '_' and one ".json".
bool plain_example_name(const nlohmann::json& value) {
  if (!value.is_string()) return true;  // the reader refuses it
  const std::string& name = value.get_ref<const std::string&>();
  const std::string suffix = ".json";
  if (name.size() <= suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) return false;
  return std::all_of(name.begin(), name.end() - static_cast<std::ptrdiff_t>(suffix.size()),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; });
}

void expand_case(const tsm::study::Study& study, size_t index) {
  try {
    const nlohmann::json model = tsm::study::case_model(study, tsm::study::case_choice(study, index));
    if (tsm::fuzz::small_model(model)) (void)tsm::io::read_model(model);
  } catch (const tsm::io::InputError&) {
  } catch (const tsm::io::SystemError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  omp_set_num_threads(1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tsm::study::Study study;
  try {
    const nlohmann::json document = tsm::io::parse_json(std::string(reinterpret_cast<const char*>(data), size));
    if (document.is_object() && document.contains("model_file") && !plain_example_name(document["model_file"])) return -1;
    study = tsm::study::read_study(document, TSMFRAME_FUZZ_EXAMPLES);
  } catch (const tsm::io::InputError&) {
    return 0;
  } catch (const tsm::io::SystemError&) {
    return 0;
  }
  const size_t cases = study.case_count();  // read_study has refused more than max_cases
  std::vector<size_t> indices = {0, cases / 2, cases - 1};
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  for (size_t index : indices) expand_case(study, index);
  return 0;
}
