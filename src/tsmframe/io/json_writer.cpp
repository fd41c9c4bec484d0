#include "tsmframe/io/json_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

namespace tsm::io {

std::string format_number(double x) {
  if (!std::isfinite(x)) return "null";
  if (x == 0.0) return "0";  // no "-0"
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

void JsonWriter::separate() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (!first_.empty()) {
    if (!first_.back()) out_ << ',';
    first_.back() = false;
  }
  if (pending_newline_) {
    out_ << '\n';
    pending_newline_ = false;
  }
}

JsonWriter& JsonWriter::begin_object() {
  separate();
  out_ << '{';
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_object() {
  out_ << '}';
  first_.pop_back();
  return *this;
}

JsonWriter& JsonWriter::begin_array() {
  separate();
  out_ << '[';
  first_.push_back(true);
  return *this;
}

JsonWriter& JsonWriter::end_array() {
  out_ << ']';
  first_.pop_back();
  return *this;
}

JsonWriter& JsonWriter::key(const std::string& name) {
  separate();
  // A key of printable ASCII without quote or backslash is its own JSON string (the common
  // case, written as is); any other goes through the JSON library's escaping.
  const bool plain = std::all_of(name.begin(), name.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u >= 0x20 && u < 0x7f && c != '"' && c != '\\';
  });
  if (plain) out_ << '"' << name << "\":";
  else out_ << nlohmann::json(name).dump() << ':';
  after_key_ = true;
  return *this;
}

JsonWriter& JsonWriter::value(double x) {
  separate();
  out_ << format_number(x);
  return *this;
}

JsonWriter& JsonWriter::value(int x) {
  separate();
  out_ << x;
  return *this;
}

JsonWriter& JsonWriter::value(const nlohmann::json& v) {
  separate();
  out_ << v.dump();
  return *this;
}

JsonWriter& JsonWriter::value(bool x) {
  separate();
  out_ << (x ? "true" : "false");
  return *this;
}

JsonWriter& JsonWriter::value(const std::string& text) {
  separate();
  out_ << nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return *this;
}

JsonWriter& JsonWriter::newline() {
  pending_newline_ = true;
  return *this;
}

}  // namespace tsm::io
