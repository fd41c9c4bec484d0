#include "json_mutator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace tsm::fuzz {

using nlohmann::json;

namespace {

constexpr size_t most_words = 256;       // of one document, beside the format's
constexpr size_t longest_word = 64;

/// Values at the edges of what the readers accept or what the types hold.
const std::vector<json>& limits() {
  static const std::vector<json> values = {
      0, 1, -1, 2, 3, 7, 255, 256, 65536,
      std::numeric_limits<std::int32_t>::max(), std::int64_t{1} << 31, std::numeric_limits<std::int32_t>::min(),
      -(std::int64_t{1} << 31) - 1, std::int64_t{1} << 32, std::int64_t{1} << 53, (std::int64_t{1} << 53) + 1,
      std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::min(),
      std::numeric_limits<std::uint64_t>::max(), 4000000000u, 100000000,
      1e50, -1e50, 1.0000001e50, 1e308, -1e308, 5e-324, 1e-300, 0.5, -0.5, 1e-8, 1e15, 9e15};
  return values;
}

/// Tokens that make a JSON pointer's list index interesting: the ends of a list and past them.
const std::vector<std::string>& index_tokens() {
  static const std::vector<std::string> tokens = {"0", "1", "2", "3", "-", "01", "4000000000", "100000000",
                                                  "18446744073709551615", "18446744073709551616",
                                                  "99999999999999999999999"};
  return tokens;
}

bool is_index(const std::string& token) {
  return token == "-" || (!token.empty() && std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; }));
}

}  // namespace

JsonMutator::JsonMutator(std::uint32_t seed, std::vector<std::string> words)
    : random_(seed), format_words_(std::move(words)) {
  if (format_words_.empty()) format_words_.push_back("x");
}

std::vector<JsonMutator::Place> JsonMutator::walk(json& document) {
  std::vector<Place> places{{&document, -1, nullptr}};
  words_ = format_words_;
  const size_t format_count = words_.size();
  const auto remember = [&](const std::string& text) {
    if (words_.size() - format_count < most_words && text.size() <= longest_word) words_.push_back(text);
  };
  for (size_t k = 0; k < places.size(); ++k) {  // breadth first: places grows behind k
    json& value = *places[k].value;
    if (value.is_object()) {
      for (auto it = value.begin(); it != value.end(); ++it) {
        places.push_back({&it.value(), static_cast<int>(k), &it.key()});
        remember(it.key());
      }
    } else if (value.is_array()) {
      for (json& entry : value) places.push_back({&entry, static_cast<int>(k), nullptr});
    } else if (value.is_string()) {
      remember(value.get_ref<const std::string&>());
    }
  }
  return places;
}

bool JsonMutator::encloses(const std::vector<Place>& places, int outer, int inner) const {
  for (int at = inner; at >= 0; at = places[at].parent)
    if (at == outer) return true;
  return false;
}

const std::string& JsonMutator::word() { return words_[below(words_.size())]; }

json JsonMutator::other_type_scalar(const json& value) {
  const json choices[] = {nullptr, true, false, 0, 1, -1, 0.5, "", word(), json::array(), json::object()};
  for (int attempt = 0; attempt < 8; ++attempt) {
    const json& pick = choices[below(std::size(choices))];
    if (pick.type() != value.type()) return pick;
  }
  return nullptr;
}

void JsonMutator::mutate(json& document) {
  const int edits = one_in(2) ? 1 : 2 + static_cast<int>(below(3));
  for (int k = 0; k < edits; ++k) {
    std::vector<Place> places = walk(document);  // afresh: an edit moves values
    edit(places);
  }
}

void JsonMutator::edit(std::vector<Place>& places) {
  const int at = static_cast<int>(below(places.size()));
  json& value = *places[at].value;
  if (one_in(4)) return edit_any(places, at);
  if (value.is_number()) edit_number(value);
  else if (value.is_string()) edit_string(value);
  else if (value.is_object()) edit_object(value, places);
  else if (value.is_array()) edit_array(value, places);
  else edit_any(places, at);
}

void JsonMutator::edit_number(json& value) {
  switch (below(5)) {
    case 0: {  // scaled; a whole number scaled by a whole factor stays whole where it fits
      static const double factors[] = {-1.0, 0.0, 0.5, 2.0, 10.0, 0.1, 1e3, 1e-3, 1e6, 1e-6, 1e12, 1e-12};
      const double factor = factors[below(std::size(factors))];
      const double scaled = value.get<double>() * factor;
      if (value.is_number_integer() && factor == std::floor(factor) && std::fabs(scaled) < 9e18)
        value = static_cast<std::int64_t>(scaled);
      else
        value = scaled;
      return;
    }
    case 1: {  // nudged by ±1 to ±3
      const int step = static_cast<int>(below(3)) + 1;
      const int delta = one_in(2) ? step : -step;
      if (value.is_number_unsigned()) {
        const std::uint64_t u = value.get<std::uint64_t>();
        if (delta < 0 && u < static_cast<std::uint64_t>(-delta)) value = static_cast<std::int64_t>(u) + delta;
        else value = u + static_cast<std::uint64_t>(delta);  // wraps past 2⁶⁴ − 1: a limit too
      } else if (value.is_number_integer()) {
        const std::int64_t s = value.get<std::int64_t>();
        const bool overflows = delta > 0 ? s > std::numeric_limits<std::int64_t>::max() - delta
                                         : s < std::numeric_limits<std::int64_t>::min() - delta;
        if (!overflows) value = s + delta;
      } else {
        value = value.get<double>() + delta;
      }
      return;
    }
    case 2:
      value = limits()[below(limits().size())];
      return;
    case 3:  // whole ↔ fractional: 5 → 5.0 or 5.5, 2.5 → 2
      if (value.is_number_integer()) {
        value = value.get<double>() + (one_in(2) ? 0.5 : 0.0);
      } else {
        const double x = value.get<double>();
        if (std::fabs(x) < 9e18) value = static_cast<std::int64_t>(x);
      }
      return;
    default: {  // a random magnitude of either sign
      const double exponent = std::uniform_real_distribution<double>(-12.0, 12.0)(random_);
      value = (one_in(2) ? 1.0 : -1.0) * std::pow(10.0, exponent);
      return;
    }
  }
}

void JsonMutator::edit_string(json& value) {
  std::string& text = value.get_ref<std::string&>();
  if (!text.empty() && text[0] == '/' && !one_in(4)) return edit_pointer(value);
  switch (below(5)) {
    case 0: value = word(); return;
    case 1: value = ""; return;
    case 2: text.resize(below(text.size() + 1)); return;
    case 3: text += one_in(2) ? text : word(); return;
    default: {
      static const char characters[] = "/~01-_ aZ.\"\\\t";
      if (!text.empty()) text[below(text.size())] = characters[below(sizeof characters - 1)];
      return;
    }
  }
}

void JsonMutator::edit_pointer(json& value) {
  std::vector<std::string> tokens;  // the pointer's reference tokens, escaped as written
  const std::string& text = value.get_ref<const std::string&>();
  for (size_t start = 1;;) {
    const size_t slash = text.find('/', start);
    tokens.push_back(text.substr(start, slash == std::string::npos ? std::string::npos : slash - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  std::vector<size_t> indices;
  for (size_t k = 0; k < tokens.size(); ++k)
    if (is_index(tokens[k])) indices.push_back(k);
  switch (below(5)) {
    case 0:  // an index changed
      if (!indices.empty()) tokens[indices[below(indices.size())]] = index_tokens()[below(index_tokens().size())];
      else tokens.push_back(index_tokens()[below(index_tokens().size())]);
      break;
    case 1:
      if (tokens.size() > 1) tokens.pop_back();
      break;
    case 2:
      tokens.push_back(one_in(2) ? word() : index_tokens()[below(index_tokens().size())]);
      break;
    case 3:
      tokens[below(tokens.size())] = word();
      break;
    default: {
      const size_t k = below(tokens.size());
      tokens.insert(tokens.begin() + static_cast<std::ptrdiff_t>(k), tokens[k]);
      break;
    }
  }
  std::string pointer;
  for (const std::string& token : tokens) pointer += "/" + token;
  value = pointer;
}

void JsonMutator::edit_object(json& value, const std::vector<Place>& places) {
  const auto random_key = [&]() { return std::next(value.begin(), static_cast<std::ptrdiff_t>(below(value.size()))).key(); };
  const size_t choice = value.empty() ? 2 : below(4);
  switch (choice) {
    case 0:
      value.erase(random_key());
      return;
    case 1: {  // renamed (where the new name is free)
      const std::string from = random_key(), to = word();
      if (value.contains(to)) return;
      json moved = std::move(value[from]);
      value.erase(from);
      value[to] = std::move(moved);
      return;
    }
    case 2: {  // a key added, with a copy of a value from anywhere (taken before the insertion)
      json copy = *places[below(places.size())].value;
      value[word()] = std::move(copy);
      return;
    }
    default: {
      json& entry = value[random_key()];
      entry = other_type_scalar(entry);
      return;
    }
  }
}

void JsonMutator::edit_array(json& value, const std::vector<Place>& places) {
  const size_t size = value.size();
  const size_t choice = size == 0 ? 4 : below(6);
  switch (choice) {
    case 0:
      value.erase(below(size));
      return;
    case 1: {  // shortened
      json shorter = json::array();
      const size_t keep = below(size);
      for (size_t k = 0; k < keep; ++k) shorter.push_back(std::move(value[k]));
      value = std::move(shorter);
      return;
    }
    case 2: {  // an entry duplicated in place
      const size_t k = below(size);
      json copy = value[k];
      value.insert(value.begin() + static_cast<std::ptrdiff_t>(k), std::move(copy));
      return;
    }
    case 3: {
      const size_t a = below(size), b = below(size);
      if (a != b) std::swap(value[a], value[b]);
      return;
    }
    case 4: {  // appended: a copy of a value from anywhere
      json copy = *places[below(places.size())].value;
      value.push_back(std::move(copy));
      return;
    }
    default:
      value = json::array();
      return;
  }
}

void JsonMutator::edit_any(std::vector<Place>& places, int at) {
  json& value = *places[at].value;
  if (value.is_boolean() && one_in(2)) {
    value = !value.get<bool>();
    return;
  }
  if (at == 0) {  // the root keeps its type (an object, mostly)
    if (value.is_object()) edit_object(value, places);
    else if (value.is_array()) edit_array(value, places);
    else value = other_type_scalar(value);
    return;
  }
  const int other = static_cast<int>(below(places.size()));
  switch (below(3)) {
    case 0: {  // a copy of another value (a type changed, a list where a number was)
      json copy = *places[other].value;
      value = std::move(copy);
      return;
    }
    case 1:
      value = other_type_scalar(value);
      return;
    default:  // two values swapped, where neither holds the other
      if (!encloses(places, at, other) && !encloses(places, other, at)) std::swap(value, *places[other].value);
      return;
  }
}

void JsonMutator::cross_over(json& document, const json& donor) {
  json donor_copy = donor;
  const std::vector<Place> donor_places = walk(donor_copy);
  const Place& from = donor_places[below(donor_places.size())];
  json graft = *from.value;
  std::vector<Place> places = walk(document);
  const int at = static_cast<int>(below(places.size()));
  json& target = *places[at].value;
  if (target.is_object() && from.key && one_in(2)) target[*from.key] = std::move(graft);  // under its own key
  else if (target.is_array() && one_in(2)) target.insert(target.begin() + static_cast<std::ptrdiff_t>(below(target.size() + 1)), std::move(graft));
  else if (at != 0) target = std::move(graft);
  else if (target.is_object()) target[from.key ? *from.key : word()] = std::move(graft);
}

}  // namespace tsm::fuzz
