#pragma once
// A small streaming JSON writer: large results are written without building a document tree
// in memory. Numbers use the shortest text that reads back to the same double; a non-finite
// number (never part of a converged state) is written as null.

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace tsm::io {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}

  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(const std::string& name);
  JsonWriter& value(double x);
  JsonWriter& value(int x);
  JsonWriter& value(bool x);
  JsonWriter& value(const std::string& text);
  JsonWriter& value(const char* text) { return value(std::string(text)); }
  /// A value as it was read (a study parameter's: a number, a string, an array …).
  JsonWriter& value(const nlohmann::json& v);
  /// A line break before the next item, to keep large files readable.
  JsonWriter& newline();

 private:
  void separate();
  std::ostream& out_;
  std::vector<bool> first_;  // per open container: no item written yet
  bool after_key_ = false;
  bool pending_newline_ = false;
};

/// Shortest round-trip text of a double ("0.1", "1e-13", "2").
std::string format_number(double x);

}  // namespace tsm::io
