#include "tsmframe/study/assignment.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <map>
#include <set>
#include <system_error>

#include "tsmframe/io/json_input.hpp"

namespace tsm::study {
namespace {

using nlohmann::json;

/// The pointer's reference tokens, unescaped, from the root.
std::vector<std::string> tokens(const std::string& pointer) {
  json::json_pointer p(pointer);
  std::vector<std::string> out;
  for (; !p.empty(); p.pop_back()) out.push_back(p.back());
  std::reverse(out.begin(), out.end());
  return out;
}

/// A list index as RFC 6901 writes it (digits, no leading zero; "-" is one past the end), or
/// nothing. An index past what 64 bits hold reads as the largest: past any list's end.
std::optional<size_t> list_index(const std::string& token, size_t size) {
  if (token == "-") return size;
  if (token.empty() || (token.size() > 1 && token[0] == '0')) return std::nullopt;
  if (!std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; })) return std::nullopt;
  size_t index = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), index);
  return error == std::errc::result_out_of_range ? SIZE_MAX : index;
}

std::string entries(size_t size) { return std::to_string(size) + (size == 1 ? " entry" : " entries"); }

/// The pointer text (escaped) of the first `count` tokens, quoted.
std::string prefix_text(const std::vector<std::string>& path, size_t count) {
  json::json_pointer p;
  for (size_t k = 0; k < count; ++k) p.push_back(path[k]);
  return io::quote_text(p.to_string());
}

/// Why the places a pointer makes below a new key (path[k]) would be more than one value each:
/// nlohmann makes a missing value an object where the next token is a key, and a list where it
/// is a number or "-" — holding the entries up to that index (4·10⁹ nulls for "4000000000";
/// none past what 64 bits hold, an exception) — so a new list may only be given its first
/// entry ("0" or "-").
std::optional<std::string> new_places(const std::vector<std::string>& path, size_t k) {
  for (size_t j = k + 1; j < path.size(); ++j) {
    const std::string& token = path[j];
    const bool makes_list = token == "-" || std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (makes_list && token != "0" && token != "-")
      return prefix_text(path, j) + " is new: it would be made a list, where " + (token.empty() ? "\"\"" : token) +
             " is past the end of its one entry (0 or \"-\" makes it)";
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> unassignable(const json& model, const std::string& pointer) {
  const std::vector<std::string> path = tokens(pointer);
  const json* at = &model;
  for (size_t k = 0; k < path.size(); ++k) {
    const bool last = k + 1 == path.size();
    const std::string& token = path[k];
    if (at->is_object()) {
      if (!at->contains(token)) return new_places(path, k);
      at = &(*at)[token];
      continue;
    }
    const std::string parent = k == 0 ? std::string("the model") : prefix_text(path, k);
    if (!at->is_array()) return parent + " is " + io::type_name(*at) + ": it has no " + io::quote_text(token);
    const size_t size = at->size();
    const std::optional<size_t> index = list_index(token, size);
    if (!index) return parent + " is a list: " + io::quote_text(token) + " is no index of it (0, 1, …)";
    if (*index > size || (!last && *index == size)) {
      const std::string appends = last ? std::to_string(size) + " appends one" : "";
      if (size == 0) return parent + " is an empty list: " + token + " is past its end" + (last ? " (" + appends + ")" : "");
      const std::string names = size == 1 ? "0 names it" : "0 to " + std::to_string(size - 1) + " name them";
      return parent + " has " + entries(size) + ": " + token + " is past its end (" + names + (last ? ", " + appends : "") + ")";
    }
    if (last) return std::nullopt;
    at = &(*at)[*index];
  }
  return std::nullopt;
}

void assign(json& model, const Assignment& assignment) {
  if (auto why = unassignable(model, assignment.pointer)) io::fail(assignment.path, *why);
  model[json::json_pointer(assignment.pointer)] = assignment.value;
}

void check_assignments(const json& model, const std::vector<const Assignment*>& assignments) {
  std::vector<const Assignment*> distinct;  // the first to give each pointer, in the study's order
  std::set<std::string> pointers;
  for (const Assignment* a : assignments)
    if (pointers.insert(a->pointer).second) distinct.push_back(a);
  const auto parent_of = [](const std::string& pointer) { return pointer.substr(0, pointer.rfind('/')); };
  std::map<std::string, int> children;  // parent pointer → how many distinct pointers set a child of it
  for (const Assignment* a : distinct) ++children[parent_of(a->pointer)];
  for (const Assignment* a : distinct) {
    // Tokens are escaped ('/' is "~1"), so the text before any '/' is an ancestor's pointer.
    const std::string parent = parent_of(a->pointer);
    bool changeable = children[parent] > 1;
    for (size_t end = parent.size(); !changeable && end > 0 && end != std::string::npos; end = parent.rfind('/', end - 1))
      changeable = pointers.count(parent.substr(0, end)) > 0;
    if (changeable) continue;
    if (auto why = unassignable(model, a->pointer)) io::fail(a->path, *why);
  }
}

}  // namespace tsm::study
