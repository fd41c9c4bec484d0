#pragma once
// A contact's reference sides (sides.hpp), one per candidate element, two bits each (+1, −1, 0
// or no_side), shared by the copies of a state — the step's start kept for a cutback, the state
// Newton moves — until they change: a reference is taken anew for every inactive contact at each
// converged step, and most come out as they were. At 10⁴ contact nodes on 3·10⁴ candidates a
// byte per candidate in each copy was 600 MB.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace tsm::contact {

/// A reference side of a candidate element that is not known: the node was beyond the
/// element's reach at the last converged state (sides.hpp).
inline constexpr signed char no_side = 2;

class SideTable {
 public:
  size_t size() const { return packed_ ? packed_->size : 0; }
  signed char operator[](size_t candidate) const {
    const unsigned code = (packed_->bytes[candidate / 4] >> (2 * (candidate % 4))) & 3u;
    return code == 3u ? no_side : static_cast<signed char>(static_cast<int>(code) - 1);
  }
  /// Every side, one per candidate, into `all` (empty: none taken yet).
  void read(std::vector<signed char>& all) const {
    all.resize(size());
    for (size_t k = 0; k < all.size(); ++k) all[k] = (*this)[k];
  }
  std::vector<signed char> values() const {
    std::vector<signed char> all;
    read(all);
    return all;
  }
  /// Takes `values` (each +1, −1, 0 or no_side); where they equal the ones held, those stay (and
  /// stay shared).
  void set(const std::vector<signed char>& values) {
    thread_local std::vector<std::uint8_t> bytes;
    bytes.assign((values.size() + 3) / 4, 0);
    for (size_t k = 0; k < values.size(); ++k) {
      const unsigned code = values[k] == no_side ? 3u : static_cast<unsigned>(values[k] + 1);
      bytes[k / 4] = static_cast<std::uint8_t>(bytes[k / 4] | (code << (2 * (k % 4))));
    }
    if (packed_ && packed_->size == values.size() && packed_->bytes == bytes) return;
    if (packed_ && packed_.use_count() == 1) {  // held by this state alone
      packed_->size = values.size();
      packed_->bytes = bytes;
    } else {
      packed_ = std::make_shared<Packed>(Packed{values.size(), bytes});
    }
  }

 private:
  struct Packed {
    size_t size = 0;
    std::vector<std::uint8_t> bytes;  ///< four sides a byte, the first in the lowest bits
  };
  std::shared_ptr<Packed> packed_;
};

}  // namespace tsm::contact
