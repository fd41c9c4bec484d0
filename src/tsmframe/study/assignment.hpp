#pragma once
// A sweep's assignment: one value set at a JSON pointer (RFC 6901) into a case's model.
//
// Through an object a pointer may name a key the model has or a new one — at any depth: an
// optional object the base model leaves out ("analysis", a member's "load") is made, holding the
// key (a misspelt key is then the model reader's to refuse, in each case); below a new key a
// list is made only with its first entry (`/extra/a/0` or `/extra/a/-`, not `/extra/a/7`: a
// list of 7 nulls and the value, or of 4·10⁹ for `/extra/a/4000000000`). Through a list it
// must name an entry the list has, or, as its last token, the place one past the end
// (`/loads/1` on a model with one load, or `/loads/-`: appends one entry, as a variant adding a
// load does). Anything else is refused: assigning there would build what it names —
// `/nodes/4000000000` a list of 4·10⁹ nulls, 3.4 GB for `/nodes/100000000` — where entries
// further past the end would only be nulls the model reader refuses; and a number or a string
// has nothing to name inside it.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace tsm::study {

struct Assignment {
  std::string pointer;   ///< "/members/0/divisions"
  nlohmann::json value;
  std::string path;      ///< where the study file gives it (`sweep[2].path`), for messages
};

/// Why `pointer` (a valid JSON pointer) names no place of `model` an assignment may set, or
/// nothing when it does.
std::optional<std::string> unassignable(const nlohmann::json& model, const std::string& pointer);

/// Sets the value in `model`; throws io::InputError at the assignment's path where the pointer
/// names no such place.
void assign(nlohmann::json& model, const Assignment& assignment);

/// Refuses (io::InputError at the first path that gives it) every pointer the base model has no
/// place for, where no other assignment of the sweep can make one: one that sets the pointer's
/// parent or an ancestor, or a sibling (which may grow the same list). The others are checked
/// in each case, against the case's model so far.
void check_assignments(const nlohmann::json& model, const std::vector<const Assignment*>& assignments);

}  // namespace tsm::study
