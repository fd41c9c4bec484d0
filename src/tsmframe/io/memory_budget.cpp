#include "tsmframe/io/memory_budget.hpp"

#include <algorithm>
#include <cstdio>

#include "tsmframe/io/machine_memory.hpp"
#include "tsmframe/io/system_error.hpp"

namespace tsm::io {

std::string bytes_text(double bytes) {
  char text[32];
  if (bytes < 1e3) std::snprintf(text, sizeof text, "%.0f B", bytes);
  else if (bytes < 1e6) std::snprintf(text, sizeof text, "%.0f kB", bytes / 1e3);
  else if (bytes < 1e9) std::snprintf(text, sizeof text, "%.0f MB", bytes / 1e6);
  else std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  return text;
}

MemoryBudget memory_budget(int share) {
  const MachineMemory machine = machine_memory();
  const std::string whole = bytes_text(machine.bytes) + " " + machine.source;
  if (share <= 1) return {machine.bytes, "the machine's " + whole};
  return {machine.bytes / share,
          bytes_text(machine.bytes / share) + ", a share of the machine's " + whole + " among " + std::to_string(share) + " study jobs"};
}

void check_memory(std::vector<MemoryPart> parts, const MemoryBudget& budget, const std::string& path, const std::string& subject) {
  double total = 0.0;
  for (const MemoryPart& part : parts) total += part.bytes;
  if (total <= budget.bytes) return;
  std::stable_sort(parts.begin(), parts.end(), [](const MemoryPart& a, const MemoryPart& b) { return a.bytes > b.bytes; });
  std::string list;
  for (const MemoryPart& part : parts)
    if (part.bytes > 0.0) list += (list.empty() ? "" : ", ") + part.name + " " + bytes_text(part.bytes);
  throw MemoryShortage(path, subject + " needs ~" + bytes_text(total) + " of memory (" + list + "), more than " + budget.description);
}

}  // namespace tsm::io
