// Reading a study file (study.hpp): the sweep's parameters and the records, strictly, with the
// model reader's JSON paths and helpers (io/json_input.hpp).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>

#include "tsmframe/io/input_file.hpp"
#include "tsmframe/io/json_input.hpp"
#include "tsmframe/study/study.hpp"
#include "tsmframe/study/study_writer.hpp"
#include "tsmframe/util/fnv.hpp"
#include "tsmframe/version.hpp"

namespace tsm::study {
namespace {

using io::check_keys;
using io::child;
using io::fail;
using io::quote_text;
using nlohmann::json;

constexpr long max_range_values = 100'000;    // (to − from) / step at most: 100,001 values
/// A range's ends: whole numbers beyond 2⁵³ are no longer exact as the doubles a model's numbers are read as.
constexpr long largest_range_end = 1L << 53;

std::string pointer(const json& value, const std::string& path) {
  if (!value.is_string()) fail(path, "expected a JSON pointer such as \"/members/0/divisions\"");
  const std::string text = value.get<std::string>();
  try {
    (void)json::json_pointer(text);
  } catch (const json::exception&) {
    fail(path, "not a JSON pointer: " + quote_text(text) + " (write \"/members/0/divisions\")");
  }
  if (text.empty()) fail(path, "the empty pointer would replace the whole model");
  return text;
}

std::string label_of(const json& value) {
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

/// A string value under a required key.
std::string required_string(const json& object, const char* key, const std::string& path, const std::string& missing) {
  if (!object.contains(key)) fail(child(path, key), missing);
  return io::string(object[key], child(path, key));
}

void read_variants(const json& variants, const std::string& path, Parameter& out) {
  if (!variants.is_array() || variants.empty()) fail(path, "expected a non-empty array");
  for (size_t k = 0; k < variants.size(); ++k) {
    const std::string vpath = child(path, k);
    const json& v = variants[k];
    if (!v.is_object()) fail(vpath, "expected {\"label\": …, \"set\": {pointer: value, …}}");
    check_keys(v, vpath, {"label", "set"});
    out.labels.push_back(required_string(v, "label", vpath, "missing (required, a string)"));
    out.values.push_back(out.labels.back());
    if (!v.contains("set") || !v["set"].is_object()) fail(child(vpath, "set"), "missing (required, an object of pointer: value)");
    std::vector<Assignment> sets;
    for (const auto& item : v["set"].items()) {
      const std::string spath = child(child(vpath, "set"), item.key());
      sets.push_back({pointer(json(item.key()), spath), item.value(), spath});
    }
    out.assignments.push_back(std::move(sets));
  }
}

/// `[from, to]` or `[from, to, step]`: from, from + step, … up to to, counted without overflow.
std::vector<json> range_values(const json& r, const std::string& path) {
  if (!r.is_array() || r.size() < 2 || r.size() > 3) fail(path, "expected [from, to] or [from, to, step] (whole numbers)");
  const long from = io::bounded_integer(r[0], child(path, 0), -largest_range_end, largest_range_end);
  const long to = io::bounded_integer(r[1], child(path, 1), -largest_range_end, largest_range_end);
  const long step = r.size() == 3 ? io::integer(r[2], child(path, 2)) : 1;
  if (step <= 0) fail(child(path, 2), "must be positive");
  if (to < from) fail(child(path, 1), "must not be below from");
  const long steps = (to - from) / step;  // within ±2⁵³ the span fits a long
  if (steps > max_range_values) fail(path, "more than " + std::to_string(max_range_values) + " values");
  std::vector<json> values;
  for (long k = 0; k <= steps; ++k) values.push_back(from + k * step);  // k · step ≤ to − from
  return values;
}

Parameter read_parameter(const json& p, const std::string& path) {
  if (!p.is_object()) fail(path, "expected an object with \"name\" and \"values\", \"range\" or \"variants\"");
  check_keys(p, path, {"name", "path", "values", "range", "variants"});
  Parameter out;
  out.name = required_string(p, "name", path, "missing (required, a string)");
  if (out.name.empty()) fail(child(path, "name"), "empty (the parameter's study.csv column needs a name)");
  if (p.contains("variants")) {
    if (p.contains("values") || p.contains("range") || p.contains("path"))
      fail(path, "give either \"variants\" or \"path\" with \"values\"/\"range\"");
    read_variants(p["variants"], child(path, "variants"), out);
    return out;
  }
  if (!p.contains("path")) fail(child(path, "path"), "missing (required with \"values\" or \"range\")");
  std::vector<std::pair<std::string, std::string>> pointers;  // pointer, where it is written
  const std::string ppath = child(path, "path");
  if (p["path"].is_array()) {
    for (size_t k = 0; k < p["path"].size(); ++k) pointers.emplace_back(pointer(p["path"][k], child(ppath, k)), child(ppath, k));
    if (pointers.empty()) fail(ppath, "give at least one pointer");
  } else {
    pointers.emplace_back(pointer(p["path"], ppath), ppath);
  }
  if (p.contains("values") == p.contains("range")) fail(path, "give exactly one of \"values\" and \"range\"");
  std::vector<json> values;
  if (p.contains("values")) {
    if (!p["values"].is_array() || p["values"].empty()) fail(child(path, "values"), "expected a non-empty array");
    values = p["values"].get<std::vector<json>>();
  } else {
    values = range_values(p["range"], child(path, "range"));
  }
  for (const json& v : values) {
    out.labels.push_back(label_of(v));
    out.values.push_back(v);
    std::vector<Assignment> sets;
    for (const auto& [ptr, where] : pointers) sets.push_back({ptr, v, where});
    out.assignments.push_back(std::move(sets));
  }
  return out;
}

Record::Quantity quantity_from_name(const std::string& name, const std::string& path) {
  using Q = Record::Quantity;
  const std::pair<const char*, Q> quantities[] = {{"displacement", Q::displacement}, {"reaction", Q::reaction},
                                                  {"contact_force", Q::contact_force}, {"contact_xi", Q::contact_xi},
                                                  {"load_factor", Q::load_factor}};
  for (const auto& [text, q] : quantities)
    if (name == text) return q;
  fail(path, "unknown quantity " + quote_text(name) + " (expected displacement, reaction, contact_force, contact_xi or load_factor)");
}

Record read_record(const json& r, const std::string& path) {
  if (!r.is_object()) fail(path, "expected {\"name\": …, \"quantity\": …}");
  check_keys(r, path, {"name", "quantity", "node", "dof", "of"});
  Record out;
  out.path = path;
  out.name = required_string(r, "name", path, "missing (required, a string)");
  if (out.name.empty()) fail(child(path, "name"), "empty (the parameter's study.csv column needs a name)");
  const std::string quantity = required_string(r, "quantity", path, "missing (required, a string)");
  out.quantity = quantity_from_name(quantity, child(path, "quantity"));
  const bool with_node = out.quantity != Record::Quantity::load_factor;
  const bool with_dof = out.quantity == Record::Quantity::displacement || out.quantity == Record::Quantity::reaction;
  if (with_node) {
    if (!r.contains("node")) fail(child(path, "node"), "missing (required for " + quantity + ")");
    out.node = io::node_reference(r["node"], child(path, "node"));
  } else if (r.contains("node")) {
    fail(child(path, "node"), "not used by load_factor");
  }
  if (with_dof) {
    const std::string dof = required_string(r, "dof", path, "missing (required for " + quantity + ": ux, uy or rz)");
    out.dof = io::dof_from_name(dof, child(path, "dof"));
  } else if (r.contains("dof")) {
    fail(child(path, "dof"), "not used by " + quantity);
  }
  if (r.contains("of")) {
    const std::string of = r["of"].is_string() ? r["of"].get<std::string>() : "";
    if (of == "last") out.of = Record::Of::last;
    else if (of == "max") out.of = Record::Of::max;
    else if (of == "min") out.of = Record::Of::min;
    else if (of == "max_abs") out.of = Record::Of::max_abs;
    else fail(child(path, "of"), "expected \"last\", \"max\", \"min\" or \"max_abs\" (over the converged steps)");
  }
  return out;
}

json read_base_model(const json& doc, const std::string& directory) {
  if (doc.contains("model") == doc.contains("model_file")) fail("model", "give exactly one of \"model\" and \"model_file\"");
  if (doc.contains("model")) {
    if (!doc["model"].is_object()) fail("model", "expected the model as an object (docs/format.md)");
    return doc["model"];
  }
  const std::filesystem::path file = std::filesystem::path(directory) / io::string(doc["model_file"], "model_file");
  try {
    return io::parse_json(io::read_input_file(file.string()));
  } catch (const io::InputError& e) {
    fail("model_file", file.string() + ": " + e.reason());
  }
}

/// The number of cases, the product of the parameters' value counts: at most a million.
void check_case_count(const std::vector<Parameter>& parameters) {
  double cases = 1.0;  // a double: a count past 2⁶⁴ must not wrap round to a small one
  for (const Parameter& p : parameters) cases *= static_cast<double>(p.labels.size());
  if (cases <= static_cast<double>(max_cases)) return;
  std::ostringstream os;
  if (cases < 1e15) os << static_cast<long long>(cases);  // exact: below 2⁵³ the products are
  else if (std::isinf(cases)) os << "past 1e308";
  else os << std::setprecision(3) << cases;
  fail("sweep", "more than a million cases (" + os.str() + ")");
}

}  // namespace

size_t Study::case_count() const {
  for (const Parameter& p : parameters)
    if (p.labels.empty()) return 0;
  size_t n = 1;
  for (const Parameter& p : parameters) {
    if (p.labels.size() > max_cases / n) throw std::length_error("a study of more than a million cases");
    n *= p.labels.size();
  }
  return n;
}

namespace {

/// Study::fingerprint of a study document and its base model.
std::string study_fingerprint(const json& doc, const json& model) {
  std::uint64_t hash = util::fnv1a(version);
  hash = util::fnv1a(doc.dump(), util::fnv1a(hash, 0));  // object keys sorted: the canonical text
  hash = util::fnv1a(model.dump(), util::fnv1a(hash, 0));
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

}  // namespace

Study read_study(const json& doc, const std::string& directory) {
  if (!doc.is_object()) fail("", "a study file is a JSON object");
  check_keys(doc, "", {"$schema", "format", "title", "model", "model_file", "sweep", "record", "keep"});
  if (doc.contains("format")) {
    const std::string format = io::string(doc["format"], "format");
    if (format != "tsmframe-study/1") fail("format", "unsupported format " + quote_text(format) + " (expected \"tsmframe-study/1\")");
  }
  Study s;
  if (doc.contains("title")) s.title = io::string(doc["title"], "title");
  s.model = read_base_model(doc, directory);
  if (!doc.contains("sweep") || !doc["sweep"].is_array() || doc["sweep"].empty())
    fail("sweep", "missing (required: a non-empty array of parameters)");
  // Every column of study.csv has a name of its own: the fixed ones, the parameters', the records'.
  const std::vector<std::string> fixed = fixed_column_names();
  std::set<std::string> names(fixed.begin(), fixed.end());
  for (size_t k = 0; k < doc["sweep"].size(); ++k) {
    s.parameters.push_back(read_parameter(doc["sweep"][k], child("sweep", k)));
    if (!names.insert(s.parameters.back().name).second)
      fail(child(child("sweep", k), "name"), quote_text(s.parameters.back().name) + " names another column already");
  }
  check_case_count(s.parameters);
  std::vector<const Assignment*> assignments;
  for (const Parameter& p : s.parameters)
    for (const auto& sets : p.assignments)
      for (const Assignment& a : sets) assignments.push_back(&a);
  check_assignments(s.model, assignments);
  if (doc.contains("record")) {
    if (!doc["record"].is_array()) fail("record", "expected an array of {\"name\": …, \"quantity\": …}");
    for (size_t k = 0; k < doc["record"].size(); ++k) {
      s.records.push_back(read_record(doc["record"][k], child("record", k)));
      if (!names.insert(s.records.back().name).second)
        fail(child(child("record", k), "name"), quote_text(s.records.back().name) + " names another column already");
    }
  }
  if (doc.contains("keep")) s.keep = io::boolean(doc["keep"], "keep");
  s.fingerprint = study_fingerprint(doc, s.model);
  return s;
}

Study read_study_file(const std::string& path) {
  return read_study(io::parse_json(io::read_input_file(path, "the study file")), std::filesystem::path(path).parent_path().string());
}

}  // namespace tsm::study
