#include "tsmframe/study/study.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "tsmframe/io/atomic_file.hpp"
#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_writer.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/io/results_writer.hpp"
#include "tsmframe/model/node_lookup.hpp"
#include "tsmframe/solver/analysis.hpp"

namespace tsm::study {
namespace {

using nlohmann::json;
using io::InputError;

[[noreturn]] void fail(const std::string& path, const std::string& reason) { throw InputError(path, reason); }

// The columns of study.csv and study.json besides case, the parameters, the records and message.
constexpr const char* run_columns[] = {"status", "converged", "steps", "iterations", "last_iterations", "load_factor", "seconds"};
constexpr const char* contact_columns[] = {"contact_first_element", "contact_max_alpha_first", "contact_last_element",
                                           "contact_elements_passed"};  // models with contacts

std::string child(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string child(const std::string& path, size_t k) { return path + "[" + std::to_string(k) + "]"; }

void check_keys(const json& object, const std::string& path, std::initializer_list<const char*> allowed) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    if (it.key() == "extra") continue;
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return it.key() == a; })) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      fail(child(path, it.key()), "unknown key \"" + it.key() + "\" (expected one of: " + list + ")");
    }
  }
}

std::string pointer(const json& value, const std::string& path) {
  if (!value.is_string()) fail(path, "expected a JSON pointer such as \"/members/0/divisions\"");
  const std::string text = value.get<std::string>();
  try {
    (void)json::json_pointer(text);
  } catch (const json::exception&) {
    fail(path, "not a JSON pointer: \"" + text + "\" (write \"/members/0/divisions\")");
  }
  if (text.empty()) fail(path, "the empty pointer would replace the whole model");
  return text;
}

std::string label_of(const json& value) {
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

Parameter read_parameter(const json& p, const std::string& path) {
  if (!p.is_object()) fail(path, "expected an object with \"name\" and \"values\", \"range\" or \"variants\"");
  check_keys(p, path, {"name", "path", "values", "range", "variants"});
  Parameter out;
  if (!p.contains("name") || !p["name"].is_string()) fail(child(path, "name"), "missing (required, a string)");
  out.name = p["name"].get<std::string>();
  if (p.contains("variants")) {
    if (p.contains("values") || p.contains("range") || p.contains("path"))
      fail(path, "give either \"variants\" or \"path\" with \"values\"/\"range\"");
    const json& variants = p["variants"];
    if (!variants.is_array() || variants.empty()) fail(child(path, "variants"), "expected a non-empty array");
    for (size_t k = 0; k < variants.size(); ++k) {
      const std::string vpath = child(child(path, "variants"), k);
      const json& v = variants[k];
      if (!v.is_object()) fail(vpath, "expected {\"label\": …, \"set\": {pointer: value, …}}");
      check_keys(v, vpath, {"label", "set"});
      if (!v.contains("label") || !v["label"].is_string()) fail(child(vpath, "label"), "missing (required, a string)");
      if (!v.contains("set") || !v["set"].is_object()) fail(child(vpath, "set"), "missing (required, an object of pointer: value)");
      out.labels.push_back(v["label"].get<std::string>());
      std::vector<std::pair<std::string, json>> sets;
      for (auto it = v["set"].begin(); it != v["set"].end(); ++it)
        sets.emplace_back(pointer(json(it.key()), child(child(vpath, "set"), it.key())), it.value());
      out.assignments.push_back(std::move(sets));
    }
    return out;
  }
  if (!p.contains("path")) fail(child(path, "path"), "missing (required with \"values\" or \"range\")");
  std::vector<std::string> pointers;
  if (p["path"].is_array()) {
    for (size_t k = 0; k < p["path"].size(); ++k) pointers.push_back(pointer(p["path"][k], child(child(path, "path"), k)));
    if (pointers.empty()) fail(child(path, "path"), "give at least one pointer");
  } else {
    pointers.push_back(pointer(p["path"], child(path, "path")));
  }
  std::vector<json> values;
  if (p.contains("values") == p.contains("range")) fail(path, "give exactly one of \"values\" and \"range\"");
  if (p.contains("values")) {
    if (!p["values"].is_array() || p["values"].empty()) fail(child(path, "values"), "expected a non-empty array");
    for (const json& v : p["values"]) values.push_back(v);
  } else {
    const json& r = p["range"];
    const std::string rpath = child(path, "range");
    if (!r.is_array() || r.size() < 2 || r.size() > 3) fail(rpath, "expected [from, to] or [from, to, step] (whole numbers)");
    for (size_t k = 0; k < r.size(); ++k)
      if (!r[k].is_number_integer()) fail(child(rpath, k), "expected a whole number");
    const long from = r[0].get<long>(), to = r[1].get<long>(), step = r.size() == 3 ? r[2].get<long>() : 1;
    if (step <= 0) fail(child(rpath, 2), "must be positive");
    if (to < from) fail(child(rpath, 1), "must not be below from");
    if ((to - from) / step > 100000) fail(rpath, "more than 100000 values");
    for (long v = from; v <= to; v += step) values.push_back(v);
  }
  for (const json& v : values) {
    out.labels.push_back(label_of(v));
    std::vector<std::pair<std::string, json>> sets;
    for (const std::string& ptr : pointers) sets.emplace_back(ptr, v);
    out.assignments.push_back(std::move(sets));
  }
  return out;
}

Record read_record(const json& r, const std::string& path) {
  if (!r.is_object()) fail(path, "expected {\"name\": …, \"quantity\": …}");
  check_keys(r, path, {"name", "quantity", "node", "dof", "of"});
  Record out;
  out.path = path;
  if (!r.contains("name") || !r["name"].is_string() || r["name"].get<std::string>().empty())
    fail(child(path, "name"), "missing (required, a string)");
  out.name = r["name"].get<std::string>();
  if (!r.contains("quantity") || !r["quantity"].is_string()) fail(child(path, "quantity"), "missing (required, a string)");
  const std::string quantity = r["quantity"].get<std::string>();
  using Q = Record::Quantity;
  const std::pair<const char*, Q> quantities[] = {{"displacement", Q::displacement}, {"reaction", Q::reaction},
                                                  {"contact_force", Q::contact_force}, {"contact_xi", Q::contact_xi},
                                                  {"load_factor", Q::load_factor}};
  bool known = false;
  for (const auto& [text, q] : quantities)
    if (quantity == text) out.quantity = q, known = true;
  if (!known)
    fail(child(path, "quantity"), "unknown quantity \"" + quantity +
                                      "\" (expected displacement, reaction, contact_force, contact_xi or load_factor)");
  const bool with_node = out.quantity != Q::load_factor;
  const bool with_dof = out.quantity == Q::displacement || out.quantity == Q::reaction;
  if (with_node) {
    if (!r.contains("node")) fail(child(path, "node"), "missing (required for " + quantity + ")");
    const json& node = r["node"];
    if (!node.is_number_integer() && !(node.is_array() && node.size() == 2 && node[0].is_number() && node[1].is_number()))
      fail(child(path, "node"), "expected a node id or coordinates [x, y]");
    out.node = node;
  } else if (r.contains("node")) {
    fail(child(path, "node"), "not used by load_factor");
  }
  if (with_dof) {
    if (!r.contains("dof") || !r["dof"].is_string()) fail(child(path, "dof"), "missing (required for " + quantity + ": ux, uy or rz)");
    const std::string dof = r["dof"].get<std::string>();
    out.dof = dof == "ux" ? 0 : dof == "uy" ? 1 : dof == "rz" ? 2 : -1;
    if (out.dof < 0) fail(child(path, "dof"), "unknown dof \"" + dof + "\" (expected ux, uy or rz)");
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

/// A node reference of a record (an id, or coordinates within 1e-9 of the model's size, as in
/// the model file) in one case's model.
int resolve_node(const Model& model, const json& ref, const std::string& path) {
  if (ref.is_number_integer()) {
    const int index = model.node_index(ref.get<int>());
    if (index < 0) fail(path, "unknown node " + ref.dump());
    return index;
  }
  std::string problem;
  const int found = node_at(model, Eigen::Vector2d(ref[0].get<double>(), ref[1].get<double>()), problem);
  if (found < 0) fail(path, problem);
  return found;
}

}  // namespace

size_t Study::case_count() const {
  size_t n = 1;
  for (const Parameter& p : parameters) n *= p.labels.size();
  return n;
}

Study read_study(const json& doc, const std::string& directory) {
  if (!doc.is_object()) fail("", "a study file is a JSON object");
  check_keys(doc, "", {"format", "title", "model", "model_file", "sweep", "record", "keep"});
  if (doc.contains("format") && doc["format"] != "tsmframe-study/1") fail("format", "unsupported format (expected \"tsmframe-study/1\")");
  Study s;
  if (doc.contains("title")) {
    if (!doc["title"].is_string()) fail("title", "expected a string");
    s.title = doc["title"].get<std::string>();
  }
  if (doc.contains("model") == doc.contains("model_file")) fail("model", "give exactly one of \"model\" and \"model_file\"");
  if (doc.contains("model")) {
    s.model = doc["model"];
    if (!s.model.is_object()) fail("model", "expected the model as an object (FORMAT.md)");
  } else {
    if (!doc["model_file"].is_string()) fail("model_file", "expected a file name");
    const std::filesystem::path file = std::filesystem::path(directory) / doc["model_file"].get<std::string>();
    std::ifstream in(file);
    if (!in) fail("model_file", "cannot read " + file.string());
    try {
      s.model = json::parse(in);
    } catch (const json::exception& e) {
      fail("model_file", file.string() + ": invalid JSON (" + std::string(e.what()) + ")");
    }
  }
  if (!doc.contains("sweep") || !doc["sweep"].is_array() || doc["sweep"].empty())
    fail("sweep", "missing (required: a non-empty array of parameters)");
  // Every column of study.csv has a name of its own: the fixed ones, the parameters', the records'.
  std::set<std::string> names = {"case", "message"};
  names.insert(std::begin(run_columns), std::end(run_columns));
  names.insert(std::begin(contact_columns), std::end(contact_columns));
  for (size_t k = 0; k < doc["sweep"].size(); ++k) {
    s.parameters.push_back(read_parameter(doc["sweep"][k], child("sweep", k)));
    if (!names.insert(s.parameters.back().name).second)
      fail(child(child("sweep", k), "name"), "\"" + s.parameters.back().name + "\" names another column already");
  }
  if (s.case_count() > 1000000) fail("sweep", "more than a million cases");
  if (doc.contains("record")) {
    if (!doc["record"].is_array()) fail("record", "expected an array of {\"name\": …, \"quantity\": …}");
    for (size_t k = 0; k < doc["record"].size(); ++k) {
      s.records.push_back(read_record(doc["record"][k], child("record", k)));
      if (!names.insert(s.records.back().name).second)
        fail(child(child("record", k), "name"), "\"" + s.records.back().name + "\" names another column already");
    }
  }
  if (doc.contains("keep")) {
    if (!doc["keep"].is_boolean()) fail("keep", "expected true or false");
    s.keep = doc["keep"].get<bool>();
  }
  return s;
}

Study read_study_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail("", "cannot open the study file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception& e) {
    fail("", std::string("invalid JSON: ") + e.what());
  }
  return read_study(doc, std::filesystem::path(path).parent_path().string());
}

std::vector<size_t> case_choice(const Study& study, size_t index) {
  std::vector<size_t> choice(study.parameters.size());
  for (size_t p = study.parameters.size(); p-- > 0;) {
    const size_t n = study.parameters[p].labels.size();
    choice[p] = index % n;
    index /= n;
  }
  return choice;
}

json case_model(const Study& study, const std::vector<size_t>& choice) {
  json m = study.model;
  for (size_t p = 0; p < study.parameters.size(); ++p)
    for (const auto& [ptr, value] : study.parameters[p].assignments[choice[p]]) m[json::json_pointer(ptr)] = value;
  return m;
}

namespace {

CaseResult run_case(const Study& study, size_t index, const std::string& keep_directory) {
  CaseResult row;
  row.index = index;
  row.choice = case_choice(study, index);
  const auto start = std::chrono::steady_clock::now();
  Model model;
  try {
    model = io::read_model(case_model(study, row.choice));
  } catch (const InputError& e) {
    row.status = "bad-input";
    row.message = e.what();
    return row;
  } catch (const json::exception& e) {
    row.status = "bad-input";
    row.message = e.what();
    return row;
  }
  // The records' nodes (and contacts) in this case's model, then their values at every converged
  // step (by step number: an arc-length step landing on its target replaces the one before).
  struct Resolved {
    int node = -1, contact = -1;
  };
  std::vector<Resolved> resolved(study.records.size());
  try {
    for (size_t r = 0; r < study.records.size(); ++r) {
      const Record& record = study.records[r];
      if (record.node.is_null()) continue;
      const std::string path = child(record.path, "node");
      resolved[r].node = resolve_node(model, record.node, path);
      const int id = model.nodes[resolved[r].node].id;
      if (record.quantity == Record::Quantity::contact_force || record.quantity == Record::Quantity::contact_xi) {
        for (size_t c = 0; c < model.contacts.size(); ++c)
          if (model.contacts[c].node == resolved[r].node) resolved[r].contact = static_cast<int>(c);
        if (resolved[r].contact < 0) fail(path, "node " + std::to_string(id) + " is no contact node");
      }
      if (record.quantity == Record::Quantity::reaction && !model.constrained[dofs_per_node * resolved[r].node + record.dof])
        fail(child(record.path, "dof"), "node " + std::to_string(id) + "'s " + (record.dof == 0 ? "ux" : record.dof == 1 ? "uy" : "rz") +
                                            " is free: it has no reaction");
    }
  } catch (const InputError& e) {
    row.status = "bad-input";
    row.message = e.what();
    return row;
  }
  std::vector<std::vector<std::pair<int, double>>> values(study.records.size());
  solver::StepObserver observer;
  if (!study.records.empty())
    observer = [&](const solver::StepRecord& step) {
      if (!step.converged) return;
      for (size_t r = 0; r < study.records.size(); ++r) {
        const Record& record = study.records[r];
        const int dof = dofs_per_node * resolved[r].node + record.dof;
        double v = NAN;
        switch (record.quantity) {
          case Record::Quantity::displacement: v = step.displacements[dof]; break;
          case Record::Quantity::reaction: v = step.reactions[dof]; break;
          case Record::Quantity::contact_force: {
            const solver::ContactPoint& c = step.contacts[resolved[r].contact];
            v = c.element >= 0 ? c.force : 0.0;
            break;
          }
          case Record::Quantity::contact_xi: {
            const solver::ContactPoint& c = step.contacts[resolved[r].contact];
            if (c.element >= 0) v = c.alpha;
            break;
          }
          case Record::Quantity::load_factor: v = step.load_factor; break;
        }
        auto& list = values[r];
        while (!list.empty() && list.back().first >= step.step) list.pop_back();
        list.emplace_back(step.step, v);
      }
    };
  const solver::RunResult result = solver::run_analysis(model, observer);
  row.recorded.assign(study.records.size(), NAN);
  for (size_t r = 0; r < study.records.size(); ++r) {
    const auto& list = values[r];
    if (list.empty()) continue;
    double& out = row.recorded[r];
    for (const auto& [step, v] : list) {
      if (std::isnan(v)) continue;
      switch (study.records[r].of) {
        case Record::Of::last: break;
        case Record::Of::max: out = std::isnan(out) ? v : std::max(out, v); break;
        case Record::Of::min: out = std::isnan(out) ? v : std::min(out, v); break;
        case Record::Of::max_abs: out = std::isnan(out) ? std::abs(v) : std::max(out, std::abs(v)); break;
      }
    }
    if (study.records[r].of == Record::Of::last) out = list.back().second;
  }
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  row.status = solver::status_name(result.status);
  row.converged = result.status == solver::Status::converged;
  row.message = result.message;
  for (const solver::StepRecord& s : result.steps) {
    row.iterations += s.iterations;
    row.last_iterations = s.iterations;
    if (!s.converged) continue;
    ++row.steps;
    row.load_factor = s.load_factor;
    if (s.contacts.empty() || s.contacts[0].element < 0) continue;
    const int element = s.contacts[0].element;
    if (row.contact_first_element == 0) row.contact_first_element = model.elements[element].id;
    if (model.elements[element].id == row.contact_first_element)
      row.contact_max_alpha_first = std::max(row.contact_max_alpha_first, s.contacts[0].alpha);
    if (row.contact_last_element != 0 && model.elements[element].id != row.contact_last_element) ++row.contact_elements_passed;
    row.contact_last_element = model.elements[element].id;
  }
  if (!keep_directory.empty()) {
    try {
      io::write_results((std::filesystem::path(keep_directory) / "cases" / std::to_string(index + 1)).string(), model, result);
    } catch (const std::exception& e) {
      row.message += std::string(row.message.empty() ? "" : "; ") + "results not kept: " + e.what();
    }
  }
  return row;
}

}  // namespace

std::vector<CaseResult> run_study(const Study& study, int threads, const std::string& keep_directory,
                                  const std::function<void(const CaseResult&)>& progress) {
  const size_t n = study.case_count();
  std::vector<CaseResult> rows(n);
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = static_cast<int>(std::min<size_t>(threads, n));
  // Big cases first would balance better; cases are independent, so a shared counter suffices.
  std::atomic<size_t> next{0};
  std::mutex report;
  auto worker = [&] {
    // Each case on one thread: the cases share the cores. (A thread's OpenMP setting is its own:
    // the caller's omp_set_num_threads does not reach the pool's threads, whose cases opened
    // two-thread teams on two busy cores.)
    omp_set_num_threads(1);
    for (size_t k; (k = next.fetch_add(1)) < n;) {
      rows[k] = run_case(study, k, study.keep ? keep_directory : std::string());
      if (progress) {
        std::lock_guard<std::mutex> lock(report);
        progress(rows[k]);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  const int callers = omp_get_max_threads();  // the calling thread works too: its setting back after
  worker();
  omp_set_num_threads(callers);
  for (std::thread& t : pool) t.join();
  return rows;
}

namespace {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return quoted + "\"";
}

}  // namespace

void write_study_json(std::ostream& out, const Study& study, const std::vector<CaseResult>& rows) {
  const bool contacts = !study.model.value("contacts", json::array()).empty();
  io::JsonWriter w(out);
  w.begin_object();
  w.key("format").value("tsmframe-study-results/1");
  w.key("title").value(study.title);
  w.key("parameters").begin_array();
  for (const Parameter& p : study.parameters) {
    w.newline().begin_object().key("name").value(p.name).key("values").begin_array();
    for (const std::string& l : p.labels) w.value(l);
    w.end_array().end_object();
  }
  w.end_array();
  w.newline().key("cases").begin_array();
  for (const CaseResult& r : rows) {
    w.newline().begin_object();
    w.key("case").value(static_cast<int>(r.index + 1));
    for (size_t p = 0; p < study.parameters.size(); ++p) w.key(study.parameters[p].name).value(study.parameters[p].labels[r.choice[p]]);
    w.key("status").value(r.status).key("converged").value(r.converged).key("steps").value(r.steps);
    w.key("iterations").value(r.iterations).key("last_iterations").value(r.last_iterations);
    w.key("load_factor").value(r.load_factor).key("seconds").value(r.seconds);
    if (contacts) {
      w.key("contact_first_element").value(r.contact_first_element);
      w.key("contact_max_alpha_first").value(r.contact_max_alpha_first);
      w.key("contact_last_element").value(r.contact_last_element);
      w.key("contact_elements_passed").value(r.contact_elements_passed);
    }
    for (size_t k = 0; k < study.records.size(); ++k)  // null where the case has no value
      w.key(study.records[k].name).value(k < r.recorded.size() ? r.recorded[k] : NAN);
    w.key("message").value(r.message);
    w.end_object();
  }
  w.end_array();
  w.newline().end_object();
  out << '\n';
}

void write_study(const std::string& directory, const Study& study, const std::vector<CaseResult>& rows) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) throw std::runtime_error(directory + ": cannot create the output directory: " + error.message());
  const bool contacts = !study.model.value("contacts", json::array()).empty();
  auto write_csv = [&](std::ostream& out) {
    out << "case";
    for (const Parameter& p : study.parameters) out << ',' << csv_field(p.name);
    for (const char* column : run_columns) out << ',' << column;
    if (contacts)
      for (const char* column : contact_columns) out << ',' << column;
    for (const Record& record : study.records) out << ',' << csv_field(record.name);
    out << ",message\n";
    for (const CaseResult& r : rows) {
      out << r.index + 1;
      for (size_t p = 0; p < study.parameters.size(); ++p) out << ',' << csv_field(study.parameters[p].labels[r.choice[p]]);
      out << ',' << r.status << ',' << (r.converged ? "true" : "false") << ',' << r.steps << ',' << r.iterations << ','
          << r.last_iterations << ',' << io::format_number(r.load_factor) << ',' << io::format_number(r.seconds);
      if (contacts)
        out << ',' << r.contact_first_element << ',' << io::format_number(r.contact_max_alpha_first) << ','
            << r.contact_last_element << ',' << r.contact_elements_passed;
      for (size_t k = 0; k < study.records.size(); ++k)  // empty where the case has no value
        out << ',' << (k < r.recorded.size() && !std::isnan(r.recorded[k]) ? io::format_number(r.recorded[k]) : std::string());
      out << ',' << csv_field(r.message) << '\n';
    }
  };
  const std::filesystem::path dir(directory);
  auto write_json = [&](std::ostream& out) { write_study_json(out, study, rows); };
  io::write_files_atomically({{(dir / "study.csv").string(), write_csv}, {(dir / "study.json").string(), write_json}});
}

}  // namespace tsm::study
