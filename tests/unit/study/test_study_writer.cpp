// study.csv and study.json (study/study_writer.hpp): one list of columns, so both files name
// and order the same columns and carry the same value in each field; a field the CSV cannot
// hold as it is is quoted; a record a case has none of is empty in the CSV and null in the JSON.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_writer.hpp"
#include "tsmframe/study/study_writer.hpp"

namespace {

using nlohmann::json;
using ordered_json = nlohmann::ordered_json;  // study.json's keys in the order written
using namespace tsm::study;

/// A study built in code: two parameters, two records, a model with a contact or without.
Study two_parameter_study(bool contacts) {
  Study s;
  s.title = "writer";
  s.model = {{"contacts", contacts ? json::array({json::object()}) : json::array()}};
  // "divisions" as read from "values": [2, 16]; "set-up" as read from two variants.
  s.parameters = {{"divisions", {"2", "16"}, {{}, {}}, {2, 16}},
                  {"set-up", {"a, b", "say \"c\""}, {{}, {}}, {"a, b", "say \"c\""}}};
  s.records.resize(2);
  s.records[0].name = "tip_uy";
  s.records[1].name = "peak";
  return s;
}

/// Two rows: one converged, with both records; one bad-input row, with none.
std::vector<CaseResult> two_rows() {
  CaseResult converged;
  converged.index = 0;
  converged.choice = {0, 1};
  converged.status = "converged";
  converged.converged = true;
  converged.steps = 4;
  converged.iterations = 17;
  converged.last_iterations = 3;
  converged.load_factor = 0.1;
  converged.negative_eigenvalues = 1;
  converged.notes = "Past a limit point.";
  converged.seconds = 0.25;
  converged.contact_first_element = 3;
  converged.contact_max_alpha_first = 0.75;
  converged.contact_last_element = 5;
  converged.contact_elements_passed = 2;
  converged.recorded = {-1.5e-3, 1.0};
  CaseResult bad;
  bad.index = 3;
  bad.choice = {1, 1};
  bad.status = "bad-input";
  bad.message = "members[0].divisions: must be between 1 and 100000, got 0";
  return {converged, bad};
}

/// The CSV's lines, each split at the commas outside quotes (quotes kept).
std::vector<std::vector<std::string>> csv_lines(const std::string& text) {
  std::vector<std::vector<std::string>> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted) fields.emplace_back();
      else fields.back() += c;
    }
    lines.push_back(fields);
  }
  return lines;
}

/// A study.json field as study.csv writes it.
std::string as_csv(const ordered_json& value) {
  if (value.is_null()) return "";
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_integer()) return std::to_string(value.get<long>());
  if (value.is_number()) return tsm::io::format_number(value.get<double>());
  const std::string text = value.get<std::string>();
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

struct Written {
  std::vector<std::vector<std::string>> csv;
  ordered_json json_document;
};

Written write_both(const Study& study, const std::vector<CaseResult>& rows) {
  std::ostringstream csv, json_text;
  write_study_csv(csv, study, rows);
  write_study_json(json_text, study, rows);
  return {csv_lines(csv.str()), ordered_json::parse(json_text.str())};
}

TEST(StudyWriter, TheCsvAndTheJsonNameAndOrderTheSameColumnsAndHoldTheSameValues) {
  for (bool contacts : {true, false}) {
    const Study study = two_parameter_study(contacts);
    const Written w = write_both(study, two_rows());
    ASSERT_EQ(w.csv.size(), 3u);
    ASSERT_EQ(w.json_document["cases"].size(), 2u);
    for (size_t r = 0; r < 2; ++r) {
      const ordered_json& row = w.json_document["cases"][r];
      std::vector<std::string> keys;
      for (const auto& item : row.items()) keys.push_back(item.key());
      ASSERT_EQ(keys.size(), w.csv[0].size()) << "contacts " << contacts;
      size_t k = 0;
      for (const auto& item : row.items()) {
        EXPECT_EQ(w.csv[0][k], item.key());
        EXPECT_EQ(w.csv[r + 1][k], as_csv(item.value())) << item.key();
        ++k;
      }
    }
  }
}

TEST(StudyWriter, TheColumnsAreTheCaseTheParametersTheRunsTheContactsTheRecordsAndTheMessage) {
  std::vector<std::string> names;
  for (const Column& c : study_columns(two_parameter_study(true))) names.push_back(c.name);
  const std::vector<std::string> expected = {
      "case", "divisions", "set-up", "status", "converged", "steps", "iterations", "last_iterations", "load_factor",
      "negative_eigenvalues", "seconds", "contact_first_element", "contact_max_alpha_first", "contact_last_element",
      "contact_elements_passed", "tip_uy", "peak", "notes", "message"};
  EXPECT_EQ(names, expected);
  names.clear();
  for (const Column& c : study_columns(two_parameter_study(false))) names.push_back(c.name);
  EXPECT_EQ(names.size(), expected.size() - 4) << "no contact columns without contacts";
  EXPECT_EQ(std::count(names.begin(), names.end(), "contact_first_element"), 0);
}

TEST(StudyWriter, ARowsFieldsAreItsValuesAndARecordItHasNoneOfIsEmptyOrNull) {
  const Written w = write_both(two_parameter_study(true), two_rows());
  const ordered_json& converged = w.json_document["cases"][0];
  EXPECT_EQ(converged["case"], 1);
  EXPECT_EQ(converged["divisions"], 2);  // a number in study.json, its label in study.csv
  EXPECT_EQ(w.csv[1][1], "2");
  EXPECT_EQ(converged["set-up"], "say \"c\"");
  EXPECT_EQ(converged["iterations"], 17);
  EXPECT_EQ(converged["load_factor"], 0.1);
  EXPECT_EQ(converged["tip_uy"], -1.5e-3);
  const ordered_json& bad = w.json_document["cases"][1];
  EXPECT_EQ(bad["case"], 4);
  EXPECT_TRUE(bad["tip_uy"].is_null());
  EXPECT_TRUE(bad["peak"].is_null());
  EXPECT_EQ(w.csv[2][15], "");
  EXPECT_EQ(w.csv[2][16], "");
  EXPECT_EQ(converged["negative_eigenvalues"], 1);  // an unstable end state
  EXPECT_EQ(w.csv[1][9], "1");
  EXPECT_TRUE(bad["negative_eigenvalues"].is_null());  // unknown: no converged step
  EXPECT_EQ(w.csv[2][9], "");
  EXPECT_EQ(converged["notes"], "Past a limit point.");
  EXPECT_EQ(bad["notes"], "");
  EXPECT_EQ(w.csv[1][2], "\"say \"\"c\"\"\"");  // a quote doubled, the field quoted
  EXPECT_EQ(w.csv[2][2], "\"say \"\"c\"\"\"");
}

TEST(StudyWriter, TheJsonListsEachParametersValuesInOrder) {
  const Written w = write_both(two_parameter_study(false), two_rows());
  EXPECT_EQ(w.json_document["format"], "tsmframe-study-results/1");
  EXPECT_EQ(w.json_document["title"], "writer");
  EXPECT_EQ(w.json_document["parameters"],
            ordered_json::parse(R"([{"name": "divisions", "values": [2, 16]}, {"name": "set-up", "values": ["a, b", "say \"c\""]}])"));
}

TEST(StudyWriter, NoParameterOrRecordMayTakeTheNameOfAFixedColumn) {
  const json model = {{"nodes", json::array()}};
  for (const std::string& name : fixed_column_names()) {
    const json as_parameter = {{"model", model}, {"sweep", {{{"name", name}, {"path", "/extra"}, {"values", {1}}}}}};
    EXPECT_THROW(read_study(as_parameter, "."), tsm::io::InputError) << name;
    json as_record = {{"model", model}, {"sweep", {{{"name", "x"}, {"path", "/extra"}, {"values", {1}}}}}};
    as_record["record"] = {{{"name", name}, {"quantity", "load_factor"}}};
    EXPECT_THROW(read_study(as_record, "."), tsm::io::InputError) << name;
  }
  EXPECT_EQ(fixed_column_names().size(), 15u);  // case, notes, message, the 8 run columns and the 4 contact columns
}

}  // namespace
