#pragma once
// A frictional contact's status as results.json names it (and a restart reads it back).

#include <array>
#include <string_view>

#include "tsmframe/contact/friction.hpp"

namespace tsm::io {

/// In FrictionStatus's order.
inline constexpr std::array<std::string_view, 4> friction_names = {"none", "open", "stick", "slip"};

inline std::string_view friction_name(contact::FrictionStatus status) {
  return friction_names[static_cast<size_t>(status)];
}

}  // namespace tsm::io
