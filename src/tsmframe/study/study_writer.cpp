#include "tsmframe/study/study_writer.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "tsmframe/io/output_file.hpp"
#include "tsmframe/io/json_writer.hpp"

namespace tsm::study {
namespace {

using Field = Cell (*)(const CaseResult&);

struct FixedColumn {
  const char* name;
  Field cell;
};

/// The run's columns, after the parameters'.
const FixedColumn run_columns[] = {
    {"status", [](const CaseResult& r) -> Cell { return r.status; }},
    {"converged", [](const CaseResult& r) -> Cell { return r.converged; }},
    {"steps", [](const CaseResult& r) -> Cell { return r.steps; }},
    {"iterations", [](const CaseResult& r) -> Cell { return r.iterations; }},
    {"last_iterations", [](const CaseResult& r) -> Cell { return r.last_iterations; }},
    {"load_factor", [](const CaseResult& r) -> Cell { return r.load_factor; }},
    {"negative_eigenvalues",  // unknown: empty, null
     [](const CaseResult& r) -> Cell { return r.negative_eigenvalues >= 0 ? Cell(r.negative_eigenvalues) : Cell(NAN); }},
    {"seconds", [](const CaseResult& r) -> Cell { return r.seconds; }},
};

/// The first contact's story, in models with contacts.
const FixedColumn contact_columns[] = {
    {"contact_first_element", [](const CaseResult& r) -> Cell { return r.contact_first_element; }},
    {"contact_max_alpha_first", [](const CaseResult& r) -> Cell { return r.contact_max_alpha_first; }},
    {"contact_last_element", [](const CaseResult& r) -> Cell { return r.contact_last_element; }},
    {"contact_elements_passed", [](const CaseResult& r) -> Cell { return r.contact_elements_passed; }},
};

const FixedColumn case_column = {"case", [](const CaseResult& r) -> Cell { return static_cast<int>(r.index + 1); }};
const FixedColumn notes_column = {"notes", [](const CaseResult& r) -> Cell { return r.notes; }};
const FixedColumn message_column = {"message", [](const CaseResult& r) -> Cell { return r.message; }};

bool has_contacts(const Study& study) { return !study.model.value("contacts", nlohmann::json::array()).empty(); }

Column parameter_column(const Study& study, size_t p) {
  const Parameter& parameter = study.parameters[p];
  return {parameter.name, [&parameter, p](const CaseResult& r) -> Cell {
            return ParameterValue{&parameter.labels[r.choice[p]], &parameter.values[r.choice[p]]};
          }};
}

Column record_column(const Study& study, size_t k) {
  return {study.records[k].name, [k](const CaseResult& r) -> Cell { return k < r.recorded.size() ? r.recorded[k] : NAN; }};
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return quoted + "\"";
}

struct CsvText {
  std::string operator()(const std::string& text) const { return csv_field(text); }
  std::string operator()(bool b) const { return b ? "true" : "false"; }
  std::string operator()(int k) const { return std::to_string(k); }
  std::string operator()(double x) const { return std::isfinite(x) ? io::format_number(x) : std::string(); }
  std::string operator()(const ParameterValue& v) const { return csv_field(*v.label); }
};

void write_csv_line(std::ostream& out, const std::vector<std::string>& fields) {
  for (size_t k = 0; k < fields.size(); ++k) out << (k == 0 ? "" : ",") << fields[k];
  out << '\n';
}

template <class T>
void write_cell(io::JsonWriter& w, const T& value) {
  w.value(value);
}
void write_cell(io::JsonWriter& w, const ParameterValue& v) { w.value(*v.value); }

void write_parameters(io::JsonWriter& w, const Study& study) {
  w.key("parameters").begin_array();
  for (const Parameter& p : study.parameters) {
    w.newline().begin_object().key("name").value(p.name).key("values").begin_array();
    for (const nlohmann::json& v : p.values) w.value(v);
    w.end_array().end_object();
  }
  w.end_array();
}

}  // namespace

std::vector<Column> study_columns(const Study& study) {
  const auto fixed = [](const FixedColumn& c) { return Column{c.name, c.cell}; };
  std::vector<Column> columns = {fixed(case_column)};
  for (size_t p = 0; p < study.parameters.size(); ++p) columns.push_back(parameter_column(study, p));
  for (const FixedColumn& c : run_columns) columns.push_back(fixed(c));
  if (has_contacts(study))
    for (const FixedColumn& c : contact_columns) columns.push_back(fixed(c));
  for (size_t k = 0; k < study.records.size(); ++k) columns.push_back(record_column(study, k));
  columns.push_back(fixed(notes_column));
  columns.push_back(fixed(message_column));
  return columns;
}

std::vector<std::string> fixed_column_names() {
  std::vector<std::string> names = {case_column.name, notes_column.name, message_column.name};
  for (const FixedColumn& c : run_columns) names.push_back(c.name);
  for (const FixedColumn& c : contact_columns) names.push_back(c.name);
  return names;
}

void write_study_csv(std::ostream& out, const Study& study, const std::vector<CaseResult>& rows) {
  const std::vector<Column> columns = study_columns(study);
  std::vector<std::string> fields;
  for (const Column& c : columns) fields.push_back(csv_field(c.name));
  write_csv_line(out, fields);
  for (const CaseResult& r : rows) {
    fields.clear();
    for (const Column& c : columns) fields.push_back(std::visit(CsvText{}, c.cell(r)));
    write_csv_line(out, fields);
  }
}

void write_study_json(std::ostream& out, const Study& study, const std::vector<CaseResult>& rows) {
  const std::vector<Column> columns = study_columns(study);
  io::JsonWriter w(out);
  w.begin_object();
  w.key("format").value("tsmframe-study-results/1");
  w.key("title").value(study.title);
  write_parameters(w, study);
  w.newline().key("cases").begin_array();
  for (const CaseResult& r : rows) {
    w.newline().begin_object();
    for (const Column& c : columns) {
      w.key(c.name);
      std::visit([&w](const auto& value) { write_cell(w, value); }, c.cell(r));
    }
    w.end_object();
  }
  w.end_array();
  w.newline().end_object();
  out << '\n';
}

void write_study(const std::string& directory, const Study& study, const std::vector<CaseResult>& rows) {
  io::make_directories(directory);
  const std::filesystem::path dir(directory);
  io::write_output_file((dir / "study.csv").string(), [&](std::ostream& out) { write_study_csv(out, study, rows); });
  io::write_output_file((dir / "study.json").string(), [&](std::ostream& out) { write_study_json(out, study, rows); });
}

}  // namespace tsm::study
