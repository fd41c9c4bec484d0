#pragma once
// Parameter studies: one model and a sweep over parameters, every case run on its own (in
// parallel over the machine's cores), one results row per case. A case that fails — bad input
// after substitution, non-convergence — is a row too, never a crash of the sweep.
//
// Study file ("tsmframe-study/1"):
//   {"format": "tsmframe-study/1", "title": "…",
//    "model": {…} | "model_file": "relative/to/the/study.json",
//    "sweep": [
//      {"name": "divisions", "path": "/members/0/divisions", "values": [6, 8, 10]},
//      {"name": "divisions", "path": ["/members/0/divisions"], "range": [6, 200]},    // [from, to(, step)], ends within ±2⁵³
//      {"name": "setup", "variants": [{"label": "cantilever", "set": {"/supports": […], "/loads": […]}}, …]}
//    ],
//    "record": [                          // response quantities, one column each (optional)
//      {"name": "tip_uy", "quantity": "displacement", "node": [9.0, 0.0], "dof": "uy"},
//      {"name": "peak", "quantity": "load_factor", "of": "max"}, …],
//    "keep": false}                      // true: each case's results.json and steps.csv under cases/<k>/
// The cases are the Cartesian product of the sweep entries, the first entry varying slowest, at
// most a million.
// Paths are JSON pointers (RFC 6901) into the model: through objects to any key, through lists
// to an entry or one past the end (assignment.hpp).

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "tsmframe/io/json_input.hpp"
#include "tsmframe/solver/status.hpp"
#include "tsmframe/study/assignment.hpp"

namespace tsm::study {

/// The columns of study.csv and study.json besides case, the parameters, the records and message.
inline constexpr const char* run_columns[] = {"status", "converged", "steps", "iterations", "last_iterations", "load_factor", "seconds"};
inline constexpr const char* contact_columns[] = {"contact_first_element", "contact_max_alpha_first", "contact_last_element",
                                                  "contact_elements_passed"};  ///< models with contacts

struct Parameter {
  std::string name;
  std::vector<std::string> labels;               ///< one per value, as written in the rows
  std::vector<std::vector<Assignment>> assignments;  ///< per value: what it sets, in order
};

/// A response quantity each case reports: at its last converged step, or the largest or
/// smallest over its converged steps.
struct Record {
  enum class Quantity { displacement, reaction, contact_force, contact_xi, load_factor };
  enum class Of { last, max, min, max_abs };
  std::string name;
  Quantity quantity = Quantity::load_factor;
  std::optional<io::NodeReference> node;  ///< id or coordinates, resolved in each case's model; none for load_factor
  int dof = -1;         ///< 0 ux, 1 uy, 2 rz (displacement, reaction)
  Of of = Of::last;
  std::string path;     ///< `record[k]`, for messages
};

struct Study {
  std::string title;
  nlohmann::json model;
  std::vector<Parameter> parameters;
  std::vector<Record> records;
  bool keep = false;
  size_t case_count() const;  ///< at most a million (read_study checks)
};

/// Reads a study file; throws io::InputError with the JSON path.
Study read_study_file(const std::string& path);
Study read_study(const nlohmann::json& document, const std::string& directory);

/// One row of the study.
struct CaseResult {
  size_t index = 0;
  std::vector<size_t> choice;       ///< value index per parameter
  std::string status;               ///< status_name, or "bad-input"
  bool converged = false;
  int steps = 0;                    ///< converged steps
  int iterations = 0;               ///< all Newton iterations, failed attempts included
  int last_iterations = 0;          ///< iterations of the last attempt
  double load_factor = 0.0;         ///< λ at the last converged step
  double seconds = 0.0;
  std::string message;
  // The first contact's story (when the model has contacts):
  int contact_first_element = 0;    ///< element id where it first touched (0: never)
  double contact_max_alpha_first = 0.0;  ///< largest α reached there at a converged step
  int contact_last_element = 0;     ///< element id at the last step in contact
  int contact_elements_passed = 0;  ///< element ends passed after the first element
  /// Per record: its value, NaN where the case has none (no converged step; a contact not
  /// touching at its last step for contact_xi).
  std::vector<double> recorded;
};

/// Runs every case on `threads` threads (0: all cores). `progress` is called after each case.
/// Whatever a case throws is its row (status "bad-input", the reason in its message); what
/// `progress` throws stops the cases and is rethrown here, after every thread has ended.
std::vector<CaseResult> run_study(const Study& study, int threads, const std::string& keep_directory,
                                  const std::function<void(const CaseResult&)>& progress = {});

/// The case's model JSON: the base model with the case's assignments, in order. Throws
/// io::InputError where an assignment's pointer names no place in the model so far (assignment.hpp).
nlohmann::json case_model(const Study& study, const std::vector<size_t>& choice);
std::vector<size_t> case_choice(const Study& study, size_t index);

/// study.json's text (the rows as its "cases"), to `out`.
void write_study_json(std::ostream& out, const Study& study, const std::vector<CaseResult>& rows);

/// study.csv and study.json into `directory` (atomically).
void write_study(const std::string& directory, const Study& study, const std::vector<CaseResult>& rows);

}  // namespace tsm::study
