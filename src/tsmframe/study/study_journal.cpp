#include "tsmframe/study/study_journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <system_error>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/output_directory.hpp"
#include "tsmframe/io/system_error.hpp"

namespace tsm::study {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr const char* journal_format = "tsmframe-study-rows/1";

json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

double number_from(const json& x) { return x.is_null() ? std::numeric_limits<double>::quiet_NaN() : x.get<double>(); }

std::int64_t now_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Writes all of `text` to `fd`; throws io::SystemError (`path`) where the system refuses.
void write_all(int fd, const std::string& text, const fs::path& path) {
  for (size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw io::SystemError(path.string(), io::os_reason(errno));
    done += static_cast<size_t>(n);
  }
}

/// One line's text: invalid UTF-8 in a message (a model's key, quoted) replaced, not thrown on.
std::string line_text(const json& value) { return value.dump(-1, ' ', false, json::error_handler_t::replace) + '\n'; }

json header(const Study& study) {
  return {{"format", journal_format}, {"study", study.fingerprint}, {"cases", study.case_count()}};
}

}  // namespace

json row_json(const CaseResult& row) {
  json recorded = json::array();
  for (const double x : row.recorded) recorded.push_back(number(x));
  return {{"case", row.index + 1},
          {"status", row.status},
          {"converged", row.converged},
          {"steps", row.steps},
          {"iterations", row.iterations},
          {"last_iterations", row.last_iterations},
          {"load_factor", number(row.load_factor)},
          {"negative_eigenvalues", row.negative_eigenvalues},
          {"notes", row.notes},
          {"seconds", number(row.seconds)},
          {"message", row.message},
          {"contact", {row.contact_first_element, number(row.contact_max_alpha_first), row.contact_last_element, row.contact_elements_passed}},
          {"recorded", recorded}};
}

std::string journal_lines(const std::vector<CaseResult>& rows) {
  std::string text;
  for (const CaseResult& row : rows)
    if (row.status != "interrupted") text += line_text(row_json(row));
  return text;
}

std::optional<CaseResult> row_from_json(const json& line, const Study& study) {
  try {
    CaseResult row;
    const size_t number_of_case = line.at("case").get<size_t>();
    if (number_of_case < 1 || number_of_case > study.case_count()) return std::nullopt;
    row.index = number_of_case - 1;
    row.choice = case_choice(study, row.index);
    row.status = line.at("status").get<std::string>();
    row.converged = line.at("converged").get<bool>();
    row.steps = line.at("steps").get<int>();
    row.iterations = line.at("iterations").get<int>();
    row.last_iterations = line.at("last_iterations").get<int>();
    row.load_factor = number_from(line.at("load_factor"));
    row.negative_eigenvalues = line.at("negative_eigenvalues").get<int>();
    row.notes = line.at("notes").get<std::string>();
    row.seconds = number_from(line.at("seconds"));
    row.message = line.at("message").get<std::string>();
    const json& contact = line.at("contact");
    row.contact_first_element = contact.at(0).get<int>();
    row.contact_max_alpha_first = number_from(contact.at(1));
    row.contact_last_element = contact.at(2).get<int>();
    row.contact_elements_passed = contact.at(3).get<int>();
    const json& recorded = line.at("recorded");
    if (!recorded.is_array() || recorded.size() != study.records.size()) return std::nullopt;
    for (const json& x : recorded) row.recorded.push_back(number_from(x));
    if (row.status == "interrupted") return std::nullopt;
    return row;
  } catch (const json::exception&) {
    return std::nullopt;
  }
}

JournalRows read_journal(const fs::path& path, const Study& study) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw io::SystemError(path.string(), "cannot be read");
  std::string line;
  json head;
  if (std::getline(in, line)) head = json::parse(line, nullptr, false);
  if (!head.is_object() || head.value("format", "") != journal_format)
    throw io::InputError(path.string(), "is no study journal (" + std::string(journal_format) + ")");
  if (head.value("study", "") != study.fingerprint)
    throw io::InputError(path.string(), "holds the rows of another study (the study file, its model or tsmframe changed since it ran)");
  JournalRows journal;
  std::set<size_t> have;
  while (std::getline(in, line)) {
    if (in.eof()) {  // no newline: a line cut short
      ++journal.skipped;
      break;
    }
    const json parsed = json::parse(line, nullptr, false);
    std::optional<CaseResult> row = parsed.is_discarded() ? std::nullopt : row_from_json(parsed, study);
    if (!row || !have.insert(row->index).second) {
      ++journal.skipped;
      continue;
    }
    journal.rows.push_back(std::move(*row));
  }
  std::sort(journal.rows.begin(), journal.rows.end(), [](const CaseResult& a, const CaseResult& b) { return a.index < b.index; });
  return journal;
}

std::optional<ResumePoint> find_resume_point(const std::string& out, const Study& study) {
  for (const fs::path& dead : io::dead_temporaries(out))
    if (fs::exists(dead / journal_name)) return ResumePoint{dead, true, read_journal(dead / journal_name, study)};
  if (fs::exists(fs::path(out) / journal_name)) return ResumePoint{out, false, read_journal(fs::path(out) / journal_name, study)};
  return std::nullopt;
}

StudyJournal::StudyJournal(const fs::path& path, const Study& study, const std::vector<CaseResult>& rows) : path_(path) {
  const fs::path fresh = path.string() + ".new";
  fd_ = ::open(fresh.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) throw io::SystemError(fresh.string(), io::os_reason(errno));
  const std::string text = line_text(header(study)) + journal_lines(rows);
  write_all(fd_, text, fresh);
  if (::fdatasync(fd_) != 0 || ::rename(fresh.c_str(), path.c_str()) != 0) {
    const int failure = errno;
    ::close(fd_), fd_ = -1;
    throw io::SystemError(path.string(), io::os_reason(failure));
  }
  last_sync_ = now_ms();
}

StudyJournal::~StudyJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void StudyJournal::append(const CaseResult& row) {
  const std::string line = journal_lines({row});
  if (line.empty()) return;  // a stopped case
  write_all(fd_, line, path_);
  if (now_ms() - last_sync_ < 1000) return;
  ::fdatasync(fd_);  // the disk: a lost machine loses a second's rows at most
  last_sync_ = now_ms();
}

}  // namespace tsm::study
