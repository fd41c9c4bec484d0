#include "tsmframe/io/machine_memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace tsm::io {
namespace {

/// A small file's text ("" where it cannot be read).
std::string small_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A number of bytes in a control group's file; −1 where absent or unlimited ("max").
double group_value(const std::string& path) {
  const std::string text = small_file(path);
  if (text.empty() || text.rfind("max", 0) == 0) return -1.0;
  return std::strtod(text.c_str(), nullptr);
}

/// The memory the process's control group leaves it (its limit less its use); −1 without a limit.
double control_group_left() {
  const ControlGroup group = memory_control_group(small_file("/proc/self/cgroup"));
  if (group.path.empty()) return -1.0;
  std::string base = group.v2 ? "/sys/fs/cgroup" : "/sys/fs/cgroup/memory";
  if (group.path != "/") base.append(group.path);
  const double limit = group_value(base + (group.v2 ? "/memory.max" : "/memory.limit_in_bytes"));
  if (limit < 0.0 || limit >= 1e18) return -1.0;  // v1 writes "no limit" as a number near 2⁶³
  const double used = group_value(base + (group.v2 ? "/memory.current" : "/memory.usage_in_bytes"));
  return std::max(0.0, limit - std::max(0.0, used));
}

/// What the address-space limit leaves the process (the limit less what it has mapped); −1 without one.
double address_space_left() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return -1.0;
  const double mapped = kilobyte_field(small_file("/proc/self/status"), "VmSize");
  return std::max(0.0, static_cast<double>(limit.rlim_cur) - std::max(0.0, mapped));
}

}  // namespace

double kilobyte_field(const std::string& text, const std::string& key) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(key + ":", 0) != 0) continue;
    return 1024.0 * std::strtod(line.c_str() + key.size() + 1, nullptr);
  }
  return -1.0;
}

ControlGroup memory_control_group(const std::string& text) {
  std::istringstream lines(text);
  ControlGroup v2;
  for (std::string line; std::getline(lines, line);) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    std::string controllers(1, ',');  // ",memory," matches a whole name in the list
    controllers.append(line, first + 1, second - first - 1).push_back(',');
    const std::string path = line.substr(second + 1);
    if (controllers.find(",memory,") != std::string::npos) return {path, false};
    if (line.rfind("0::", 0) == 0) v2 = {path, true};
  }
  return v2;
}

MachineMemory machine_memory() {
  MachineMemory m;
  m.bytes = kilobyte_field(small_file("/proc/meminfo"), "MemAvailable");
  m.source = "available (MemAvailable)";
  if (m.bytes < 0.0) {  // no /proc: the free pages (the page cache left out, so less than MemAvailable)
    m.bytes = static_cast<double>(sysconf(_SC_AVPHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
    m.source = "free";
  }
  if (const double left = address_space_left(); left >= 0.0 && left < m.bytes)
    m = {left, "left by the address-space limit (ulimit -v)"};
  if (const double left = control_group_left(); left >= 0.0 && left < m.bytes)
    m = {left, "left by the control group's memory limit"};
  return m;
}

}  // namespace tsm::io
