#include "tsmframe/util/first_touch.hpp"

#include "tsmframe/util/parallel_for.hpp"

#if defined(__unix__) || defined(__APPLE__)
#include <sys/mman.h>
#endif

#include <algorithm>
#include <cstdint>

namespace tsm::util {

void touch_pages(void* data, std::size_t bytes) {
  constexpr std::size_t page = 4096;
  constexpr std::size_t pages_per_part = 256;  // 1 MiB: smaller ranges are not worth a thread
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + page - 1) / page * page;
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) / page * page;
  if (end <= begin) return;  // no whole page: left to the writer
  const std::size_t pages = (end - begin) / page;
  const long parts = static_cast<long>(std::max<std::size_t>(1, pages / pages_per_part));
  parallel_for_static(0L, parts, parts > 1, [&](long p) {
    const std::size_t first = pages * static_cast<std::size_t>(p) / static_cast<std::size_t>(parts);
    const std::size_t last = pages * static_cast<std::size_t>(p + 1) / static_cast<std::size_t>(parts);
    auto* start = reinterpret_cast<unsigned char*>(begin + first * page);
#ifdef MADV_POPULATE_WRITE
    if (madvise(start, (last - first) * page, MADV_POPULATE_WRITE) == 0) return;
#endif
    for (std::size_t k = 0; k < last - first; ++k) static_cast<volatile unsigned char*>(start)[k * page] = 0;
  });
}

}  // namespace tsm::util
