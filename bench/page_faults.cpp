// What a page of fresh memory costs on first write (issue 5: the set-up's share of a run), three
// ways: touched by one thread, by all threads side by side, or mapped in by the kernel in one call
// per range (util::touch_pages: MADV_POPULATE_WRITE, shared over the threads). 64 MiB each, a
// fresh mapping every time. Usage: tsmframe_page_faults
#include <sys/mman.h>

#include <chrono>
#include <cstdio>

#include "tsmframe/util/first_touch.hpp"

namespace {

constexpr std::size_t bytes = std::size_t{64} << 20, page = 4096;

template <class Fill>
void measure(const char* how, Fill&& fill) {
  auto* p = static_cast<unsigned char*>(mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0));
  if (p == MAP_FAILED) return;
  const auto t0 = std::chrono::steady_clock::now();
  fill(p);
  for (std::size_t k = 0; k < bytes; k += page) p[k] = 1;  // the writer's own pass
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%-40s %7.1f ms  %5.2f us per page\n", how, 1e3 * s, 1e6 * s / (bytes / page));
  munmap(p, bytes);
}

}  // namespace

int main() {
  for (int round = 0; round < 2; ++round) {
    measure("first write, one thread", [](unsigned char*) {});
    measure("first write, all threads", [](unsigned char* p) {
#pragma omp parallel for schedule(static)
      for (long k = 0; k < static_cast<long>(bytes / page); ++k) p[k * page] = 0;
    });
    measure("mapped in first (util::touch_pages)", [](unsigned char* p) { tsm::util::touch_pages(p, bytes); });
  }
}
