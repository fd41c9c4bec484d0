#include "tsmframe/study/study_runner.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <mutex>
#include <new>
#include <thread>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/memory_budget.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/io/results_writer.hpp"
#include "tsmframe/io/system_error.hpp"
#include "tsmframe/solver/analysis.hpp"

namespace tsm::study {

using nlohmann::json;

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
    for (const Assignment& a : study.parameters[p].assignments[choice[p]]) assign(m, a);
  return m;
}

std::optional<std::string> invalid_in_every_case(const Study& study) {
  const auto refusal = [&](size_t index) -> std::optional<std::string> {
    try {
      io::read_model(case_model(study, case_choice(study, index)));
    } catch (const io::InputError& e) {
      return std::string(e.what());
    } catch (const io::SystemError&) {  // memory a case may lack is its own row's to say
    }
    return std::nullopt;
  };
  const size_t cases = study.case_count();
  if (cases == 0) return std::nullopt;
  const std::optional<std::string> first = refusal(0);
  if (!first || (cases > 1 && refusal(cases - 1) != first)) return std::nullopt;
  return "model: " + *first + " (in the first and the last case alike: no parameter of the sweep mends it)";
}

namespace {

/// A record's node and contact (an index into the model's contacts) in one case's model.
struct ResolvedRecord {
  int node = -1, contact = -1;
};

/// A record's node in one case's model: by id, or the one node at its coordinates (as in a model file).
int resolve_record_node(const Model& model, const io::NodeReference& node, const std::string& path) {
  return io::resolve_node(node, path, model, [&](long id) { return id == static_cast<int>(id) ? model.node_index(static_cast<int>(id)) : -1; });
}

/// The records' nodes (and contacts) in this case's model; throws io::InputError where the case has none.
std::vector<ResolvedRecord> resolve_records(const Study& study, const Model& model) {
  std::vector<ResolvedRecord> resolved(study.records.size());
  for (size_t r = 0; r < study.records.size(); ++r) {
    const Record& record = study.records[r];
    if (!record.node) continue;
    const std::string path = io::child(record.path, "node");
    resolved[r].node = resolve_record_node(model, *record.node, path);
    const int id = model.nodes[resolved[r].node].id;
    if (record.quantity == Record::Quantity::contact_force || record.quantity == Record::Quantity::contact_xi) {
      for (size_t c = 0; c < model.contacts.size(); ++c)
        if (model.contacts[c].node == resolved[r].node) resolved[r].contact = static_cast<int>(c);
      if (resolved[r].contact < 0) io::fail(path, "node " + std::to_string(id) + " is no contact node");
    }
    if (record.quantity == Record::Quantity::reaction && !model.constrained[dofs_per_node * resolved[r].node + record.dof])
      io::fail(io::child(record.path, "dof"), "node " + std::to_string(id) + "'s " + dof_name(record.dof) + " is free: it has no reaction");
  }
  return resolved;
}

/// A record's value at a converged step; NaN where there is none (a contact not touching: its xi).
double record_value(const Record& record, const ResolvedRecord& resolved, const solver::StepRecord& step) {
  const int dof = dofs_per_node * resolved.node + record.dof;
  switch (record.quantity) {
    case Record::Quantity::displacement: return step.displacements[dof];
    case Record::Quantity::reaction: return step.reactions[dof];
    case Record::Quantity::contact_force: {
      const solver::ContactPoint& c = step.contacts[resolved.contact];
      return c.element >= 0 ? c.force : 0.0;
    }
    case Record::Quantity::contact_xi: {
      const solver::ContactPoint& c = step.contacts[resolved.contact];
      return c.element >= 0 ? c.alpha : NAN;
    }
    case Record::Quantity::load_factor: return step.load_factor;
  }
  return NAN;
}

/// A record's values at the converged steps: (step, value).
using StepValues = std::vector<std::pair<int, double>>;

/// An observer keeping each record's value at every converged step, by step number: an
/// arc-length step landing on its target replaces the one before. None without records.
solver::StepObserver record_observer(const Study& study, const std::vector<ResolvedRecord>& resolved,
                                     std::vector<StepValues>& values) {
  if (study.records.empty()) return {};
  return [&study, &resolved, &values](const solver::StepRecord& step) {
    if (!step.converged) return;
    for (size_t r = 0; r < study.records.size(); ++r) {
      StepValues& list = values[r];
      while (!list.empty() && list.back().first >= step.step) list.pop_back();
      list.emplace_back(step.step, record_value(study.records[r], resolved[r], step));
    }
  };
}

/// A record's column from its values at the converged steps: the last, or the extreme over
/// them; NaN where there is none.
double recorded(Record::Of of, const StepValues& list) {
  if (list.empty()) return NAN;
  if (of == Record::Of::last) return list.back().second;
  double out = NAN;
  for (const auto& [step, v] : list) {
    if (std::isnan(v)) continue;
    switch (of) {
      case Record::Of::last: break;
      case Record::Of::max: out = std::isnan(out) ? v : std::max(out, v); break;
      case Record::Of::min: out = std::isnan(out) ? v : std::min(out, v); break;
      case Record::Of::max_abs: out = std::isnan(out) ? std::abs(v) : std::max(out, std::abs(v)); break;
    }
  }
  return out;
}

/// The row's run columns and the first contact's story, from the run's steps.
void summarise_run(const Model& model, const solver::RunResult& result, CaseResult& row) {
  row.status = solver::status_name(result.status);
  row.converged = result.status == solver::Status::converged;
  row.message = result.message;
  for (const std::string& note : result.notes) row.notes += (row.notes.empty() ? "" : " ") + note;
  for (const solver::StepRecord& s : result.steps) {
    row.iterations += s.iterations;
    row.last_iterations = s.iterations;
    if (!s.converged) continue;
    ++row.steps;
    row.load_factor = s.load_factor;
    row.negative_eigenvalues = s.negative_eigenvalues;
    if (s.contacts.empty() || s.contacts[0].element < 0) continue;
    const int element = model.elements[s.contacts[0].element].id;
    if (row.contact_first_element == 0) row.contact_first_element = element;
    if (element == row.contact_first_element) row.contact_max_alpha_first = std::max(row.contact_max_alpha_first, s.contacts[0].alpha);
    if (row.contact_last_element != 0 && element != row.contact_last_element) ++row.contact_elements_passed;
    row.contact_last_element = element;
  }
}

/// The row of a case that could not be run: status "bad-input", the reason its message.
CaseResult bad_input_row(const Study& study, size_t index, const std::string& message) {
  CaseResult row;
  row.index = index;
  row.choice = case_choice(study, index);
  row.status = "bad-input";
  row.message = message;
  return row;
}

/// The case's results.json and steps.csv under `directory`/cases/<case>/ (io::SystemError where
/// the system fails: the study stops).
void keep_results(const std::string& directory, const Model& model, const solver::RunResult& result, const CaseResult& row) {
  io::write_results((std::filesystem::path(directory) / "cases" / std::to_string(row.index + 1)).string(), model, result);
}

/// Case `index`, its model held to `budget` (the case's share of the machine's memory).
CaseResult run_case(const Study& study, size_t index, const std::string& keep_directory, const solver::StopRequest* stop,
                    const io::MemoryBudget& budget) {
  const auto start = std::chrono::steady_clock::now();
  Model model;
  std::vector<ResolvedRecord> resolved;
  try {
    model = io::read_model(case_model(study, case_choice(study, index)), budget);
    resolved = resolve_records(study, model);
  } catch (const io::InputError& e) {
    return bad_input_row(study, index, e.what());
  } catch (const io::MemoryShortage& e) {  // a case whose run would not fit its share: a row, as running out of memory is
    return bad_input_row(study, index, e.what());
  } catch (const json::exception& e) {
    return bad_input_row(study, index, e.what());
  }
  std::vector<StepValues> values(study.records.size());
  const solver::RunResult result = solver::run_analysis(model, record_observer(study, resolved, values), stop);
  CaseResult row;
  row.index = index;
  row.choice = case_choice(study, index);
  for (size_t r = 0; r < study.records.size(); ++r) row.recorded.push_back(recorded(study.records[r].of, values[r]));
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summarise_run(model, result, row);
  if (!keep_directory.empty()) keep_results(keep_directory, model, result, row);
  return row;
}

/// run_case, with whatever else it throws made the case's row: a case that runs out of memory
/// (std::bad_alloc in its reader or its analysis) must neither end the sweep nor escape its
/// thread, where it ends the program (std::terminate). A SystemError (its results cannot be kept)
/// is no fault of the case: it goes on, to end the study.
CaseResult run_case_caught(const Study& study, size_t index, const std::string& keep_directory,
                           const solver::StopRequest* stop, const io::MemoryBudget& budget) {
  try {
    return run_case(study, index, keep_directory, stop, budget);
  } catch (const io::SystemError&) {
    throw;
  } catch (const std::bad_alloc& e) {
    return bad_input_row(study, index, std::string("the case ran out of memory (") + e.what() + ")");
  } catch (const std::exception& e) {
    return bad_input_row(study, index, std::string("the case could not be run: ") + e.what());
  }
}

/// The threads to run `cases` cases on: `threads` (0: all cores), no more than there are cases
/// (one at least: the caller's).
int thread_count(int threads, size_t cases) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return static_cast<int>(std::max<size_t>(1, std::min<size_t>(threads, cases)));
}

}  // namespace

std::vector<CaseResult> run_study(const Study& study, int threads, const std::string& keep_directory,
                                  const std::function<void(const CaseResult&)>& progress, const solver::StopRequest* stop,
                                  std::vector<CaseResult> done, const StudyShard& shard) {
  const size_t n = study.case_count();
  std::vector<CaseResult> rows(n);
  std::vector<char> ran(n, 0);
  for (CaseResult& row : done)
    if (row.index < n) ran[row.index] = 1, rows[row.index] = std::move(row);
  const std::string keep = study.keep ? keep_directory : std::string();
  // The machine's memory as the study starts, shared by the cases run at once.
  const io::MemoryBudget budget = io::memory_budget(thread_count(threads, shard.cases(n)));
  // Big cases first would balance better; cases are independent, so a shared counter suffices.
  std::atomic<size_t> next{0};
  std::mutex report;
  std::exception_ptr failure;  // what `progress` threw, rethrown on the calling thread after the join
  auto worker = [&] {
    // Each case on one thread: the cases share the cores. (A thread's OpenMP setting is its own:
    // the caller's omp_set_num_threads does not reach the pool's threads.)
    omp_set_num_threads(1);
    try {
      for (size_t k; !solver::stop_requested(stop) && (k = next.fetch_add(1)) < n;) {
        if (ran[k] || !shard.holds(k)) continue;  // done before, or another shard's
        rows[k] = run_case_caught(study, k, keep, stop, budget);
        ran[k] = 1;
        if (!progress) continue;
        std::lock_guard<std::mutex> lock(report);
        progress(rows[k]);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(report);
      if (!failure) failure = std::current_exception();
      next = n;  // the other threads stop after their case
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < thread_count(threads, shard.cases(n)); ++t) pool.emplace_back(worker);
  const int callers = omp_get_max_threads();  // the calling thread works too: its setting back after
  worker();
  omp_set_num_threads(callers);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  if (std::find(ran.begin(), ran.end(), 0) == ran.end()) return rows;
  std::vector<CaseResult> kept;  // stopped on request: the rows of the cases run and done
  for (size_t k = 0; k < n; ++k)
    if (ran[k]) kept.push_back(std::move(rows[k]));
  return kept;
}

}  // namespace tsm::study
