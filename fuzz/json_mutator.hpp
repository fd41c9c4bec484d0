#pragma once
// Structural mutations of a JSON document: the edits that keep a model or study file parseable
// and mostly well-typed, so that a mutated input gets past the reader to the solver or the case
// expansion, where byte flips would mostly end at the parser. One mutation is one to four edits,
// each at a value drawn from the whole tree:
//   - numbers scaled (×−1, ×0, ×0.5, ×2, ×10, ×1e6, ×1e-6, …), nudged by ±1–3, set to a limit
//     (0, ±1, 2³¹, 2⁵³, 2⁶³−1, 2⁶⁴−1, 1e50, 1e308, …) or turned from whole to fractional;
//   - strings replaced by a word of the format or of the document (keys, enumerations), emptied
//     or cut; a JSON pointer ("/members/0/divisions") gets an index changed (to 0, one past the
//     end, 4000000000, 2⁶⁴, "-"), a token dropped or one added;
//   - object keys dropped, renamed to another word, or added with a value copied from elsewhere;
//   - arrays shortened, emptied, an entry duplicated, two entries swapped, one appended;
//   - any value replaced by a copy of another (a type changed), by a scalar of another type, or
//     swapped with another value that is neither inside it nor around it; booleans flipped.
// Grafting (cross-over) puts a copy of a value of one document at a random place of another.
// The edits never recurse: a deeply nested document costs a walk, not stack.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

namespace tsm::fuzz {

class JsonMutator {
 public:
  /// `words`: keys and string values of the input format (added to those of each document).
  JsonMutator(std::uint32_t seed, std::vector<std::string> words);

  /// Applies one to four structural edits to `document`.
  void mutate(nlohmann::json& document);

  /// Puts a copy of a random value of `donor` into `document`: in place of one of its values,
  /// or as a new array entry or object key.
  void cross_over(nlohmann::json& document, const nlohmann::json& donor);

 private:
  struct Place {
    nlohmann::json* value;
    int parent;               ///< index of the enclosing value in the walk, −1 for the root
    const std::string* key;   ///< its key in the enclosing object (null in an array, at the root)
  };

  /// Every value of the tree, parents before children; collects the document's words too.
  std::vector<Place> walk(nlohmann::json& document);
  bool encloses(const std::vector<Place>& places, int outer, int inner) const;

  void edit(std::vector<Place>& places);
  void edit_number(nlohmann::json& value);
  void edit_string(nlohmann::json& value);
  void edit_pointer(nlohmann::json& value);
  void edit_object(nlohmann::json& value, const std::vector<Place>& places);
  void edit_array(nlohmann::json& value, const std::vector<Place>& places);
  void edit_any(std::vector<Place>& places, int at);

  const std::string& word();
  nlohmann::json other_type_scalar(const nlohmann::json& value);
  size_t below(size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<size_t>(0, n - 1)(random_); }
  bool one_in(unsigned n) { return below(n) == 0; }

  std::mt19937 random_;
  std::vector<std::string> format_words_;
  std::vector<std::string> words_;  ///< format_words_ and the current document's keys and strings
};

}  // namespace tsm::fuzz
