#pragma once
// The memory this process may still take (README, "Memory"): the kernel's MemAvailable — what it
// can hand out now without swapping, the memory other processes hold left out (physical memory
// would admit a run on a busy shared machine that the out-of-memory killer then ends, nothing
// written) — or less where the process is limited: by its address-space limit (ulimit -v,
// prlimit --as) less what it has mapped, or by its control group's memory limit less the group's use.

#include <string>

namespace tsm::io {

struct MachineMemory {
  double bytes = 0.0;
  /// Which limit it is, for messages: "available (MemAvailable)", …
  std::string source;
};

/// The memory this process may take now.
MachineMemory machine_memory();

/// A field of /proc/meminfo or /proc/self/status given in kB ("MemAvailable:  22890604 kB"), in
/// bytes; −1 where `text` has no such field.
double kilobyte_field(const std::string& text, const std::string& key);

/// The memory control group's path of this process from /proc/self/cgroup's `text`, and whether it
/// is cgroup v2's (a line "0::/path") rather than v1's memory controller ("4:memory:/path"); an
/// empty path where neither is there.
struct ControlGroup {
  std::string path;
  bool v2 = false;
};
ControlGroup memory_control_group(const std::string& text);

}  // namespace tsm::io
