#pragma once
// A sweep's assignment: one value set at a JSON pointer (RFC 6901) into a case's model.

#include <nlohmann/json.hpp>
#include <string>

namespace tsm::study {

struct Assignment {
  std::string pointer;   ///< "/members/0/divisions"
  nlohmann::json value;
  std::string path;      ///< where the study file gives it (`sweep[2].path`), for messages
};

}  // namespace tsm::study
