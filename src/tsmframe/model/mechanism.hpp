#pragma once
// Kinematic check of a model before any solve. Beam elements are rigid-jointed and carry
// axial force and bending, so the only mechanisms are rigid-body motions of connected parts
// that the supports do not stop: a node that no element holds, or a part whose fixed dofs
// leave a translation or a rotation free.

#include <optional>
#include <string>

#include "tsmframe/model/model.hpp"

namespace tsm {

/// A sentence naming the free motion and a node on it, or nothing if the model is stable. Held
/// contacts resting on a part as drawn (model/resting_contact) count as supports along their
/// normal unless `resting_contacts_hold` is false.
std::optional<std::string> find_mechanism(const Model& model, bool resting_contacts_hold = true);

}  // namespace tsm
