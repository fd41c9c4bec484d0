#pragma once

namespace tsm {
inline constexpr const char* version = "0.1.0";
}  // namespace tsm
