#pragma once
// Writing a study's rows (study_runner.hpp): study.csv and study.json, both from one list of
// columns — case, the parameters, the run's columns, the first contact's story (models with
// contacts), the records, message — so that the two files name and order the same columns.

#include <functional>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

#include "tsmframe/study/study.hpp"
#include "tsmframe/study/study_runner.hpp"

namespace tsm::study {

/// A parameter's value in a row: its label in study.csv, the value itself in study.json.
struct ParameterValue {
  const std::string* label = nullptr;
  const nlohmann::json* value = nullptr;
};

/// One field of a row. A number that is not finite (a record the case has none of) is an
/// empty field in study.csv and null in study.json.
using Cell = std::variant<std::string, bool, int, double, ParameterValue>;

/// A column of study.csv and study.json: its name and its field in each row.
struct Column {
  std::string name;
  std::function<Cell(const CaseResult&)> cell;
};

/// The study's columns, in order.
std::vector<Column> study_columns(const Study& study);

/// The names of the columns every study may have (all but the parameters' and the records'):
/// names a parameter or a record may not take.
std::vector<std::string> fixed_column_names();

/// study.csv's text, to `out`.
void write_study_csv(std::ostream& out, const Study& study, const std::vector<CaseResult>& rows);
/// study.json's text (the parameters and their values, the rows as its "cases"), to `out`.
void write_study_json(std::ostream& out, const Study& study, const std::vector<CaseResult>& rows);

/// study.csv and study.json into `directory` (the temporary directory of an io::OutputDirectory:
/// they appear with its commit); throws io::SystemError (the OS's reason) where the system fails.
void write_study(const std::string& directory, const Study& study, const std::vector<CaseResult>& rows);

}  // namespace tsm::study
