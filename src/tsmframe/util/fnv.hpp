#pragma once
// FNV-1a, the 64-bit Fowler–Noll–Vo hash: a fingerprint of values (not cryptographic: it tells
// apart what changed by accident, not what an adversary made collide).

#include <cstdint>
#include <string_view>

namespace tsm::util {

inline constexpr std::uint64_t fnv_offset = 14695981039346656037ull;
inline constexpr std::uint64_t fnv_prime = 1099511628211ull;

/// `hash` with one more word folded in.
inline std::uint64_t fnv1a(std::uint64_t hash, std::uint64_t word) { return (hash ^ word) * fnv_prime; }

/// The hash of `bytes`, byte by byte, from `hash`.
inline std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash = fnv_offset) {
  for (const unsigned char c : bytes) hash = fnv1a(hash, c);
  return hash;
}

}  // namespace tsm::util
