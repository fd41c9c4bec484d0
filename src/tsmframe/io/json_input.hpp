#pragma once
// Typed reads of JSON input — model files and study files alike — each failing with an
// InputError that names the JSON path of the offending value in one syntax: `members[2].section`,
// `sweep[0].variants[1].set["/supports"]` (a key that is no plain identifier is quoted in
// brackets); the document's own keys stand alone (`nodes`).

#include <Eigen/Core>
#include <functional>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::io {

/// The largest |x| of any number in a model: no unit system needs more, and products of a few
/// such numbers (EA · l, a load times a displacement) would overflow mid-analysis.
inline constexpr double largest_number = 1e50;

/// `parent.key`, or `parent["odd key"]` when the key is not a plain identifier.
std::string child(const std::string& parent, const std::string& key);
/// `parent[index]`.
std::string child(const std::string& parent, size_t index);

/// `text` as a JSON string, quotes and escapes included.
std::string quote_text(const std::string& text);
/// "a number", "a string", "true/false", "a list", "an object" or "null".
const char* type_name(const nlohmann::json& value);

[[noreturn]] void fail(const std::string& path, const std::string& reason);

/// Parses JSON text; a syntax error names its line and column (of the offending character).
nlohmann::json parse_json(const std::string& text);

void expect_object(const nlohmann::json& value, const std::string& path);
void expect_array(const nlohmann::json& value, const std::string& path);
/// Every key must be one of `allowed`, or "extra" (ignored, anywhere).
void check_keys(const nlohmann::json& object, const std::string& path, std::initializer_list<const char*> allowed);

/// Calls each(entry, path) for every entry of the array `document[key]` (none without the key),
/// each an object with only `allowed` keys (a model file's "supports", "springs", …).
void for_each_entry(const nlohmann::json& document, const char* key, std::initializer_list<const char*> allowed,
                    const std::function<void(const nlohmann::json& entry, const std::string& path)>& each);

/// A finite number within ±largest_number.
double number(const nlohmann::json& value, const std::string& path);
/// The number under `key`, if the object has the key.
std::optional<double> optional_number(const nlohmann::json& object, const char* key, const std::string& path);
/// The number under `key`; "missing (required)" at `path.key` without it.
double required_number(const nlohmann::json& object, const char* key, const std::string& path);
/// `value` itself, if it is > 0.
double positive(double value, const std::string& path);

/// A whole number (5, or 5.0 written as a float below 9e15), within the range of `long`.
long integer(const nlohmann::json& value, const std::string& path);
/// A whole number within [lo, hi].
long bounded_integer(const nlohmann::json& value, const std::string& path, long lo, long hi);

std::string string(const nlohmann::json& value, const std::string& path);
bool boolean(const nlohmann::json& value, const std::string& path);
/// `[x, y]`.
Eigen::Vector2d point(const nlohmann::json& value, const std::string& path);

/// ux, uy or rz (Dof) from its name.
int dof_from_name(const std::string& name, const std::string& path);

/// A node as the input names it: by id (`3`) or by coordinates (`[4.5, 0.0]`), not yet looked up.
struct NodeReference {
  std::optional<long> id;  ///< by id
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< by coordinates, when there is no id
};
/// Reads a node reference's form: an id or [x, y].
NodeReference node_reference(const nlohmann::json& value, const std::string& path);
/// The index of the node a reference names in `model`: by id through `index_of_id` (−1: none),
/// or the one node at the coordinates (node_at: within 1e-9 of the model's size).
int resolve_node(const NodeReference& reference, const std::string& path, const Model& model,
                 const std::function<int(long id)>& index_of_id);

}  // namespace tsm::io
