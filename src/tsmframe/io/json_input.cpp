#include "tsmframe/io/json_input.hpp"

#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

#include "tsmframe/io/json_writer.hpp"
#include "tsmframe/model/node_lookup.hpp"

namespace tsm::io {

using nlohmann::json;

std::string child(const std::string& parent, const std::string& key) {
  bool plain = !key.empty() && !std::isdigit(static_cast<unsigned char>(key[0]));
  for (char c : key) plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-');
  if (!plain) return parent + "[" + quote_text(key) + "]";
  return parent.empty() ? key : parent + "." + key;
}

std::string child(const std::string& parent, size_t index) { return parent + "[" + std::to_string(index) + "]"; }

std::string quote_text(const std::string& text) { return json(text).dump(); }

const char* type_name(const json& value) {
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_boolean()) return "true/false";
  if (value.is_array()) return "a list";
  if (value.is_object()) return "an object";
  return "null";
}

void fail(const std::string& path, const std::string& reason) { throw InputError(path, reason); }

namespace {

/// Line and column (1-based) of a byte offset.
std::pair<size_t, size_t> line_column(const std::string& text, size_t offset) {
  size_t line = 1, column = 1;
  for (size_t k = 0; k < std::min(offset, text.size()); ++k) {
    if (text[k] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

}  // namespace

json parse_json(const std::string& text) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    // nlohmann's byte is one past the offending character; report the character itself.
    const auto [line, column] = line_column(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string reason = e.what();
    const auto colon = reason.find("syntax error");
    if (colon != std::string::npos) reason = reason.substr(colon);
    fail("", "invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + reason);
  } catch (const json::exception& e) {  // a number beyond a double's range (out_of_range 406)
    std::string reason = e.what();
    const auto bracket = reason.find("] ");
    if (bracket != std::string::npos) reason = reason.substr(bracket + 2);
    fail("", "invalid JSON: " + reason + " (beyond a double's range)");
  }
}

void expect_object(const json& value, const std::string& path) {
  if (!value.is_object()) fail(path, std::string("expected an object, found ") + type_name(value));
}

void expect_array(const json& value, const std::string& path) {
  if (!value.is_array()) fail(path, std::string("expected a list, found ") + type_name(value));
}

void check_keys(const json& object, const std::string& path, std::initializer_list<const char*> allowed) {
  for (const auto& item : object.items()) {
    if (item.key() == "extra") continue;
    bool known = false;
    for (const char* name : allowed) known = known || item.key() == name;
    if (known) continue;
    std::string list;
    for (const char* name : allowed) list += (list.empty() ? "" : ", ") + std::string(name);
    fail(child(path, item.key()), "unknown key " + quote_text(item.key()) + " (expected one of: " + list + ")");
  }
}

void for_each_entry(const json& document, const char* key, std::initializer_list<const char*> allowed,
                    const std::function<void(const json& entry, const std::string& path)>& each) {
  if (!document.contains(key)) return;
  const json& entries = document[key];
  expect_array(entries, key);
  for (size_t k = 0; k < entries.size(); ++k) {
    const std::string path = child(key, k);
    expect_object(entries[k], path);
    check_keys(entries[k], path, allowed);
    each(entries[k], path);
  }
}

double number(const json& value, const std::string& path) {
  if (!value.is_number()) fail(path, std::string("expected a number, found ") + type_name(value));
  const double x = value.get<double>();
  if (!std::isfinite(x)) fail(path, "the number is not finite");
  if (std::abs(x) > largest_number)
    fail(path, "beyond ±1e50 (" + format_number(x) + "): no unit system needs it, and products of such numbers overflow");
  return x;
}

std::optional<double> optional_number(const json& object, const char* key, const std::string& path) {
  if (!object.contains(key)) return std::nullopt;
  return number(object.at(key), child(path, key));
}

double required_number(const json& object, const char* key, const std::string& path) {
  if (!object.contains(key)) fail(child(path, key), "missing (required)");
  return number(object.at(key), child(path, key));
}

double positive(double value, const std::string& path) {
  if (!(value > 0.0)) {
    std::ostringstream os;
    os << "must be positive, got " << value;
    fail(path, os.str());
  }
  return value;
}

long integer(const json& value, const std::string& path) {
  // An unsigned number past the largest long (2⁶³ and up) would wrap to a negative one.
  if (value.is_number_unsigned() && value.get<unsigned long>() > static_cast<unsigned long>(std::numeric_limits<long>::max()))
    fail(path, "expected a whole number within ±" + std::to_string(std::numeric_limits<long>::max()) + ", found " + value.dump());
  if (value.is_number_integer()) return value.get<long>();
  if (value.is_number_float()) {
    const double x = value.get<double>();
    if (std::floor(x) == x && std::abs(x) < 9e15) return static_cast<long>(x);
  }
  fail(path, std::string("expected a whole number, found ") + (value.is_number() ? value.dump() : type_name(value)));
}

long bounded_integer(const json& value, const std::string& path, long lo, long hi) {
  const auto out_of_bounds = [&](const std::string& found) {
    fail(path, "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", got " + found);
  };
  if (value.is_number_unsigned() && value.get<unsigned long>() > static_cast<unsigned long>(std::numeric_limits<long>::max()))
    out_of_bounds(value.dump());
  const long n = integer(value, path);
  if (n < lo || n > hi) out_of_bounds(std::to_string(n));
  return n;
}

std::string string(const json& value, const std::string& path) {
  if (!value.is_string()) fail(path, std::string("expected a string, found ") + type_name(value));
  return value.get<std::string>();
}

bool boolean(const json& value, const std::string& path) {
  if (!value.is_boolean()) fail(path, std::string("expected true or false, found ") + type_name(value));
  return value.get<bool>();
}

Eigen::Vector2d point(const json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 2) fail(path, "expected a point [x, y]");
  return {number(value[0], child(path, 0)), number(value[1], child(path, 1))};
}

int dof_from_name(const std::string& name, const std::string& path) {
  if (name == "ux") return ux;
  if (name == "uy") return uy;
  if (name == "rz") return rz;
  fail(path, "unknown dof " + quote_text(name) + " (expected ux, uy or rz)");
}

NodeReference node_reference(const json& value, const std::string& path) {
  NodeReference reference;
  if (value.is_array()) {
    reference.point = point(value, path);
    return reference;
  }
  if (!value.is_number()) fail(path, std::string("expected a node id or [x, y], found ") + type_name(value));
  reference.id = integer(value, path);
  return reference;
}

int resolve_node(const NodeReference& reference, const std::string& path, const Model& model,
                 const std::function<int(long id)>& index_of_id) {
  if (!reference.id) {
    std::string problem;
    const int found = node_at(model, reference.point, problem);
    if (found < 0) fail(path, problem);
    return found;
  }
  const int index = index_of_id(*reference.id);
  if (index < 0) fail(path, "unknown node " + std::to_string(*reference.id));
  return index;
}

}  // namespace tsm::io
