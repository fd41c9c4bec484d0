#pragma once
// The memory a run may take, and the refusal of a model whose estimate (model/memory_estimate)
// exceeds it, before the memory is spent: one line with the estimate, what it is made of and what
// the machine has — a MemoryShortage, a SystemError (exit 3: it would run on a bigger machine), unlike the caps
// the readers hold every model to (InputError, exit 2).

#include <string>
#include <vector>

#include "tsmframe/model/memory_estimate.hpp"

namespace tsm::io {

struct MemoryBudget {
  double bytes = 0.0;
  /// What it is, for the refusal's "more than …": "the 18.2 GB this machine has available (MemAvailable)".
  std::string description;
};

/// The machine's memory now (machine_memory), shared by `share` runs at once (a study's jobs).
MemoryBudget memory_budget(int share = 1);

/// Refuses an estimate beyond the budget: throws MemoryShortage(path, "the run needs ~… of memory (…),
/// more than …"), the parts largest first; `path` names where in the input most of it goes, `subject`
/// what needs it.
void check_memory(std::vector<MemoryPart> parts, const MemoryBudget& budget, const std::string& path,
                  const std::string& subject = "the run");
inline void check_memory(const MemoryEstimate& estimate, const MemoryBudget& budget, const std::string& path) {
  check_memory(estimate.parts(), budget, path);
}

/// Bytes as text: "512 B", "57 MB", "20.4 GB".
std::string bytes_text(double bytes);

}  // namespace tsm::io
