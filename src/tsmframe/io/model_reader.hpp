#pragma once
// Reads a model file (FORMAT.md, "tsmframe-model/1") strictly: unknown keys, wrong types and
// inconsistent data are InputErrors carrying the JSON path (`members[2].section`). Each member's
// keys become a MemberInput that model/mesh.hpp divides into elements; the model is checked for
// mechanisms before it is returned.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "tsmframe/model/model.hpp"

namespace tsm::io {

/// Builds a model from parsed JSON. Throws InputError.
Model read_model(const nlohmann::json& document);

/// Parses `text` (errors name line and column) and builds the model. Throws InputError.
Model read_model_text(const std::string& text);

/// Reads the file at `path` (io/input_file.hpp: at most 1 GiB, no directory, no NUL byte). Throws
/// InputError (a missing file too).
Model read_model_file(const std::string& path);

}  // namespace tsm::io
