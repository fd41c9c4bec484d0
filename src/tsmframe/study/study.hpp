#pragma once
// Parameter studies: one model and a sweep over parameters, every case run on its own (in
// parallel over the machine's cores), one results row per case. A case that fails — bad input
// after substitution, non-convergence — is a row too, never a crash of the sweep. This file is
// what a study is and how it is read; study_runner.hpp runs its cases, study_writer.hpp writes
// their rows.
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
#include <string>
#include <vector>

#include "tsmframe/io/json_input.hpp"
#include "tsmframe/study/assignment.hpp"

namespace tsm::study {

/// The most cases a study may have.
inline constexpr size_t max_cases = 1'000'000;

struct Parameter {
  std::string name;
  std::vector<std::string> labels;               ///< one per value, as written in study.csv's rows
  std::vector<std::vector<Assignment>> assignments;  ///< per value: what it sets, in order
  /// Per value, as study.json's rows show it: the value as given (a number as a number), a
  /// variant's label.
  std::vector<nlohmann::json> values;
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
  /// What the rows depend on, as 16 hex digits: tsmframe's version, the study document and its
  /// model (FNV-1a over their canonical JSON). A journal's rows (study_journal.hpp) are this
  /// study's only where its fingerprint is this.
  std::string fingerprint;
  /// The number of cases, the product of the parameters' value counts; throws
  /// std::length_error past max_cases (read_study refuses such a study first).
  size_t case_count() const;
};

/// Reads a study file (io/input_file.hpp: at most 1 GiB, no directory); throws io::InputError with
/// the JSON path.
Study read_study_file(const std::string& path);
Study read_study(const nlohmann::json& document, const std::string& directory);

}  // namespace tsm::study
