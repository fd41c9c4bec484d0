#pragma once
// Reads a model file (docs/format.md, "tsmframe-model/1") strictly: unknown keys, wrong types and
// inconsistent data are InputErrors carrying the JSON path (`members[2].section`). Each member's
// keys become a MemberInput that model/mesh.hpp divides into elements — counted first, against the
// element cap and the memory budget; the whole run's memory estimate is held to the budget before
// the model is returned (io/memory_budget.hpp: a SystemError), and the model is checked for mechanisms.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "tsmframe/io/memory_budget.hpp"
#include "tsmframe/model/model.hpp"

namespace tsm::io {

/// Whether a model that is a mechanism where the analysis starts is refused (InputError at
/// "supports") — a run's reading — or read as drawn, for `tsmframe plot` to show it and name
/// the free motion (model::starting_mechanism).
enum class Mechanisms { refuse, allow };

/// Builds a model from parsed JSON whose run fits `budget`; `input_bytes`: the text it was parsed
/// from, if that is held while it is read. Throws InputError, and SystemError (at the JSON path
/// where most of the memory goes) for a model whose run would not fit.
Model read_model(const nlohmann::json& document, const MemoryBudget& budget, double input_bytes = 0.0,
                 Mechanisms mechanisms = Mechanisms::refuse);
/// The same within the machine's memory now (memory_budget()).
Model read_model(const nlohmann::json& document);

/// Parses `text` (errors name line and column) and builds the model. Throws InputError, SystemError.
Model read_model_text(const std::string& text, Mechanisms mechanisms = Mechanisms::refuse);

/// Reads the file at `path` (io/input_file.hpp: at most 1 GiB, no directory, no NUL byte), its
/// text and parsed document held to the memory budget before it is parsed. Throws InputError (a
/// missing file too), and SystemError prefixed with the path.
Model read_model_file(const std::string& path, Mechanisms mechanisms = Mechanisms::refuse);

}  // namespace tsm::io
